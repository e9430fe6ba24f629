// Shared by the acquisition tests, the sweep and the benchmark: the two targets (the paper's plate, the
// shaded box), a perturbed far-range cue, attitude error modulo the target's symmetries, and one acquisition
// run on rendered frames of a static target.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <vector>

#include "../nearrange/tracker_fixture.hpp"
#include "visnav/acquisition/acquisition.hpp"

namespace visnav::test {

enum class Target { kPlate, kBox };

struct Scene {
  PolygonModel model;
  synthetic::RenderOptions render;
  std::vector<Mat3> symmetries;  ///< model-frame rotations S with model(S p) == model(p)
};

inline Scene makeScene(Target target) {
  Scene s;
  s.symmetries.push_back(Mat3::Identity());
  s.symmetries.push_back(Eigen::AngleAxisd(kPi, Vec3::UnitZ()).toRotationMatrix());
  if (target == Target::kPlate) {
    s.model = makeRectanglePlate(2.3, 1.8);
  } else {
    s.model = makeBox(0.8, 0.6, 0.5);
    s.symmetries.push_back(Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix());
    s.symmetries.push_back(Eigen::AngleAxisd(kPi, Vec3::UnitY()).toRotationMatrix());
    // Sun shading (as in the tracker tests): with one flat brightness the inner edges would carry no
    // contrast.
    s.render.shading.enabled = true;
    s.render.shading.sun_dir_c = Vec3(0.3, 0.5, 1.0);
  }
  return s;
}

/// Smallest attitude error [deg] over the poses that look identical (the target's symmetries).
inline double attitudeErrorDeg(const Scene& scene, const Pose& truth, const Pose& estimate) {
  double best = 1e9;
  for (const Mat3& s : scene.symmetries)
    best = std::min(best, logSo3(estimate.R_c_m * (truth.R_c_m * s).transpose()).norm() * kDegPerRad);
  return best;
}

/// A plate-style attitude: facing the camera (roll 180 deg), spun by `spin` about the boresight, then tilted
/// by `tilt` (the obliquity) about the image-plane axis at angle `tilt_axis`.
inline Mat3 tiltedAttitude(double tilt_deg, double tilt_axis_deg, double spin_deg) {
  const Vec3 axis(std::cos(tilt_axis_deg * kRadPerDeg), std::sin(tilt_axis_deg * kRadPerDeg), 0.0);
  return (Eigen::AngleAxisd(tilt_deg * kRadPerDeg, axis) *
          Eigen::AngleAxisd(spin_deg * kRadPerDeg, Vec3::UnitZ()) * Eigen::AngleAxisd(kPi, Vec3::UnitX()))
      .toRotationMatrix();
}

/// The far-range cue for `truth`: direction rotated by `direction_error_deg` (about an image-plane axis at
/// `error_axis_deg`), distance scaled by (1 + distance_error_rel).
inline FarRangeSolution perturbedCue(const Pose& truth, double direction_error_deg, double error_axis_deg,
                                     double distance_error_rel) {
  const Vec3 axis(std::cos(error_axis_deg * kRadPerDeg), std::sin(error_axis_deg * kRadPerDeg), 0.0);
  FarRangeSolution cue;
  cue.valid = true;
  cue.direction_c = Eigen::AngleAxisd(direction_error_deg * kRadPerDeg, axis) * truth.t_c_m.normalized();
  cue.distance_m = truth.t_c_m.z() * (1.0 + distance_error_rel);
  return cue;
}

struct AcquisitionRun {
  acq::AcquisitionResult last;
  int steps = 0;
  double step_sum_us = 0.0;  ///< with a clock: wall time of the step() calls
  double step_max_us = 0.0;
  double attitude_error_deg = 0.0;
  double position_error_m = 0.0;
  bool succeeded() const { return last.state == acq::AcquisitionState::kSucceeded; }
};

/// Frames of a static target (noise differs per frame; `frames` distinct renders are cycled).
inline std::vector<RenderedFrame> renderStatic(synthetic::Renderer& renderer, const Pose& truth, int frames,
                                               std::uint64_t seed) {
  std::vector<RenderedFrame> out;
  for (int i = 0; i < frames; ++i)
    out.push_back(renderFrame(renderer, truth, seed + static_cast<std::uint64_t>(i)));
  return out;
}

inline AcquisitionRun runAcquisition(acq::Acquisition& acquisition, const Scene& scene,
                                     const std::vector<RenderedFrame>& frames, const FarRangeSolution& cue,
                                     int max_steps = 60, MonotonicClockNs clock = nullptr) {
  AcquisitionRun run;
  acquisition.start(cue);
  for (int i = 0; i < max_steps; ++i) {
    const RenderedFrame& f = frames[static_cast<std::size_t>(i) % frames.size()];
    const std::int64_t t0 = clock != nullptr ? clock() : 0;
    acquisition.step(f.image(), static_cast<std::uint64_t>(i), run.last);
    if (clock != nullptr) {
      const double us = static_cast<double>(clock() - t0) * 1e-3;
      run.step_sum_us += us;
      run.step_max_us = std::max(run.step_max_us, us);
    }
    ++run.steps;
    if (run.last.state == acq::AcquisitionState::kSucceeded ||
        run.last.state == acq::AcquisitionState::kFailed)
      break;
  }
  const Pose& truth = frames.front().truth;
  run.attitude_error_deg = attitudeErrorDeg(scene, truth, run.last.pose);
  run.position_error_m = (run.last.pose.t_c_m - truth.t_c_m).norm();
  return run;
}

}  // namespace visnav::test
