// Internals shared by the scene sources (scene.cpp: the Scene and its models; scene_draw.cpp: the seeded
// draws; scene_cases.cpp: the named field-report cases).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "visnav/campaign/scene.hpp"

namespace visnav::campaign::detail {

std::uint64_t splitmix64(std::uint64_t x);

/// Face-on (model +z towards the camera), turned about the boresight by yaw, then tilted about an axis in
/// the image plane at tilt_dir.
Mat3 baseAttitude(double yaw_deg, double tilt_deg, double tilt_dir_deg);

CameraIntrinsics makeCamera(int w, int h, double f, double cx, double cy, double k1, double k2 = 0.0);

template <typename... Args>
std::string fmt(const char* format, Args... args) {
  char buf[128];
  std::snprintf(buf, sizeof(buf), format, args...);
  return buf;
}

int capFrames(int drawn, int max_frames);

/// The gradient background of `s` placed on the target at `pose`: contrast +contrast_plus -> 0 ->
/// -contrast_minus along the direction `angle_rad`, over 0.7 of the target's radius, softness
/// `softness_rel` of that radius (solveGradient).
void applyGradient(Scene& s, const Pose& pose, double contrast_plus, double contrast_minus, double angle_rad,
                   double softness_rel);

/// Symmetries and gamma: what every scene derives from its model and camera.
void finishScene(Scene& s);

}  // namespace visnav::campaign::detail
