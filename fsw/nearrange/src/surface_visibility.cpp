#include "visnav/nearrange/surface_visibility.hpp"

#include <cmath>

namespace visnav {

SurfaceView viewSurface(const ModelSurface& surface, const Pose& T_c_m) {
  SurfaceView view;
  const Vec3 n = T_c_m.R_c_m * surface.normal_m;
  const Vec3 q = T_c_m.transform(surface.centroid_m);
  const double range = q.norm();
  if (range < 1e-12) return view;
  const Vec3 d = q / range;
  const double cos_phi = -n.dot(d);
  view.front_facing = cos_phi > 0.0;
  const double phi_deg = std::acos(std::fmin(1.0, std::fabs(cos_phi))) * kDegPerRad;
  // Which side of the line of sight the normal leans to decides v = 90 -/+ phi.
  const Vec3 lean = n + cos_phi * d;
  const double side = std::fabs(lean.x()) > 1e-9 ? lean.x() : lean.y();
  view.v_deg = side >= 0.0 ? 90.0 + phi_deg : 90.0 - phi_deg;
  return view;
}

bool updateVisibility(bool tracked, const SurfaceView& view, const VisibilityThresholds& t) {
  if (!view.front_facing) return false;
  if (tracked) return view.v_deg >= t.exit_low_deg && view.v_deg <= t.exit_high_deg;
  return view.v_deg > t.enter_low_deg && view.v_deg < t.enter_high_deg;
}

}  // namespace visnav
