// Tunables of the mode manager and the FDIR monitor (issue 3), with units, ranges and defaults. The
// generated reference is config/PARAMETERS.md; a run takes its values from the [navigation] table.
#pragma once

#include "visnav/core/param_visitor.hpp"

namespace visnav::nav {

struct NavigationParams {
  // Mode hysteresis (distances along the boresight, counts of consecutive frames).
  int start_mode = 1;                   ///< NavMode index the pipeline starts in (1 = far range)
  double acquire_below_m = 30.0;        ///< far range -> acquisition when the far-range distance is below
  double far_range_above_m = 40.0;      ///< near range -> far range when the estimated distance is above
  int enter_frames = 3;                 ///< consecutive frames a distance condition must hold
  int acquisition_timeout_frames = 25;  ///< acquisition gives up (back to far range) after this many frames
  int fault_persistence_frames = 5;     ///< a near-range fault held this long falls back to far range
  int coast_frames = 3;                 ///< frames the filter may propagate without a usable measurement
  // FDIR thresholds (near range).
  double min_inlier_ratio = 0.5;  ///< edge-point inliers / points over the used lines, below: fault
  int min_usable_lines = 3;       ///< fewer used lines: fault
  double max_rms_px = 1.0;        ///< LM residual above: fault
  double min_range_m = 1.0;       ///< plausible distance band (t_c_m.z)
  double max_range_m = 1000.0;
  double max_frame_age_ms = 150.0;  ///< frame older than this when processed: fault

  template <typename Visitor>
  void visit(Visitor& v) {
    v.enumeration(
        {"navigation", "start_mode", "-", 0, 3, "mode after start (standby waits for a resume command)"},
        "standby|far_range|acquisition|near_range", start_mode);
    v.real({"navigation", "acquire_below_m", "m", 1.0, 10000.0,
            "far range hands over to acquisition when its distance stays below this for enter_frames"},
           acquire_below_m);
    v.real({"navigation", "far_range_above_m", "m", 1.0, 10000.0,
            "near range falls back to far range when the distance stays above this for enter_frames "
            "(must exceed acquire_below_m: the gap is the hysteresis)"},
           far_range_above_m);
    v.integer({"navigation", "enter_frames", "count", 1, 1000,
               "consecutive frames a distance condition must hold before the mode changes"},
              enter_frames);
    v.integer({"navigation", "acquisition_timeout_frames", "count", 1, 10000,
               "acquisition returns to far range when it has not succeeded within this many frames"},
              acquisition_timeout_frames);
    v.integer({"navigation", "fault_persistence_frames", "count", 1, 1000,
               "a near-range fault held for this many consecutive frames falls back to far range"},
              fault_persistence_frames);
    v.integer({"navigation", "coast_frames", "count", 0, 1000,
               "frames the Kalman prediction stands in for a failed near-range measurement (sec. II-H)"},
              coast_frames);
    v.real({"navigation", "min_inlier_ratio", "-", 0.0, 1.0,
            "FDIR: edge-point inlier ratio over the used lines below this is a fault"},
           min_inlier_ratio);
    v.integer({"navigation", "min_usable_lines", "count", 0, 1000, "FDIR: fewer used lines is a fault"},
              min_usable_lines);
    v.real({"navigation", "max_rms_px", "px", 0.001, 100.0, "FDIR: pose-fit residual above this is a fault"},
           max_rms_px);
    v.real({"navigation", "min_range_m", "m", 0.0, 100000.0, "FDIR: plausible range band, lower end"},
           min_range_m);
    v.real({"navigation", "max_range_m", "m", 0.0, 100000.0, "FDIR: plausible range band, upper end"},
           max_range_m);
    v.real({"navigation", "max_frame_age_ms", "ms", 0.0, 100000.0,
            "FDIR: a frame older than this when processed is a fault (0 disables the check)"},
           max_frame_age_ms);
  }

  const char* crossCheck() const {
    if (!(far_range_above_m > acquire_below_m))
      return "far_range_above_m must exceed acquire_below_m (hysteresis)";
    if (!(max_range_m > min_range_m)) return "max_range_m must exceed min_range_m";
    return nullptr;
  }
};

}  // namespace visnav::nav
