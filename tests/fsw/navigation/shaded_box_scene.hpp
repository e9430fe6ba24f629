// The shaded box the close-range reacquisition tests slew away from (test_local_reacquisition.cpp drives
// LocalReacquisition on it, test_pipeline_reacquisition.cpp the whole pipeline): one scene, so the two
// measure the same geometry.
#pragma once

#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::test {

/// A box of half sizes 0.8 x 0.6 x 0.5 m.
inline PolygonModel shadedBox() { return makeBox(0.8, 0.6, 0.5); }

/// Lambert shading from one sun: one flat brightness would hide the box's inner edges.
inline synthetic::RenderOptions shadedBoxRender() {
  synthetic::RenderOptions render;
  render.shading.enabled = true;
  render.shading.sun_dir_c = Vec3(0.3, 0.5, 1.0);
  return render;
}

/// The box at 10 m, three faces in view.
inline Pose shadedBoxPose() { return Pose::fromYpr({0.6, 0.4, 2.8}, Vec3(0.1, -0.05, 10.0)); }

/// `pose` after the camera turned `deg` about its own y axis: a slew moves the target across the image and
/// turns it with the camera, its look along the line of sight unchanged.
inline Pose slewedAboutCameraY(const Pose& pose, double deg) {
  const Mat3 r = expSo3(Vec3::UnitY() * (deg * kRadPerDeg));
  Pose p;
  p.R_c_m = r * pose.R_c_m;
  p.t_c_m = r * pose.t_c_m;
  return p;
}

}  // namespace visnav::test
