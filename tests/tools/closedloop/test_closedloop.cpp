// visnav-closedloop's parts (tools/closedloop): the chaser's limits, the hold geometry, the estimator on
// visnav-shaped measurements, and the guidance fed the truth reaching the hold point.
#include <cmath>
#include <cstring>

#include "gtest/gtest.h"
#include "visnav/closedloop/chaser.hpp"
#include "visnav/closedloop/guidance.hpp"
#include "visnav/closedloop/simulation.hpp"

namespace {

using namespace visnav;
using namespace visnav::closedloop;

TEST(Chaser, ThrustAndRatesAreLimitedAndDeltaVCounted) {
  ChaserLimits limits;
  limits.accel_max_m_s2 = 0.05;
  limits.rate_max_rad_s = 0.02;
  limits.angular_accel_max_rad_s2 = 0.01;
  Chaser chaser(limits, ChaserState{});
  Command cmd;
  cmd.accel_w = Vec3(3.0, 4.0, 0.0);  // 5 m/s^2 asked, 0.05 given, same direction
  cmd.rate_w = Vec3(0.0, 0.0, 1.0);
  for (int i = 0; i < 100; ++i) chaser.step(cmd, 0.1);  // 10 s
  const ChaserState& s = chaser.state();
  EXPECT_NEAR(s.v_w.norm(), 0.5, 1e-12);
  EXPECT_NEAR(s.v_w.x() / s.v_w.y(), 0.75, 1e-12);
  EXPECT_NEAR(s.p_w.norm(), 0.5 * 0.05 * 100.0, 1e-9);
  EXPECT_NEAR(s.delta_v_m_s, 0.5, 1e-12);
  EXPECT_NEAR(s.omega_w.z(), 0.02, 1e-12);  // reached the rate limit (0.01 rad/s^2 for 2 s), not 1 rad/s
  // Attitude: 0.1 s steps ramping 0.001 rad/s each up to 0.02, then constant: 0.021 rad in the ramp + 0.16.
  EXPECT_NEAR(logSo3(s.R_w_c).z(), 0.0021 * 10 + 0.02 * 8.0, 1e-9);
}

TEST(HoldGeometry, LookingAtTheTargetFromTheHoldPointIsTheHoldAttitudeUpToTheTwin) {
  const Mat3 R_w_m = expSo3(Vec3(0.3, -0.2, 1.1));
  ChaserState s;
  s.p_w = R_w_m * Vec3(0.0, 0.0, 5.0);
  s.R_w_c = lookAt(s.p_w, R_w_m.col(0));
  const Pose pose = relativePose(s, R_w_m);
  EXPECT_LT(attitudeErrorModSymmetry(pose.R_c_m, holdRelativeAttitude()), 1e-9);
  EXPECT_LT((pose.t_c_m - Vec3(0.0, 0.0, 5.0)).norm(), 1e-12);  // target centre on the boresight, 5 m
  // The twin (camera rolled 180 deg) is the same view of the plate; 10 deg of roll is 10 deg.
  s.R_w_c = lookAt(s.p_w, -R_w_m.col(0));
  EXPECT_LT(attitudeErrorModSymmetry(relativePose(s, R_w_m).R_c_m, holdRelativeAttitude()), 1e-9);
  s.R_w_c = s.R_w_c * expSo3(Vec3(0.0, 0.0, 10.0 * kRadPerDeg));
  EXPECT_NEAR(attitudeErrorModSymmetry(relativePose(s, R_w_m).R_c_m, holdRelativeAttitude()) * kDegPerRad,
              10.0, 1e-9);
}

visnav_solution farSolution(const Vec3& dir_c, double distance) {
  visnav_solution sol;
  std::memset(&sol, 0, sizeof(sol));
  sol.mode = VISNAV_MODE_FAR_RANGE;
  sol.far_valid = 1;
  for (int i = 0; i < 3; ++i) sol.far_direction_c[i] = dir_c[i];
  sol.far_distance_m = distance;
  return sol;
}

TEST(VisnavEstimator, FarRangeThenNearRangeTakesOverThePosition) {
  VisnavEstimator est;
  const Mat3 R_w_c = lookAt(Vec3(0.0, 0.0, 100.0), Vec3::UnitX());
  // Far range reads 10 % long: the estimate follows it (nothing better is known).
  for (int k = 0; k < 20; ++k) est.update(farSolution(Vec3::UnitZ(), 110.0), R_w_c, Vec3::Zero(), 0.2);
  ASSERT_TRUE(est.estimate().position_valid);
  EXPECT_NEAR(est.estimate().p_w.z(), 110.0, 1.0);
  EXPECT_FALSE(est.estimate().attitude_valid);
  // A near-range pose at 100 m replaces it at once, and gives the target's attitude.
  visnav_solution sol;
  std::memset(&sol, 0, sizeof(sol));
  sol.mode = VISNAV_MODE_NEAR_RANGE;
  sol.pose_valid = 1;
  sol.track_status = VISNAV_TRACK_TRACKING;
  sol.position_m[2] = 100.0;
  sol.quaternion[1] = 1.0;  // roll 180 deg: R_c_m = diag(1, -1, -1), the plate faces the camera
  for (int i = 0; i < 6; ++i) sol.covariance[i * 7] = 1e-4;
  est.update(sol, R_w_c, Vec3::Zero(), 0.2);
  EXPECT_NEAR(est.estimate().p_w.z(), 100.0, 1e-6);
  EXPECT_EQ(est.nearFramesInARow(), 1);
  ASSERT_TRUE(est.estimate().attitude_valid);
  EXPECT_LT(logSo3(est.estimate().R_w_m.transpose() * R_w_c * holdRelativeAttitude()).norm(), 1e-9);
  // A lost frame is not a measurement.
  sol.track_status = VISNAV_TRACK_LOST;
  est.update(sol, R_w_c, Vec3::Zero(), 0.2);
  EXPECT_EQ(est.nearFramesInARow(), 0);
}

TEST(ClosedLoop, GuidanceFedTheTruthHoldsThePointOnTheShortScenario) {
  ScenarioParams p;
  ASSERT_TRUE(presetScenario("ci", std::string(VISNAV_SOURCE_DIR) + "/config", p));
  RunResult r;
  ASSERT_TRUE(runClosedLoop(p, false, r).ok);
  EXPECT_TRUE(r.arrived) << r.ended;
  EXPECT_LT(r.final_position_error_m, p.gate_position_m);
  EXPECT_LT(r.final_attitude_error_deg, p.gate_attitude_deg);
  EXPECT_GT(r.arrival_time_s, 30.0);  // 55 m at <= 2 m/s and 0.05 m/s^2 cannot take less
  EXPECT_GT(r.arrival_delta_v_m_s, 1.0);
  ScenarioParams bad;
  EXPECT_FALSE(presetScenario("100", "/x", bad));
}

}  // namespace
