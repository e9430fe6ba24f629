// Rigid pose T_c_m (model frame -> camera frame), rotations and their parametrisations.
// Conventions (DIN 9300 yaw-pitch-roll, quaternion order, perturbation side): CONVENTIONS.md.
#pragma once

#include <Eigen/Geometry>

#include "visnav/core/types.hpp"

namespace visnav {

/// Yaw (psi, about z), pitch (theta, about y'), roll (phi, about x''), radians: R = Rz(yaw) Ry(pitch)
/// Rx(roll).
struct YawPitchRoll {
  double yaw_rad = 0.0;
  double pitch_rad = 0.0;
  double roll_rad = 0.0;
};

Mat3 rotationFromYpr(const YawPitchRoll& ypr);
/// Inverse of rotationFromYpr. At pitch = +-90 deg (gimbal lock) roll is set to 0 and yaw absorbs it.
YawPitchRoll yprFromRotation(const Mat3& rotation);

/// SO(3) exponential / logarithm (rotation vector, radians), stable near zero and near pi.
Mat3 expSo3(const Vec3& omega);
Vec3 logSo3(const Mat3& rotation);
Mat3 skew(const Vec3& v);
/// The rotation taking unit vector a onto unit vector b (about their common normal; identity if parallel).
Mat3 rotationBetween(const Vec3& a, const Vec3& b);

struct Pose {
  Mat3 R_c_m = Mat3::Identity();  ///< rotates model-frame vectors into the camera frame
  Vec3 t_c_m = Vec3::Zero();      ///< model origin expressed in the camera frame [m]

  Vec3 transform(const Vec3& p_m) const { return R_c_m * p_m + t_c_m; }

  /// 6-vector update delta = (omega [rad], dt [m]); rotation is perturbed on the left:
  /// R <- exp(omega) R, t <- t + dt. No Euler angles, so no singularity can stall the solver.
  Pose boxPlus(const Vec6& delta) const;
  /// delta such that other == this->boxPlus(delta).
  Vec6 boxMinus(const Pose& other) const;

  Eigen::Quaterniond quaternion() const { return Eigen::Quaterniond(R_c_m); }
  YawPitchRoll ypr() const { return yprFromRotation(R_c_m); }

  static Pose fromYpr(const YawPitchRoll& ypr, const Vec3& t_c_m);
  static Pose fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t_c_m);
};

}  // namespace visnav
