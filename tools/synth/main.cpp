// visnav-synth: renders a synthetic image sequence (drivers/replay/README.md format) from a scenario file.
// Usage and scenario keys: tools/synth/README.md.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "scenario.hpp"
#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/replay/sequence.hpp"

namespace {

void usage(std::FILE* stream) {
  std::fprintf(stream,
               "usage: visnav-synth --scenario FILE.toml --out DIR [--frames N] [--stride K] [--seed S] "
               "[--dry-run]\n"
               "       visnav-synth --help | --version\n"
               "Renders a synthetic image sequence with truth from a scenario file (tools/synth/README.md).\n"
               "  --frames N  render at most N frames     --stride K  every K-th trajectory frame\n"
               "  --seed S    noise seed (overrides the scenario's)\n"
               "  --dry-run   only check that the target stays inside the image; write nothing\n"
               "  exit code: 0 done, 1 target outside the image, 2 usage, 3 load or write error\n");
}

// Every vertex inside the image means the whole (convex) target is inside.
bool targetInside(const visnav::PinholeCamera& camera, const visnav::PolygonModel& model,
                  const visnav::Pose& T) {
  for (const visnav::Vec3& v : model.vertices()) {
    visnav::Vec2 px;
    if (!camera.project(T.transform(v), px) || !camera.inImage(px, 1.0)) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace visnav;
  std::string scenario_path;
  std::string out_dir;
  long long max_frames = -1;
  long long stride = 1;
  long long seed = -1;
  bool dry_run = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (const int code = cli::standardOption(argv[i], "visnav-synth", usage); code >= 0) return code;
    if (arg == "--scenario" && has_value) {
      scenario_path = argv[++i];
    } else if (arg == "--out" && has_value) {
      out_dir = argv[++i];
    } else if ((arg == "--frames" || arg == "--stride" || arg == "--seed") && has_value) {
      long long& target = arg == "--frames" ? max_frames : (arg == "--stride" ? stride : seed);
      if (!cli::parseInteger(argv[++i], 0, std::numeric_limits<long long>::max(), target) ||
          (arg == "--stride" && stride < 1)) {
        std::fprintf(stderr, "visnav-synth: bad value '%s' for %s\n", argv[i], arg.c_str());
        usage(stderr);
        return 2;
      }
    } else if (arg == "--dry-run") {
      dry_run = true;
    } else {
      std::fprintf(stderr, "visnav-synth: bad argument '%s'\n", arg.c_str());
      usage(stderr);
      return 2;
    }
  }
  if (scenario_path.empty() || (out_dir.empty() && !dry_run)) {
    usage(stderr);
    return 2;
  }

  synth::Scenario sc;
  LoadError e = synth::loadScenario(scenario_path, sc);
  CameraIntrinsics intrinsics;
  PolygonModel model;
  if (e.ok) e = io::loadCamera(sc.camera_path, intrinsics);
  if (e.ok) e = io::loadModel(sc.model_path, model);
  synthetic::Renderer renderer;
  const PinholeCamera camera(intrinsics);
  if (e.ok) e = renderer.init(camera, model, sc.render);
  replay::SequenceWriter writer;
  if (e.ok && !dry_run) {
    e = writer.open(out_dir, sc.name, intrinsics, model, sc.bit_depth, sc.max_code, sc.trajectory.rate_hz);
  }
  if (!e.ok) {
    std::fprintf(stderr, "visnav-synth: %s\n", e.message.c_str());
    return visnav::cli::kExitInvalidInput;
  }
  if (seed >= 0) sc.seed = static_cast<std::uint64_t>(seed);

  const int w = camera.width();
  const int h = camera.height();
  std::vector<std::uint8_t> img8(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  std::vector<std::uint16_t> img16(sc.bit_depth == 16 ? img8.size() : 0U);
  const int total = sc.trajectory.frameCount();
  std::vector<int> rendered;  // frame numbers, for clutter.csv
  long long written = 0;
  int outside = 0;
  int first_outside = -1;
  double render_s = 0.0;
  const auto t_start = std::chrono::steady_clock::now();
  for (long long i = 0; i < total && (max_frames < 0 || written < max_frames); i += stride) {
    const int frame = static_cast<int>(i);
    const Pose pose = sc.trajectory.pose(frame);
    if (!targetInside(camera, model, pose)) {
      if (first_outside < 0) first_outside = frame;
      ++outside;
    }
    ++written;
    if (dry_run) continue;
    const auto t0 = std::chrono::steady_clock::now();
    const std::uint64_t frame_seed =
        synthetic::Renderer::frameSeed(sc.seed, static_cast<std::uint64_t>(frame));
    const std::string path = writer.framePath(frame);
    renderer.setFrameIndex(frame);
    if (sc.bit_depth == 8) {
      renderer.render(pose, frame_seed, img8.data(), w);
      render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      e = replay::writePgm8(path, ImageView8(img8.data(), w, h));
    } else {
      renderer.render(pose, frame_seed, img16.data(), 2 * w, sc.max_code);
      render_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      e = replay::writePgm16(path, ImageView16(img16.data(), w, h), sc.max_code);
    }
    if (!e.ok) {
      std::fprintf(stderr, "visnav-synth: %s\n", e.message.c_str());
      return visnav::cli::kExitInvalidInput;
    }
    writer.addFrame(frame, sc.trajectory.timestampNs(frame), &pose);
    rendered.push_back(frame);
  }
  if (!dry_run) e = writer.close();
  if (e.ok && !dry_run) e = synth::writeClutterCsv(out_dir, sc.render, rendered, w, h);
  if (!e.ok) {
    std::fprintf(stderr, "visnav-synth: %s\n", e.message.c_str());
    return visnav::cli::kExitInvalidInput;
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::printf(
      "visnav-synth: %s: %lld of %d frames (%dx%d, %d bit) -> %s in %.1f s (render %.1f ms/frame); "
      "target outside the image in %d frames",
      sc.name.c_str(), written, total, w, h, sc.bit_depth, dry_run ? "(dry run)" : out_dir.c_str(), wall_s,
      written > 0 && !dry_run ? 1e3 * render_s / static_cast<double>(written) : 0.0, outside);
  if (first_outside >= 0) std::printf(" (first: %d)", first_outside);
  std::printf("\n");
  return outside > 0 ? visnav::cli::kExitFailed : visnav::cli::kExitOk;  // README "Exit codes"
}
