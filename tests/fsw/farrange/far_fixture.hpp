// Shared by the far-range tests and the benchmark: the far_range scenario's satellite, camera and lighting
// rendered with the project's renderer (config/scenarios/far_range.toml, without its clutter unless asked).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "visnav/farrange/far_range_estimator.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::test {

/// 6 mm lens on 6 um pixels (fx = fy = 1000 px) with the scenario's mild barrel distortion.
inline PinholeCamera farCamera(int width = 640, int height = 480, bool distorted = true) {
  CameraIntrinsics k =
      CameraIntrinsics::fromSi(width, height, 6e-3, 6e-6, 6e-6, 0.0, 0.5 * width, 0.5 * height);
  if (distorted) {
    k.distortion.k1 = -0.05;
    k.distortion.k2 = 0.01;
  }
  return PinholeCamera(k);
}

inline PolygonModel smallsat() {
  PolygonModel model;
  io::loadModel(std::string(VISNAV_SOURCE_DIR) + "/config/models/smallsat_panels.toml", model);
  return model;
}

inline synthetic::RenderOptions farRender() {
  synthetic::RenderOptions o;
  o.background = 0.03;
  o.target_brightness = -1.0;
  o.noise_sigma = 0.015;
  o.shading.enabled = true;
  o.shading.ambient = 0.2;
  o.shading.sun_dir_c = Vec3(0.3, 0.2, 1.0);
  return o;
}

/// Satellite facing the camera at `range_m` along a line of sight (azimuth right, elevation up, degrees),
/// turned by `yaw_deg` about the line of sight.
inline Pose satAt(double range_m, double azimuth_deg = 0.0, double elevation_deg = 0.0,
                  double yaw_deg = 0.0) {
  const double az = azimuth_deg * kRadPerDeg;
  const double el = elevation_deg * kRadPerDeg;
  const Vec3 dir(std::sin(az) * std::cos(el), -std::sin(el), std::cos(az) * std::cos(el));
  return Pose::fromYpr({yaw_deg * kRadPerDeg, 0.0, kPi}, range_m * dir);
}

struct FarFrame {
  int width = 0;
  int height = 0;
  Pose truth;
  std::vector<std::uint8_t> pixels;
  MonoImage image() const { return MonoImage::from8(ImageView8(pixels.data(), width, height)); }
};

inline FarFrame renderFar(synthetic::Renderer& renderer, const Pose& truth, std::uint64_t seed,
                          std::int64_t frame_index = 0) {
  FarFrame f;
  f.width = renderer.width();
  f.height = renderer.height();
  f.truth = truth;
  f.pixels.resize(static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height));
  renderer.setFrameIndex(frame_index);
  renderer.render(truth, seed, f.pixels.data(), f.width);
  return f;
}

/// A broad glow (a Gaussian blob of sigma 8 px) larger in the response than the far satellite at 300 m
/// (test_far_refuted.cpp, test_far_noalloc.cpp).
inline synthetic::Glint glowAt(const Vec2& at_px) {
  synthetic::Glint g;
  g.first_frame = 0;
  g.last_frame = 1000;
  g.start_px = g.end_px = at_px;
  g.sigma_px = 8.0;
  g.peak = 1.0;
  return g;
}

/// Angle between two directions [deg].
inline double angleDeg(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

}  // namespace visnav::test
