// Runs the far-range estimator over a recorded sequence (drivers/replay format) and scores it against the
// truth: direction error [deg], distance error [%], "right target chosen" (all frames and the frames with
// clutter in view, from the sequence's clutter.csv), step time. Also the gamma calibration of eq. 16 from
// such a run. Used by visnav-calibrate-gamma and visnav-far-eval (README.md in this folder). Ground tool
// code: allocates.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/farrange/far_range_params.hpp"
#include "visnav/farrange/gamma_calibration.hpp"
#include "visnav/replay/sequence.hpp"

namespace visnav::far_eval {

struct FrameRecord {
  std::int64_t frame = 0;
  double truth_range_m = 0.0;      ///< |t_c_m|
  double target_radius_deg = 0.0;  ///< angular radius of the model's bounding sphere at that range
  bool valid = false;
  double direction_error_deg = 0.0;  ///< angle between estimated and true line of sight (eval::farRangeError)
  double distance_m = 0.0;
  double distance_error_pct = 0.0;  ///< 100 * (estimate - t_c_m.z) / t_c_m.z (eval::farRangeError)
  int cluster_pixels = 0;
  int raw_pixels = 0;
  int boundary_pixels = 0;
  int cluster_count = 0;
  std::uint32_t flags = 0;
  bool right_target = false;  ///< valid and inside the target's angular radius + 0.1 deg
  int bars_in_view = 0;       ///< from clutter.csv (0 when the sequence has none)
  int glints_in_view = 0;
  double step_us = 0.0;
};

/// Every frame with truth, in order; the estimator keeps its state across frames like the flight loop.
/// reset_each_frame: independent frames (no track between them).
LoadError runSequence(const replay::Sequence& sequence, const far::FarRangeParams& params,
                      bool reset_each_frame, std::vector<FrameRecord>& out);

/// Reads DIR/clutter.csv into the records (no file: leaves zeros).
LoadError readClutter(const std::string& directory, std::vector<FrameRecord>& records);

/// Gamma from the frames with the right target in [min_range, max_range] (truth range, n as reported).
far::GammaEstimate calibrateFromRecords(const std::vector<FrameRecord>& records, double min_range_m,
                                        double max_range_m);

struct Summary {
  int frames = 0;
  int valid = 0;
  int right = 0;
  int clutter_frames = 0;  ///< a bar in view
  int clutter_right = 0;
  int glint_frames = 0;  ///< a glint in view (stars included)
  int glint_right = 0;
  double direction_median_deg = 0.0;  ///< over right-target frames
  double direction_p95_deg = 0.0;
  double distance_median_pct = 0.0;  ///< median |error| over right-target frames
  double distance_p95_pct = 0.0;
  double step_median_us = 0.0;
  double step_p95_us = 0.0;

  double rightFraction() const { return frames > 0 ? static_cast<double>(right) / frames : 0.0; }
  double clutterRightFraction() const {
    return clutter_frames > 0 ? static_cast<double>(clutter_right) / clutter_frames : 1.0;
  }
  double glintRightFraction() const {
    return glint_frames > 0 ? static_cast<double>(glint_right) / glint_frames : 1.0;
  }
};

/// Over the records with truth range in [min_range_m, max_range_m).
Summary summarise(const std::vector<FrameRecord>& records, double min_range_m = 0.0,
                  double max_range_m = 1e300);

/// Per-frame CSV (header + one row per record).
LoadError writeRecordsCsv(const std::string& path, const char* method,
                          const std::vector<FrameRecord>& records, bool append);

}  // namespace visnav::far_eval
