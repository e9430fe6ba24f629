// Shared by test_far_estimator.cpp and test_far_extended.cpp: scenes of the far-range satellite and plates
// approaching from 200 m, and the estimator run over them.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "far_fixture.hpp"

namespace visnav::far::approach_support {

using test::angleDeg;

// The outline search of an extended target (fsw/farrange/README.md) at its measured setting, the default,
// and switched off.
inline FarRangeParams withOutlineSearch() {
  FarRangeParams p;
  p.extended_min_half_px = 12.0;
  return p;
}
inline FarRangeParams withoutOutlineSearch() {
  FarRangeParams p;
  p.extended_min_half_px = 0.0;
  return p;
}

inline FarRangeParams method(FarRangeMethod m) {
  FarRangeParams p;
  p.method = static_cast<int>(m);
  return p;
}

struct Scene {
  PinholeCamera camera = test::farCamera();
  PolygonModel model = test::smallsat();
  synthetic::Renderer renderer;
  explicit Scene(const synthetic::RenderOptions& options = test::farRender()) {
    EXPECT_TRUE(renderer.init(camera, model, options).ok);
  }
  Scene(const synthetic::RenderOptions& options, const PinholeCamera& c, const PolygonModel& m)
      : camera(c), model(m) {
    EXPECT_TRUE(renderer.init(camera, model, options).ok);
  }
  test::FarFrame frame(const Pose& pose, std::uint64_t seed = 1, std::int64_t index = 0) {
    return test::renderFar(renderer, pose, seed, index);
  }
};

inline FarRangeResult estimateOnce(const PinholeCamera& camera, const FarRangeParams& params,
                                   const test::FarFrame& f) {
  FarRangeEstimator e;
  EXPECT_TRUE(e.init(camera, params).ok);
  FarRangeResult r;
  EXPECT_EQ(e.estimate(f.image(), r), Status::kOk);
  return r;
}

// A plate approaching from 200 m to 12 m at 3 % a frame, gamma calibrated at 200 m. `last_good_m` is the
// closest range with a fix on the target (direction inside its bounding sphere, distance within 25 %).
struct ApproachScene {
  synthetic::RenderOptions render;
  PinholeCamera camera;
  PolygonModel model;
  double gamma = 0.0;  ///< 0: calibrated on a frame at 200 m
};

// A flat plate of `width_m` x `height_m` (brightness on background level, noise, blur) seen by a
// width_px x height_px camera of focal length f_px.
inline ApproachScene plateScene(double width_m, double height_m, double brightness, double background,
                                double noise, double blur_px, int width_px, int height_px, double f_px) {
  ApproachScene a;
  a.render.background = background;
  a.render.target_brightness = brightness;
  a.render.noise_sigma = noise;
  a.render.blur_sigma_px = blur_px;
  CameraIntrinsics k =
      CameraIntrinsics::fromSi(width_px, height_px, 6e-3, 6e-6, 6e-6, 0.0, 0.5 * width_px, 0.5 * height_px);
  k.fx_px = k.fy_px = f_px;
  a.camera = PinholeCamera(k);
  a.model = makeRectanglePlate(width_m, height_m);
  return a;
}

// octagon/26 in kind: a bright flat plate on 640x480, f 1180 px, noise 0.063.
inline ApproachScene brightPlate() { return plateScene(2.0, 2.2, 0.87, 0.28, 0.063, 0.33, 640, 480, 1180.0); }

// plate/50 in kind: a long plate of low contrast (0.27) in noise on 1024x768, f 1134 px (plate/50 had 0.108,
// where the edge response does not close the outline either).
inline ApproachScene dimPlateInNoise() {
  ApproachScene a = plateScene(2.9, 1.2, 0.52, 0.246, 0.08, 0.4, 1024, 768, 1134.0);
  a.gamma = 1134.0 * std::sqrt(2.9 * 1.2);  // f sqrt(face-on area), as the campaign sets it
  return a;
}

// `target_radius_m` > 0: the estimator knows the target's radius (extent distance, as in the pipeline).
inline std::vector<FarRangeResult> approach(const ApproachScene& a, const FarRangeParams& p,
                                            double& last_good_m, double target_radius_m = 0.0) {
  Scene s(a.render, a.camera, a.model);
  FarRangeParams q = p;
  q.gamma = a.gamma;
  if (!(q.gamma > 0.0)) {
    // gamma calibrated at the start distance (eq. 16), as visnav-calibrate-gamma would.
    const FarRangeResult cal = estimateOnce(s.camera, p, s.frame(test::satAt(200.0, 1.0, -0.5, 10.0), 99));
    EXPECT_TRUE(cal.valid);
    q.gamma = 200.0 * std::sqrt(static_cast<double>(cal.cluster_pixels));
  }
  FarRangeEstimator e;
  EXPECT_TRUE(e.init(s.camera, q).ok);
  e.setTargetRadius(target_radius_m);
  std::vector<FarRangeResult> results;
  last_good_m = 1e9;
  for (int i = 0; i < 93; ++i) {
    const double range = 200.0 * std::pow(0.97, i);
    const test::FarFrame f = s.frame(test::satAt(range, 1.0 + 0.02 * i, -0.5, 10.0 + 0.3 * i), 100 + i, i);
    FarRangeResult r;
    e.estimate(f.image(), r);
    const double radius_deg = std::atan(s.model.boundingRadius() / range) * kDegPerRad;
    if (r.valid && angleDeg(r.direction_c, f.truth.t_c_m.normalized()) < radius_deg &&
        std::abs(r.distance_m / range - 1.0) < 0.25)
      last_good_m = range;
    results.push_back(r);
  }
  return results;
}

}  // namespace visnav::far::approach_support
