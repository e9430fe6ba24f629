// The truth side of the loop: the chaser (camera carrier) as a double integrator with an acceleration
// limit and a rate-limited attitude, the target tumbling about a world-fixed axis, and the true relative
// pose T_c_m the renderer draws. World frame W: inertial, origin at the target's centre (model origin).
#pragma once

#include "visnav/core/types.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::closedloop {

struct ChaserLimits {
  double accel_max_m_s2 = 0.05;
  double rate_max_rad_s = 0.035;
  double angular_accel_max_rad_s2 = 0.0087;
};

/// What the guidance asks for, held over one frame: acceleration and angular rate, world frame.
struct Command {
  Vec3 accel_w = Vec3::Zero();
  Vec3 rate_w = Vec3::Zero();
};

struct ChaserState {
  Vec3 p_w = Vec3::Zero();  ///< camera centre [m]
  Vec3 v_w = Vec3::Zero();  ///< [m/s]
  Mat3 R_w_c = Mat3::Identity();
  Vec3 omega_w = Vec3::Zero();  ///< body rate, world frame [rad/s]
  double delta_v_m_s = 0.0;     ///< integral of |acceleration| dt
};

class Chaser {
 public:
  Chaser(const ChaserLimits& limits, const ChaserState& initial) : m_limits(limits), m_state(initial) {}
  /// Applies the command (clipped to the limits) for dt_s.
  void step(const Command& command, double dt_s);
  const ChaserState& state() const { return m_state; }

 private:
  ChaserLimits m_limits;
  ChaserState m_state;
};

/// The target's attitude: R_w_m(t) = exp(axis * rate * t) R_w_m0.
struct TargetMotion {
  Mat3 R_w_m0 = Mat3::Identity();
  Vec3 omega_w = Vec3::Zero();
  Mat3 attitude(double t_s) const { return expSo3(omega_w * t_s) * R_w_m0; }
};

/// True T_c_m from the chaser state and the target attitude.
Pose relativePose(const ChaserState& chaser, const Mat3& R_w_m);

/// Camera attitude looking from p_w at the target centre with the camera x axis as close as possible to
/// `x_hint_w` (the target's x axis at the hold point; the current camera x axis in far range).
Mat3 lookAt(const Vec3& p_w, const Vec3& x_hint_w);

/// The hold attitude relative to the target: camera x along model x, boresight along -z_m (facing the
/// +z face), R_c_m = diag(1, -1, -1).
Mat3 holdRelativeAttitude();

/// Angle [rad] between two attitudes, the smaller of the plate's two symmetric twins (180 deg about z_m).
double attitudeErrorModSymmetry(const Mat3& R_c_m, const Mat3& R_c_m_wanted);

}  // namespace visnav::closedloop
