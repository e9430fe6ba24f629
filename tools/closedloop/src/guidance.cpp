#include "visnav/closedloop/guidance.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::closedloop {
namespace {

using Mat6x6 = Eigen::Matrix<double, 6, 6>;

constexpr double kAccelNoise = 2e-3;         ///< m/s^2: unmodelled acceleration (thrust errors, none here)
constexpr double kFarDistanceSigma = 0.15;   ///< relative: far range's distance (fsw/farrange/README.md)
constexpr double kFarDirectionSigma = 2e-3;  ///< rad
constexpr double kPoseFloorSigma = 0.01;     ///< m: floor under the tracker's position covariance
constexpr double kGateChi2 = 25.0;           ///< 3 dof
constexpr int kReinitAfterRejections = 10;
constexpr double kRateFilterGain = 0.05;  ///< per frame: low-pass of the target's rate from poses
constexpr double kMaxTargetRate = 0.2;    ///< rad/s: a faster difference between poses is a jump

Vec3 clipNorm(const Vec3& v, double max_norm) {
  const double n = v.norm();
  return n > max_norm && n > 0.0 ? Vec3(v * (max_norm / n)) : v;
}

}  // namespace

const char* toString(Phase phase) { return phase == Phase::kNearRange ? "near_range_6dof" : "line_of_sight"; }

void VisnavEstimator::fuse(const Vec3& z_w, const Mat3& R) {
  const Vec3 y = z_w - m_est.p_w;
  const Mat3 S = m_P.topLeftCorner<3, 3>() + R;
  const Mat3 S_inv = S.inverse();
  if (y.dot(S_inv * y) > kGateChi2) {
    ++m_rejected;
    if (++m_rejections_in_a_row < kReinitAfterRejections) return;
    // The estimate has lost the measurements for good: restart from them, keep the velocity.
    m_est.p_w = z_w;
    m_P.topLeftCorner<3, 3>() = R;
    m_P.topRightCorner<3, 3>().setZero();
    m_P.bottomLeftCorner<3, 3>().setZero();
    m_rejections_in_a_row = 0;
    return;
  }
  m_rejections_in_a_row = 0;
  const Eigen::Matrix<double, 6, 3> K = m_P.leftCols<3>() * S_inv;
  m_est.p_w += K.topRows<3>() * y;
  m_est.v_w += K.bottomRows<3>() * y;
  Mat6x6 I_KH = Mat6x6::Identity();
  I_KH.leftCols<3>() -= K;
  m_P = I_KH * m_P * I_KH.transpose() + K * R * K.transpose();  // Joseph form
}

