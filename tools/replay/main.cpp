// visnav-replay: the flight pipeline over a sequence directory, as fast as possible. See README.md.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/replay_tool/replay_runner.hpp"

namespace {

void usage(std::FILE* stream) {
  std::fputs(
      "usage: visnav-replay --sequence DIR --out replay.csv [--config FILE] [--camera FILE] [--model FILE]\n"
      "                     [--initial-pose x,y,z,yaw_deg,pitch_deg,roll_deg | --init-from-truth]\n"
      "                     [--overlay-dir DIR]\n"
      "                     [--overlay-every N] [--max-frames N] [--residual vertex|point_to_line]\n"
      "                     [--no-timing] [--no-progress]\n"
      "       visnav-replay --help | --version\n"
      "Runs the flight pipeline over a recorded sequence as fast as possible; one CSV row per frame\n"
      "(tools/replay/README.md). Exit code: 0 done, 2 usage, 3 an input that does not load or an output\n"
      "that cannot be written.\n",
      stream);
}

}  // namespace

int main(int argc, char** argv) {
  visnav::replay_tool::ReplayOptions options;
  options.progress = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    auto value = [&]() { return std::string(argv[++i]); };
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-replay", usage); code >= 0) return code;
    if (arg == "--sequence" && has_value) {
      options.sequence_dir = value();
    } else if (arg == "--out" && has_value) {
      options.output_csv = value();
    } else if (arg == "--config" && has_value) {
      options.config_path = value();
    } else if (arg == "--camera" && has_value) {
      options.camera_path = value();
    } else if (arg == "--model" && has_value) {
      options.model_path = value();
    } else if (arg == "--overlay-dir" && has_value) {
      options.overlay_dir = value();
    } else if ((arg == "--overlay-every" || arg == "--max-frames") && has_value) {
      // Whole-argument positive integer: "10x", "0" and "-3" are errors, not silently 0 or negative.
      long long n = 0;
      if (!visnav::cli::parseInteger(argv[++i], 1, 1000000000, n)) {
        std::fprintf(stderr, "visnav-replay: %s wants a positive integer, got '%s'\n", arg.c_str(), argv[i]);
        return 2;
      }
      (arg == "--overlay-every" ? options.overlay_every : options.max_frames) = static_cast<int>(n);
    } else if (arg == "--initial-pose" && has_value) {
      if (!visnav::replay_tool::parsePoseArgument(value(), options.initial_pose)) {
        std::fputs("visnav-replay: --initial-pose wants x,y,z,yaw_deg,pitch_deg,roll_deg\n", stderr);
        return 2;
      }
      options.start = visnav::replay_tool::ReplayOptions::Start::kInitialPose;
    } else if (arg == "--init-from-truth") {
      options.start = visnav::replay_tool::ReplayOptions::Start::kFirstTruth;
    } else if (arg == "--residual" && has_value) {
      const std::string r = value();
      if (r != "vertex" && r != "point_to_line") {
        std::fputs("visnav-replay: --residual must be vertex or point_to_line\n", stderr);
        return 2;
      }
      options.override_residual = true;
      options.residual =
          r == "vertex" ? visnav::PoseResidualMode::kVertex : visnav::PoseResidualMode::kPointToLine;
    } else if (arg == "--no-timing") {
      options.timing = false;
    } else if (arg == "--no-progress") {
      options.progress = false;
    } else {
      std::fprintf(stderr, "visnav-replay: unknown or incomplete argument '%s'\n", arg.c_str());
      usage(stderr);
      return 2;
    }
  }
  if (options.sequence_dir.empty() || options.output_csv.empty()) {
    usage(stderr);
    return 2;
  }
  visnav::replay_tool::ReplaySummary summary;
  const visnav::LoadError error = visnav::replay_tool::runReplay(options, summary);
  if (!error.ok) {
    std::fprintf(stderr, "visnav-replay: %s\n", error.message.c_str());
    return visnav::cli::kExitInvalidInput;
  }
  std::printf(
      "visnav-replay: %d frames: valid poses delivered %d; far range %d, acquisition %d, near range "
      "(tracker verdicts): tracking %d, degraded %d, lost %d; %d mode transitions; step time median %.1f "
      "us, p95 %.1f us\n",
      summary.frames, summary.valid_poses, summary.far_range, summary.acquisition, summary.tracking,
      summary.degraded, summary.lost, summary.transitions, summary.median_total_us, summary.p95_total_us);
  return 0;
}
