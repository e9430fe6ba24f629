// Shared by the tracker tests: the paper's synthetic recipe rendered with the project's renderer.
#pragma once

#include <cstdint>
#include <vector>

#include "visnav/nearrange/near_range_tracker.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::test {

inline PinholeCamera vgaCamera() {
  return PinholeCamera(CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320.0, 240.0));
}

/// The paper's plate facing the camera (roll 180 deg flips its +z normal towards the camera).
inline Pose plateAt(double distance_m, double lateral_x_m = 0.0, double yaw_deg = 0.0,
                    double pitch_deg = 0.0) {
  return Pose::fromYpr({yaw_deg * kRadPerDeg, pitch_deg * kRadPerDeg, kPi},
                       Vec3(lateral_x_m, 0.0, distance_m));
}

struct RenderedFrame {
  Pose truth;
  std::vector<std::uint8_t> pixels;
  MonoImage image() const { return MonoImage::from8(ImageView8(pixels.data(), 640, 480)); }
};

inline RenderedFrame renderFrame(synthetic::Renderer& renderer, const Pose& truth, std::uint64_t seed) {
  RenderedFrame f;
  f.truth = truth;
  f.pixels.resize(640U * 480U);
  renderer.render(truth, seed, f.pixels.data(), 640);
  return f;
}

}  // namespace visnav::test
