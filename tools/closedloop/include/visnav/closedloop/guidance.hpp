// The guidance and its own relative-state estimate. Input per frame: either visnav's solution (the only
// relative information) with the chaser's own attitude, rate and commanded acceleration (what its star
// tracker, gyros and thrusters know), or, for the reference run, the true relative state. Output: a Command.
#pragma once

#include <cstdint>

#include "visnav/closedloop/chaser.hpp"
#include "visnav/closedloop/scenario.hpp"
#include "visnav/visnav.h"

namespace visnav::closedloop {

/// What the guidance believes: chaser position and velocity relative to the target (world frame), and
/// once near range has a pose, the target's attitude and rate.
struct RelativeEstimate {
  bool position_valid = false;
  Vec3 p_w = Vec3::Zero();
  Vec3 v_w = Vec3::Zero();
  bool attitude_valid = false;
  Mat3 R_w_m = Mat3::Identity();
  Vec3 target_rate_w = Vec3::Zero();
};

/// Translational Kalman filter (world frame, constant velocity driven by the commanded acceleration) over
/// visnav's measurements: far range (direction, distance) or the near-range pose; plus the target attitude
/// from the pose and its rate from successive poses. Fixed-size Eigen.
class VisnavEstimator {
 public:
  /// One frame: propagate with the acceleration commanded over the last frame, then fuse `sol`.
  void update(const visnav_solution& sol, const Mat3& R_w_c, const Vec3& accel_w, double dt_s);
  const RelativeEstimate& estimate() const { return m_est; }
  int nearFramesInARow() const { return m_near_in_a_row; }
  std::uint64_t rejected() const { return m_rejected; }

 private:
  void fuse(const Vec3& z_w, const Mat3& R);
  RelativeEstimate m_est;
  Eigen::Matrix<double, 6, 6> m_P = Eigen::Matrix<double, 6, 6>::Identity();
  int m_near_in_a_row = 0;
  int m_rejections_in_a_row = 0;
  std::uint64_t m_rejected = 0;
  bool m_have_last_attitude = false;
  Mat3 m_last_R_w_m = Mat3::Identity();
};

enum class Phase : std::uint8_t { kLineOfSight = 0, kNearRange = 1 };
const char* toString(Phase phase);

class Guidance {
 public:
  explicit Guidance(const ScenarioParams& params) : m_p(params) {}
  /// `near_ok`: near range has delivered poses (the 6-DOF phase may run).
  Command command(const RelativeEstimate& est, bool near_ok, const Mat3& R_w_c, const Vec3& omega_w);
  Phase phase() const { return m_phase; }

 private:
  ScenarioParams m_p;
  Phase m_phase = Phase::kLineOfSight;
};

}  // namespace visnav::closedloop
