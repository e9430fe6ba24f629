// visnav-edge-score: the truth-free edge-alignment score of poses on a sequence's frames (tools/realimages/
// README.md, "The metric"). The same code scores visnav-replay's CSV and ViSP's (visp_mbt_compare), so the
// two trackers compare on the same frames. Exit codes (README.md "Exit codes", visnav::cli): 0 scored, 2
// usage, 3 a sequence or pose CSV that does not load.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/realimages/edge_score.hpp"
#include "visnav/replay/sequence.hpp"

namespace {

const char* const kUsage =
    "usage: visnav-edge-score --sequence DIR (--poses CSV | --pose x,y,z,yaw_deg,pitch_deg,roll_deg)\n"
    "                         [--label NAME] [--out FRAMES.csv] [--max-frames N] [--search-px N]\n"
    "                         [--step-px S] [--min-gradient G] [--markdown-row]\n"
    "       visnav-edge-score --help | --version\n"
    "Scores how well the projected model edges (back faces culled) lie on the image gradient, per frame:\n"
    "samples every S px (2) along each visible edge, the Sobel gradient maximum along the normal within +-N "
    "px\n"
    "(10), its offset from the edge. --poses: a visnav-replay CSV or any CSV with its columns (frame, "
    "status,\n"
    "x_m..qz; mode and t_total_us optional); frames without a tracking/degraded row count as not tracked.\n"
    "--pose: one pose for every frame. Prints frames, tracked frames, mode changes, the median |offset| "
    "[px],\n"
    "the share of samples within 1 px with a gradient >= G (10 grey levels/px), frames aligned (tracked and\n"
    "at least half their samples within 1 px), the median t_total_us; --markdown-row prints it as a table "
    "row.\n"
    "  exit code: 0 scored, 2 usage, 3 a sequence or CSV that does not load\n";

using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;

bool parsePose(const std::string& text, visnav::Pose& pose) {
  double v[6];
  std::size_t start = 0;
  for (int i = 0; i < 6; ++i) {
    const std::size_t comma = text.find(',', start);
    if ((i < 5) != (comma != std::string::npos)) return false;
    const std::string item = text.substr(start, i < 5 ? comma - start : std::string::npos);
    // Blanks after a comma are fine ("0, 0, 20, ..."), as in visnav-replay --initial-pose.
    const std::size_t first = item.find_first_not_of(" \t");
    if (first == std::string::npos || !visnav::cli::parseNumber(item.substr(first), v[i])) return false;
    start = comma + 1;
  }
  const double k = M_PI / 180.0;
  pose = visnav::Pose::fromYpr({v[3] * k, v[4] * k, v[5] * k}, visnav::Vec3(v[0], v[1], v[2]));
  return true;
}

/// t_total_us by frame, when the CSV has that column (visnav-replay, visp_mbt_compare).
std::map<std::int64_t, double> readStepTimes(const std::string& path) {
  std::map<std::int64_t, double> out;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return out;
  const std::vector<std::string> header = visnav::eval::splitCsvLine(line);
  const auto it = std::find(header.begin(), header.end(), "t_total_us");
  const auto fr = std::find(header.begin(), header.end(), "frame");
  if (it == header.end() || fr == header.end()) return out;
  const std::size_t col = static_cast<std::size_t>(it - header.begin());
  const std::size_t fcol = static_cast<std::size_t>(fr - header.begin());
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = visnav::eval::splitCsvLine(line);
    double value = 0.0;
    if (cells.size() > std::max(col, fcol) && visnav::cli::parseNumber(cells[col], value) && value > 0.0)
      out[std::strtoll(cells[fcol].c_str(), nullptr, 10)] = value;
  }
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  std::string sequence_dir, poses_path, pose_text, label, out_path;
  long max_frames = -1;
  bool markdown = false;
  visnav::realimages::EdgeScoreOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-edge-score", kUsage); code >= 0)
      return code;
    double number = 0.0;
    long long count = 0;
    if (arg == "--sequence" && has_value) {
      sequence_dir = argv[++i];
    } else if (arg == "--poses" && has_value) {
      poses_path = argv[++i];
    } else if (arg == "--pose" && has_value) {
      pose_text = argv[++i];
    } else if (arg == "--label" && has_value) {
      label = argv[++i];
    } else if (arg == "--out" && has_value) {
      out_path = argv[++i];
    } else if (arg == "--markdown-row") {
      markdown = true;
    } else if ((arg == "--max-frames" || arg == "--search-px") && has_value) {
      if (!visnav::cli::parseInteger(argv[++i], 1, 1000000000, count)) {
        std::fprintf(stderr, "visnav-edge-score: %s wants a whole number >= 1, got '%s'\n", arg.c_str(),
                     argv[i]);
        return kExitUsage;
      }
      if (arg == "--max-frames")
        max_frames = static_cast<long>(count);
      else
        options.search_half_px = static_cast<int>(std::min(count, 64LL));
    } else if ((arg == "--step-px" || arg == "--min-gradient") && has_value) {
      if (!visnav::cli::parseNumber(argv[++i], number) || number < (arg == "--step-px" ? 0.25 : 0.0) ||
          number > 1e6) {
        std::fprintf(stderr, "visnav-edge-score: %s: bad value '%s'\n", arg.c_str(), argv[i]);
        return kExitUsage;
      }
      (arg == "--step-px" ? options.sample_step_px : options.min_gradient) = number;
    } else {
      std::fprintf(stderr, "visnav-edge-score: unknown or incomplete argument '%s'\n%s", arg.c_str(), kUsage);
      return kExitUsage;
    }
  }
  visnav::Pose fixed_pose;
  if (sequence_dir.empty() || poses_path.empty() == pose_text.empty() ||
      (!pose_text.empty() && !parsePose(pose_text, fixed_pose))) {
    std::fprintf(stderr,
                 "visnav-edge-score: --sequence and one of --poses or --pose (six numbers) needed\n%s",
                 kUsage);
    return kExitUsage;
  }
  if (label.empty()) label = poses_path.empty() ? "pose" : poses_path;

  visnav::replay::Sequence sequence;
  if (const visnav::LoadError e = visnav::replay::loadSequence(sequence_dir, sequence); !e.ok) {
    std::fprintf(stderr, "visnav-edge-score: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  if (sequence.bit_depth != 8) {
    std::fprintf(stderr, "visnav-edge-score: %s: only 8-bit sequences are scored\n", sequence_dir.c_str());
    return kExitInvalidInput;
  }
  std::map<std::int64_t, visnav::eval::ReplayRow> rows;
  std::map<std::int64_t, double> step_us;
  int mode_changes = 0;
  if (!poses_path.empty()) {
    std::vector<visnav::eval::ReplayRow> list;
    if (const visnav::LoadError e = visnav::eval::loadReplayCsv(poses_path, list); !e.ok) {
      std::fprintf(stderr, "visnav-edge-score: %s\n", e.message.c_str());
      return kExitInvalidInput;
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      rows[list[k].frame] = list[k];
      if (k > 0 && list[k].mode != list[k - 1].mode) ++mode_changes;
    }
    step_us = readStepTimes(poses_path);
  }

  const visnav::PinholeCamera camera(sequence.camera);
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(camera.width()) * camera.height());
  visnav::realimages::Gradient gradient;
  std::FILE* out = nullptr;
  if (!out_path.empty()) {
    out = std::fopen(out_path.c_str(), "w");
    if (out == nullptr) {
      std::fprintf(stderr, "visnav-edge-score: cannot write %s\n", out_path.c_str());
      return kExitInvalidInput;
    }
    std::fputs("frame,tracked,samples,with_edge,within,median_abs_offset_px,within_fraction\n", out);
  }
  int frames = 0, tracked = 0, aligned = 0;
  long samples = 0, within = 0;
  std::vector<double> offsets, times;
  for (const visnav::replay::FrameEntry& entry : sequence.frames) {
    if (max_frames > 0 && frames >= max_frames) break;
    ++frames;
    visnav::Pose pose = fixed_pose;
    if (!poses_path.empty()) {
      const auto it = rows.find(entry.frame);
      const bool ok = it != rows.end() && visnav::eval::isTracked(it->second.status) && it->second.has_pose;
      if (!ok) {
        if (out != nullptr) std::fprintf(out, "%lld,0,,,,,\n", static_cast<long long>(entry.frame));
        continue;
      }
      pose = it->second.pose;
      if (const auto t = step_us.find(entry.frame); t != step_us.end()) times.push_back(t->second);
    }
    ++tracked;
    int w = 0, h = 0, maxval = 0;
    if (const visnav::LoadError e = visnav::replay::readPgm(entry.file, pixels.data(), pixels.size(), w, h,
                                                            maxval, sequence.max_code);
        !e.ok || w != camera.width() || h != camera.height()) {
      std::fprintf(stderr, "visnav-edge-score: %s\n",
                   e.ok ? "frame size differs from the camera" : e.message.c_str());
      if (out != nullptr) std::fclose(out);
      return kExitInvalidInput;
    }
    gradient.compute(pixels.data(), w, h, w);
    const visnav::realimages::FrameEdgeScore s =
        visnav::realimages::scoreFrame(gradient, camera, sequence.model, pose, options);
    samples += s.samples;
    within += s.within;
    offsets.insert(offsets.end(), s.abs_offsets.begin(), s.abs_offsets.end());
    if (s.samples > 0 && s.withinFraction() >= 0.5) ++aligned;
    if (out != nullptr)
      std::fprintf(out, "%lld,1,%d,%d,%d,%.4f,%.4f\n", static_cast<long long>(entry.frame), s.samples,
                   s.with_edge, s.within, s.median_abs_offset_px(), s.withinFraction());
  }
  if (out != nullptr) std::fclose(out);
  const double med = median(offsets);
  const double share = samples > 0 ? 100.0 * static_cast<double>(within) / static_cast<double>(samples) : 0.0;
  const double step = median(times);
  const std::string step_text = std::isnan(step) ? "-" : std::to_string(std::lround(step)) + " us";
  if (markdown) {
    std::printf("| %s | %d | %d | %d | %d | %.2f | %.1f %% | %s |\n", label.c_str(), frames, tracked,
                mode_changes, aligned, med, share, step_text.c_str());
  } else {
    std::printf(
        "%s: frames %d, tracked %d, mode changes %d, frames aligned %d, samples %ld, median |offset| %.2f "
        "px, "
        "within %.0f px %.1f %%, step median %s\n",
        label.c_str(), frames, tracked, mode_changes, aligned, samples, med, options.within_px, share,
        step_text.c_str());
  }
  return kExitOk;
}