void VisnavEstimator::update(const visnav_solution& sol, const Mat3& R_w_c, const Vec3& accel_w,
                             double dt_s) {
  if (m_est.position_valid) {
    m_est.p_w += m_est.v_w * dt_s + 0.5 * accel_w * dt_s * dt_s;
    m_est.v_w += accel_w * dt_s;
    Mat6x6 F = Mat6x6::Identity();
    F.topRightCorner<3, 3>() = Mat3::Identity() * dt_s;
    Mat6x6 Q = Mat6x6::Zero();
    const double q = kAccelNoise * kAccelNoise;
    Q.topLeftCorner<3, 3>() = Mat3::Identity() * q * dt_s * dt_s * dt_s * dt_s / 4.0;
    Q.topRightCorner<3, 3>() = Mat3::Identity() * q * dt_s * dt_s * dt_s / 2.0;
    Q.bottomLeftCorner<3, 3>() = Q.topRightCorner<3, 3>();
    Q.bottomRightCorner<3, 3>() = Mat3::Identity() * q * dt_s * dt_s;
    m_P = F * m_P * F.transpose() + Q;
  }
  const bool near =
      sol.mode == VISNAV_MODE_NEAR_RANGE && sol.pose_valid != 0 && sol.track_status != VISNAV_TRACK_LOST;
  Vec3 z = Vec3::Zero();
  Mat3 R = Mat3::Identity();
  if (near) {
    const Vec3 t_c_m(sol.position_m[0], sol.position_m[1], sol.position_m[2]);
    const Eigen::Quaterniond q(sol.quaternion[0], sol.quaternion[1], sol.quaternion[2], sol.quaternion[3]);
    Mat3 cov_t;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) cov_t(i, j) = sol.covariance[(3 + i) * 6 + 3 + j];
    z = -(R_w_c * t_c_m);
    R = R_w_c * cov_t * R_w_c.transpose() + Mat3::Identity() * kPoseFloorSigma * kPoseFloorSigma;
    // Target attitude; of the plate's two symmetric twins the one closest to the last (no 180 deg jumps).
    Mat3 R_w_m = R_w_c * q.normalized().toRotationMatrix();
    if (m_have_last_attitude) {
      const Mat3 twin = R_w_m * Vec3(-1.0, -1.0, 1.0).asDiagonal();
      if (logSo3(twin * m_last_R_w_m.transpose()).norm() < logSo3(R_w_m * m_last_R_w_m.transpose()).norm())
        R_w_m = twin;
      const Vec3 rate = logSo3(R_w_m * m_last_R_w_m.transpose()) / dt_s;
      if (rate.norm() < kMaxTargetRate && m_near_in_a_row > 0)
        m_est.target_rate_w += kRateFilterGain * (rate - m_est.target_rate_w);
    }
    m_last_R_w_m = R_w_m;
    m_have_last_attitude = true;
    m_est.R_w_m = R_w_m;
    m_est.attitude_valid = true;
    // Far range's distance can be tens of per cent off; the first pose replaces what it left.
    if (m_near_in_a_row == 0 && m_est.position_valid) {
      m_est.p_w = z;
      m_P.topLeftCorner<3, 3>() = R;
      m_P.topRightCorner<3, 3>().setZero();
      m_P.bottomLeftCorner<3, 3>().setZero();
    }
    ++m_near_in_a_row;
  } else {
    m_near_in_a_row = 0;
    m_est.attitude_valid = false;
    if (sol.far_valid == 0) return;
    const Vec3 u = -(R_w_c * Vec3(sol.far_direction_c[0], sol.far_direction_c[1], sol.far_direction_c[2]));
    const double d = std::max(sol.far_distance_m, 1.0);
    z = u * d;
    const double sa = kFarDistanceSigma * d;
    const double sc = kFarDirectionSigma * d;
    R = sa * sa * u * u.transpose() + sc * sc * (Mat3::Identity() - u * u.transpose());
  }
  if (!m_est.position_valid) {
    m_est.p_w = z;
    m_est.v_w.setZero();  // the chaser starts station-keeping: relative velocity 0 +- 0.1 m/s
    m_P.setZero();
    m_P.topLeftCorner<3, 3>() = R;
    m_P.bottomRightCorner<3, 3>() = Mat3::Identity() * 0.01;
    m_est.position_valid = true;
    return;
  }
  fuse(z, R);
}

Command Guidance::command(const RelativeEstimate& est, bool near_ok, const Mat3& R_w_c, const Vec3& omega_w) {
  Command cmd;
  if (!est.position_valid) {  // nothing seen yet: stop turning, no thrust
    cmd.rate_w = Vec3::Zero();
    return cmd;
  }
  (void)omega_w;
  m_phase = near_ok && est.attitude_valid ? Phase::kNearRange : Phase::kLineOfSight;
  Mat3 R_wanted;
  Vec3 rate_ff = Vec3::Zero();
  Vec3 v_wanted;
  if (m_phase == Phase::kLineOfSight) {
    // Close along the line of sight to the stage range; any sideways velocity is damped.
    const double d = est.p_w.norm();
    const Vec3 u = est.p_w / d;
    const double closing =
        std::clamp(m_p.far_gain_1_s * (d - m_p.stage_range_m), -m_p.far_speed_max_m_s, m_p.far_speed_max_m_s);
    v_wanted = -u * closing;
    R_wanted = lookAt(est.p_w, R_w_c.col(0));
  } else {
    // 6-DOF: to the hold point on the face normal, moving with the tumbling target.
    const Vec3 hold = est.R_w_m * Vec3(0.0, 0.0, m_p.hold_distance_m);
    const Vec3 hold_velocity = est.target_rate_w.cross(hold);
    v_wanted = hold_velocity + clipNorm(m_p.near_gain_1_s * (hold - est.p_w), m_p.near_speed_max_m_s);
    R_wanted = lookAt(est.p_w, est.R_w_m.col(0));
    rate_ff = est.target_rate_w;
  }
  cmd.accel_w = clipNorm(m_p.velocity_gain_1_s * (v_wanted - est.v_w), m_p.accel_max_m_s2);
  cmd.rate_w = rate_ff + m_p.attitude_gain_1_s * logSo3(R_wanted * R_w_c.transpose());
  return cmd;
}

}  // namespace visnav::closedloop
