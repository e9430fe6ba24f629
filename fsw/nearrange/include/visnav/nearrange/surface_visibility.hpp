// Surface switching (paper sec. II-H): the viewing angle v of each surface and the hysteresis that starts
// and stops tracking it. Definitions in fsw/geometry/CONVENTIONS.md ("Surface visibility").
#pragma once

#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav {

struct VisibilityThresholds {
  double enter_low_deg = 45.0;
  double enter_high_deg = 135.0;
  double exit_low_deg = 40.0;
  double exit_high_deg = 140.0;
};

struct SurfaceView {
  bool front_facing = false;  ///< n . d < 0: the camera sees the outside of the surface
  double v_deg = 0.0;         ///< viewing angle in [0, 180], 90 = head-on (eq. 8, CONVENTIONS.md)
};

SurfaceView viewSurface(const ModelSurface& surface, const Pose& T_c_m);

/// Hysteresis step: returns the new tracking flag. Back faces are never tracked.
bool updateVisibility(bool tracked, const SurfaceView& view, const VisibilityThresholds& thresholds);

}  // namespace visnav
