// visnav-far-eval: runs the far-range estimator (paper and/or robust method) over a sequence with truth and
// prints direction error, distance error and how often the right target was chosen (all frames, frames
// with the clutter object in view, frames with glints). README.md in this folder.
// Exit codes (README.md "Exit codes", visnav::cli): 0 all requested requirements hold, 1 a requirement failed
// (or the calibration sequence has no frame with the target), 2 usage, 3 a config, sequence or frame that
// does not load, or --csv that cannot be written.
#include <cstdio>
#include <string>
#include <vector>

#include "far_cli.hpp"
#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/far_eval/far_evaluation.hpp"

namespace {

const char* const kUsage =
    "usage: visnav-far-eval --sequence DIR [--calibration DIR | --gamma G] [--config FILE]\n"
    "                       [--method paper|robust|both] [--csv per_frame.csv]\n"
    "                       [--require-direction-median-deg X] [--require-distance-median-pct X]\n"
    "                       [--require-right-fraction F] [--require-clutter-right-fraction F]\n"
    "       visnav-far-eval --help | --version\n"
    "Runs the far-range estimator over a sequence with truth: direction and distance errors, right-target\n"
    "fraction (tools/calibrate_gamma/README.md).\n"
    "  requirements apply to the robust method (or the one method given)\n"
    "  exit code: 0 all requested requirements hold, 1 a requirement failed (or no calibration frame\n"
    "  with the target), 2 usage, 3 a config, sequence or frame that does not load, or --csv that cannot\n"
    "  be written\n";

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;

struct Requirements {
  double direction_median_deg = -1.0;
  double distance_median_pct = -1.0;
  double right_fraction = -1.0;
  double clutter_right_fraction = -1.0;
};

bool check(bool ok, const char* what, double value, double limit) {
  if (!ok) std::printf("  REQUIREMENT FAILED: %s = %.4g (limit %.4g)\n", what, value, limit);
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace visnav;
  std::string sequence_dir, calibration_dir, config_path, csv_path, method = "both";
  double gamma = -1.0;
  Requirements req;
  for (int i = 1; i < argc; ++i) {
    const std::string opt = argv[i];
    if (const int code = cli::standardOption(argv[i], "visnav-far-eval", kUsage); code >= 0) return code;
    if (i + 1 >= argc) {
      std::fprintf(stderr, "visnav-far-eval: missing value for %s\n%s", opt.c_str(), kUsage);
      return kExitUsage;
    }
    const std::string v = argv[++i];
    double x = 0.0;
    const bool number = cli::parseNumber(v, x);
    if (opt == "--sequence")
      sequence_dir = v;
    else if (opt == "--calibration")
      calibration_dir = v;
    else if (opt == "--config")
      config_path = v;
    else if (opt == "--csv")
      csv_path = v;
    else if (opt == "--method" && (v == "paper" || v == "robust" || v == "both"))
      method = v;
    else if (opt == "--gamma" && number && x > 0.0)
      gamma = x;
    else if (opt == "--require-direction-median-deg" && number)
      req.direction_median_deg = x;
    else if (opt == "--require-distance-median-pct" && number)
      req.distance_median_pct = x;
    else if (opt == "--require-right-fraction" && number)
      req.right_fraction = x;
    else if (opt == "--require-clutter-right-fraction" && number)
      req.clutter_right_fraction = x;
    else {
      std::fprintf(stderr, "visnav-far-eval: bad option %s %s\n%s", opt.c_str(), v.c_str(), kUsage);
      return kExitUsage;
    }
  }
  if (sequence_dir.empty()) {
    std::fprintf(stderr, "visnav-far-eval: --sequence is required\n%s", kUsage);
    return kExitUsage;
  }
  far::FarRangeParams base;
  LoadError e = far_eval::loadFarParams(config_path, base);
  replay::Sequence seq, calibration;
  if (e.ok) e = replay::loadSequence(sequence_dir, seq);
  if (e.ok && !calibration_dir.empty()) e = replay::loadSequence(calibration_dir, calibration);
  if (!e.ok) {
    std::fprintf(stderr, "visnav-far-eval: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  std::vector<std::string> methods;
  if (method == "both" || method == "paper") methods.emplace_back("paper");
  if (method == "both" || method == "robust") methods.emplace_back("robust");
  bool all_ok = true;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    far::FarRangeParams params = base;
    params.method = far_eval::methodIndex(methods[m]);
    std::string gamma_note = "from the config";
    std::vector<far_eval::FrameRecord> records;
    if (gamma > 0.0) {
      params.gamma = gamma;
      gamma_note = "given";
    } else if (!calibration_dir.empty()) {
      // One calibration per method over the whole calibration sequence (its n definitions differ).
      e = far_eval::runSequence(calibration, params, true, records);  // independent frames
      const far::GammaEstimate g = far_eval::calibrateFromRecords(records, 0.0, 1e12);
      if (e.ok && !g.ok) {  // it ran, and found nothing to calibrate on: a negative result
        std::fprintf(stderr, "visnav-far-eval: %s: no calibration frame with the target (%s method)\n",
                     calibration_dir.c_str(), methods[m].c_str());
        return kExitFailed;
      }
      if (e.ok) params.gamma = g.gamma;
      gamma_note = "calibrated on " + calibration.name + ": " + std::to_string(g.inliers) +
                   " frames, spread " + std::to_string(100.0 * g.spread).substr(0, 4) + " %";
    }
    if (e.ok) e = far_eval::runSequence(seq, params, false, records);
    if (e.ok && !csv_path.empty())
      e = far_eval::writeRecordsCsv(csv_path, methods[m].c_str(), records, m > 0);
    if (!e.ok) {
      std::fprintf(stderr, "visnav-far-eval: %s\n", e.message.c_str());
      return kExitInvalidInput;
    }
    const far_eval::Summary s = far_eval::summarise(records);
    double range_min = 1e12, range_max = 0.0;
    for (const far_eval::FrameRecord& r : records) {
      range_min = std::min(range_min, r.truth_range_m);
      range_max = std::max(range_max, r.truth_range_m);
    }
    std::printf("%s method on %s (%d frames, range %.0f..%.0f m), gamma %.1f (%s)\n", methods[m].c_str(),
                seq.name.c_str(), s.frames, range_min, range_max, params.gamma, gamma_note.c_str());
    std::printf(
        "  right target: all %d/%d (%.1f %%), clutter in view %d/%d (%.1f %%), glints in view %d/%d (%.1f "
        "%%)\n",
        s.right, s.frames, 100.0 * s.rightFraction(), s.clutter_right, s.clutter_frames,
        100.0 * s.clutterRightFraction(), s.glint_right, s.glint_frames, 100.0 * s.glintRightFraction());
    std::printf("  direction error [deg] (right-target frames): median %.4f  p95 %.4f\n",
                s.direction_median_deg, s.direction_p95_deg);
    std::printf("  distance error |%%| (right-target frames): median %.2f  p95 %.2f\n", s.distance_median_pct,
                s.distance_p95_pct);
    std::printf("  step [us]: median %.1f  p95 %.1f  (valid %d/%d)\n", s.step_median_us, s.step_p95_us,
                s.valid, s.frames);
    // By range: where each method's n stops following 1/d^2 shows up here.
    const double bins[] = {0.0, 100.0, 200.0, 400.0, 1e300};
    for (int b = 0; b < 4; ++b) {
      const far_eval::Summary r = far_eval::summarise(records, bins[b], bins[b + 1]);
      if (r.frames == 0) continue;
      std::printf(
          "  range %s: %4d frames, right %5.1f %%, direction median %.4f deg, distance median %.2f %%\n",
          b == 0   ? "   < 100 m"
          : b == 1 ? "100-200 m"
          : b == 2 ? "200-400 m"
                   : "  >= 400 m",
          r.frames, 100.0 * r.rightFraction(), r.direction_median_deg, r.distance_median_pct);
    }
    const bool gated = methods.size() == 1 || methods[m] == "robust";
    if (!gated) continue;
    if (req.direction_median_deg >= 0.0)
      all_ok &= check(s.direction_median_deg < req.direction_median_deg, "direction median [deg]",
                      s.direction_median_deg, req.direction_median_deg);
    if (req.distance_median_pct >= 0.0)
      all_ok &= check(s.distance_median_pct < req.distance_median_pct, "distance median [%]",
                      s.distance_median_pct, req.distance_median_pct);
    if (req.right_fraction >= 0.0)
      all_ok &= check(s.rightFraction() >= req.right_fraction, "right-target fraction", s.rightFraction(),
                      req.right_fraction);
    if (req.clutter_right_fraction >= 0.0)
      all_ok &= check(s.clutterRightFraction() >= req.clutter_right_fraction, "clutter right-target fraction",
                      s.clutterRightFraction(), req.clutter_right_fraction);
  }
  return all_ok ? kExitOk : kExitFailed;
}
