#include "visnav/geometry/pose.hpp"

#include <cmath>

namespace visnav {

Mat3 rotationFromYpr(const YawPitchRoll& ypr) {
  const double cy = std::cos(ypr.yaw_rad), sy = std::sin(ypr.yaw_rad);
  const double cp = std::cos(ypr.pitch_rad), sp = std::sin(ypr.pitch_rad);
  const double cr = std::cos(ypr.roll_rad), sr = std::sin(ypr.roll_rad);
  Mat3 r;
  r << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,   //
      -sp, cp * sr, cp * cr;
  return r;
}

YawPitchRoll yprFromRotation(const Mat3& r) {
  YawPitchRoll ypr;
  const double sp = std::fmax(-1.0, std::fmin(1.0, -r(2, 0)));
  ypr.pitch_rad = std::asin(sp);
  if (std::fabs(sp) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw -/+ roll is observable; report roll = 0.
    ypr.roll_rad = 0.0;
    ypr.yaw_rad = std::atan2(-r(0, 1), r(1, 1));
  } else {
    ypr.yaw_rad = std::atan2(r(1, 0), r(0, 0));
    ypr.roll_rad = std::atan2(r(2, 1), r(2, 2));
  }
  return ypr;
}

Mat3 skew(const Vec3& v) {
  Mat3 s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

Mat3 expSo3(const Vec3& omega) {
  const double theta2 = omega.squaredNorm();
  const Mat3 w = skew(omega);
  if (theta2 < 1e-16) return Mat3::Identity() + w + 0.5 * w * w;
  const double theta = std::sqrt(theta2);
  return Mat3::Identity() + (std::sin(theta) / theta) * w + ((1.0 - std::cos(theta)) / theta2) * w * w;
}

Mat3 rotationBetween(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double s = axis.norm();
  if (s < 1e-15) return Mat3::Identity();
  return expSo3(axis / s * std::atan2(s, a.dot(b)));
}

Vec3 logSo3(const Mat3& r) {
  // Via the quaternion: well conditioned for every angle including pi.
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

Pose Pose::boxPlus(const Vec6& delta) const {
  Pose out;
  out.R_c_m = expSo3(delta.head<3>()) * R_c_m;
  out.t_c_m = t_c_m + delta.tail<3>();
  return out;
}

Vec6 Pose::boxMinus(const Pose& other) const {
  Vec6 d;
  d.head<3>() = logSo3(other.R_c_m * R_c_m.transpose());
  d.tail<3>() = other.t_c_m - t_c_m;
  return d;
}

Pose Pose::fromYpr(const YawPitchRoll& ypr, const Vec3& t) {
  Pose p;
  p.R_c_m = rotationFromYpr(ypr);
  p.t_c_m = t;
  return p;
}

Pose Pose::fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t) {
  Pose p;
  p.R_c_m = q.normalized().toRotationMatrix();
  p.t_c_m = t;
  return p;
}

}  // namespace visnav
