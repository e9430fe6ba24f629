// visnav-calibrate-gamma: gamma of eq. 16 (d = gamma / sqrt(n)) from frames at known distance, as the paper
// did at 25 m (1/30 scale: 750 m) with 16 px -> 3000. Usage and method: README.md in this folder.
// Exit codes (README.md "Exit codes", visnav::cli): 0 ok, 1 no usable frame, 2 usage, 3 a config, camera,
// sequence or frame that does not load, or --out that cannot be written.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "far_cli.hpp"
#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/far_eval/far_evaluation.hpp"
#include "visnav/io/camera_io.hpp"

namespace {

const char* const kUsage =
    "usage: visnav-calibrate-gamma --sequence DIR [--min-range M] [--max-range M]   frames with truth\n"
    "       visnav-calibrate-gamma --camera FILE --frame IMG.pgm --distance M [--frame ... --distance ...]\n"
    "       visnav-calibrate-gamma --pixels N --distance M [--pixels ... --distance ...]  known cluster "
    "sizes\n"
    "  common: [--config FILE] [--method paper|robust] [--out gamma.toml]\n"
    "       visnav-calibrate-gamma --help | --version\n"
    "Calibrates eq. 16's gamma (d = gamma / sqrt(n)) from frames at known distance\n"
    "(tools/calibrate_gamma/README.md).\n"
    "  exit code: 0 ok, 1 no usable frame, 2 usage, 3 a config, camera, sequence or frame that does not\n"
    "  load, or --out that cannot be written\n";

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;

}  // namespace

int main(int argc, char** argv) {
  using namespace visnav;
  std::string sequence_dir, camera_path, config_path, out_path, method;
  std::vector<std::string> frames;
  std::vector<double> distances, pixels;
  double min_range = 0.0;
  double max_range = 1e12;
  for (int i = 1; i < argc; ++i) {
    const std::string opt = argv[i];
    if (const int code = cli::standardOption(argv[i], "visnav-calibrate-gamma", kUsage); code >= 0)
      return code;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "visnav-calibrate-gamma: missing value for %s\n%s", opt.c_str(), kUsage);
      return kExitUsage;
    }
    const std::string v = argv[++i];
    double x = 0.0;
    const bool number = cli::parseNumber(v, x);
    if (opt == "--sequence")
      sequence_dir = v;
    else if (opt == "--camera")
      camera_path = v;
    else if (opt == "--config")
      config_path = v;
    else if (opt == "--out")
      out_path = v;
    else if (opt == "--method")
      method = v;
    else if (opt == "--frame")
      frames.push_back(v);
    else if (opt == "--distance" && number && x > 0.0)
      distances.push_back(x);
    else if (opt == "--pixels" && number && x > 0.0)
      pixels.push_back(x);
    else if (opt == "--min-range" && number)
      min_range = x;
    else if (opt == "--max-range" && number)
      max_range = x;
    else {
      std::fprintf(stderr, "visnav-calibrate-gamma: bad option %s %s\n%s", opt.c_str(), v.c_str(), kUsage);
      return kExitUsage;
    }
  }
  // The command line first (usage, exit 2), then the config (a file that does not load, exit 3).
  LoadError usage_error;
  if (!method.empty() && far_eval::methodIndex(method) < 0)
    usage_error = LoadError::failure("--method must be paper or robust");
  const int modes = (sequence_dir.empty() ? 0 : 1) + (frames.empty() ? 0 : 1) + (pixels.empty() ? 0 : 1);
  if (usage_error.ok && modes != 1)
    usage_error = LoadError::failure("give exactly one of --sequence, --frame, --pixels");
  if (usage_error.ok && (!frames.empty() || !pixels.empty()) &&
      distances.size() != (frames.empty() ? pixels.size() : frames.size()))
    usage_error = LoadError::failure("every --frame / --pixels needs its --distance");
  if (usage_error.ok && !frames.empty() && camera_path.empty())
    usage_error = LoadError::failure("--frame needs --camera");
  if (!usage_error.ok) {
    std::fprintf(stderr, "visnav-calibrate-gamma: %s\n%s", usage_error.message.c_str(), kUsage);
    return kExitUsage;
  }
  far::FarRangeParams params;
  LoadError e = far_eval::loadFarParams(config_path, params);
  if (!e.ok) {
    std::fprintf(stderr, "visnav-calibrate-gamma: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  if (!method.empty()) params.method = far_eval::methodIndex(method);
  method = params.method == static_cast<int>(far::FarRangeMethod::kPaper) ? "paper" : "robust";

  std::vector<far::GammaSample> samples;
  far::GammaEstimate estimate;
  if (!pixels.empty()) {
    for (std::size_t k = 0; k < pixels.size(); ++k) samples.push_back({distances[k], pixels[k]});
    estimate = far::calibrateGamma(samples);
  } else {
    replay::Sequence seq;
    if (!sequence_dir.empty()) {
      e = replay::loadSequence(sequence_dir, seq);
    } else {
      // Explicit frames: a sequence without truth rows is built in memory; each frame stands alone.
      e = io::loadCamera(camera_path, seq.camera);
      for (std::size_t k = 0; e.ok && k < frames.size(); ++k) {
        seq.frames.push_back({static_cast<std::int64_t>(k), 0, frames[k]});
        replay::TruthRow row;
        row.frame = static_cast<std::int64_t>(k);
        row.pose.t_c_m = Vec3(0.0, 0.0, distances[k]);
        seq.truth.push_back(row);
      }
    }
    std::vector<far_eval::FrameRecord> records;
    // Calibration frames are independent measurements: no track carried between them.
    if (e.ok) e = far_eval::runSequence(seq, params, true, records);
    if (!e.ok) {
      std::fprintf(stderr, "visnav-calibrate-gamma: %s\n", e.message.c_str());
      return kExitInvalidInput;
    }
    // Explicit frames carry no true direction: every found target counts.
    if (sequence_dir.empty()) {
      for (far_eval::FrameRecord& r : records) r.right_target = r.valid;
    }
    estimate = far_eval::calibrateFromRecords(records, min_range, max_range);
  }
  if (!estimate.ok) {
    std::fprintf(stderr, "visnav-calibrate-gamma: no frame with a target in range\n");
    return kExitFailed;
  }
  std::printf("gamma = %.6g  (%s method; %d of %d frames averaged; median %.6g; robust spread %.1f %%)\n",
              estimate.gamma, method.c_str(), estimate.inliers, estimate.samples, estimate.median,
              100.0 * estimate.spread);
  if (!out_path.empty()) {
    std::ofstream out(out_path);
    out << "# visnav-calibrate-gamma, " << method << " method, " << estimate.inliers
        << " frames\n[farrange]\n"
        << "gamma = " << estimate.gamma << "\n";
    if (!out) {
      std::fprintf(stderr, "visnav-calibrate-gamma: cannot write %s\n", out_path.c_str());
      return kExitInvalidInput;
    }
  }
  return kExitOk;
}
