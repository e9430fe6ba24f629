#include "visnav/closedloop/chaser.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::closedloop {
namespace {

Vec3 clipNorm(const Vec3& v, double max_norm) {
  const double n = v.norm();
  return n > max_norm && n > 0.0 ? Vec3(v * (max_norm / n)) : v;
}

}  // namespace

void Chaser::step(const Command& command, double dt_s) {
  const Vec3 a = clipNorm(command.accel_w, m_limits.accel_max_m_s2);
  // Exact for a constant acceleration over the step.
  m_state.p_w += m_state.v_w * dt_s + 0.5 * a * dt_s * dt_s;
  m_state.v_w += a * dt_s;
  m_state.delta_v_m_s += a.norm() * dt_s;
  // The body rate follows the commanded one as fast as the angular acceleration allows.
  const Vec3 rate_cmd = clipNorm(command.rate_w, m_limits.rate_max_rad_s);
  m_state.omega_w += clipNorm(rate_cmd - m_state.omega_w, m_limits.angular_accel_max_rad_s2 * dt_s);
  m_state.R_w_c = expSo3(m_state.omega_w * dt_s) * m_state.R_w_c;
}

Pose relativePose(const ChaserState& chaser, const Mat3& R_w_m) {
  Pose pose;
  pose.R_c_m = chaser.R_w_c.transpose() * R_w_m;
  pose.t_c_m = -(chaser.R_w_c.transpose() * chaser.p_w);
  return pose;
}

Mat3 lookAt(const Vec3& p_w, const Vec3& x_hint_w) {
  const Vec3 z = (-p_w).normalized();
  Vec3 x = x_hint_w - x_hint_w.dot(z) * z;
  if (x.norm() < 1e-6) x = z.unitOrthogonal();  // hint along the boresight: any x will do
  x.normalize();
  Mat3 R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

Mat3 holdRelativeAttitude() { return Vec3(1.0, -1.0, -1.0).asDiagonal(); }

double attitudeErrorModSymmetry(const Mat3& R_c_m, const Mat3& R_c_m_wanted) {
  const Mat3 twin = R_c_m * Vec3(-1.0, -1.0, 1.0).asDiagonal();  // 180 deg about z_m
  return std::min(logSo3(R_c_m * R_c_m_wanted.transpose()).norm(),
                  logSo3(twin * R_c_m_wanted.transpose()).norm());
}

}  // namespace visnav::closedloop
