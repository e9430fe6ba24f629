#include "visnav/navigation/pose_filter.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace visnav::nav {

namespace {

bool allFinite(const Vec3& v) { return v.allFinite(); }

/// Positive definite (and finite) by an LDLT factorisation; the factor is reused for the solve.
template <int N>
bool factorPositive(const Eigen::Matrix<double, N, N>& s, Eigen::LDLT<Eigen::Matrix<double, N, N>>& ldlt) {
  if (!s.allFinite()) return false;
  ldlt.compute(s);
  return ldlt.info() == Eigen::Success && ldlt.isPositive() && ldlt.vectorD().minCoeff() > 0.0;
}

/// Discrete process noise of a white acceleration with spectral density q [unit^2/s^3] acting on a
/// (value, rate) pair over dt: q [dt^3/3, dt^2/2; dt^2/2, dt] per axis.
void addWhiteAcceleration(Mat12& p, int value, int rate, double q, double dt) {
  const double dt2 = dt * dt;
  for (int i = 0; i < 3; ++i) {
    p(value + i, value + i) += q * dt2 * dt / 3.0;
    p(value + i, rate + i) += q * dt2 / 2.0;
    p(rate + i, value + i) += q * dt2 / 2.0;
    p(rate + i, rate + i) += q * dt;
  }
}

}  // namespace

Mat3 leftJacobianSo3(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const Mat3 w = skew(phi);
  if (theta2 < 1e-12) return Mat3::Identity() + 0.5 * w + (1.0 / 6.0) * w * w;
  const double theta = std::sqrt(theta2);
  return Mat3::Identity() + ((1.0 - std::cos(theta)) / theta2) * w +
         ((theta - std::sin(theta)) / (theta2 * theta)) * w * w;
}

LoadError PoseFilter::init(const PoseFilterParams& params) {
  if (const char* problem = params.crossCheck()) return LoadError::failure(std::string("filter: ") + problem);
  m_params = params;
  reset();
  return LoadError::success();
}

void PoseFilter::reset() {
  m_initialised = false;
  m_attitude_known = false;
  m_pose = Pose{};
  m_velocity.setZero();
  m_angular_velocity.setZero();
  m_covariance.setIdentity();
  m_consecutive_rejections = 0;
}

Status PoseFilter::initialise(const Pose& pose, const Mat6& pose_covariance) {
  Eigen::LDLT<Mat6> ldlt;
  if (!pose.R_c_m.allFinite() || !allFinite(pose.t_c_m) ||
      !factorPositive<6>(0.5 * (pose_covariance + pose_covariance.transpose()), ldlt))
    return Status::kInvalidArgument;
  m_pose = pose;
  m_velocity.setZero();
  m_angular_velocity.setZero();
  m_covariance.setZero();
  m_covariance.topLeftCorner<6, 6>() = 0.5 * (pose_covariance + pose_covariance.transpose());
  const double sv = m_params.initial_velocity_sigma_m_s;
  const double sw = m_params.initial_angular_velocity_sigma_deg_s * kRadPerDeg;
  m_covariance.block<3, 3>(kVelocity, kVelocity) = Mat3::Identity() * sv * sv;
  m_covariance.block<3, 3>(kAngularVelocity, kAngularVelocity) = Mat3::Identity() * sw * sw;
  m_initialised = true;
  m_attitude_known = true;
  m_consecutive_rejections = 0;
  return Status::kOk;
}

Status PoseFilter::initialisePosition(const Vec3& t_c_m, const Mat3& position_covariance) {
  Eigen::LDLT<Mat3> ldlt;
  if (!allFinite(t_c_m) ||
      !factorPositive<3>(0.5 * (position_covariance + position_covariance.transpose()), ldlt))
    return Status::kInvalidArgument;
  m_pose = Pose{};
  m_pose.t_c_m = t_c_m;
  m_velocity.setZero();
  m_angular_velocity.setZero();
  m_covariance.setZero();
  // Attitude unknown: a nominal +-pi per axis keeps the matrix well defined; nothing couples it to position.
  m_covariance.block<3, 3>(kAttitude, kAttitude) = Mat3::Identity() * kPi * kPi;
  m_covariance.block<3, 3>(kPosition, kPosition) =
      0.5 * (position_covariance + position_covariance.transpose());
  const double sv = m_params.initial_velocity_sigma_m_s;
  const double sw = m_params.initial_angular_velocity_sigma_deg_s * kRadPerDeg;
  m_covariance.block<3, 3>(kVelocity, kVelocity) = Mat3::Identity() * sv * sv;
  m_covariance.block<3, 3>(kAngularVelocity, kAngularVelocity) = Mat3::Identity() * sw * sw;
  m_initialised = true;
  m_attitude_known = false;
  m_consecutive_rejections = 0;
  return Status::kOk;
}

Status PoseFilter::predict(double dt_s) {
  if (!m_initialised || !(dt_s > 0.0) || !(dt_s <= m_params.max_prediction_s))
    return Status::kInvalidArgument;
  const Vec3 rotation = m_angular_velocity * dt_s;
  // Error-state transition, first order (left perturbation):
  //   omega+ = exp(w dt) omega + J_l(w dt) dt dw,   dt+ = dt + dt_s dv,   dw+ = dw,   dv+ = dv.
  Mat12 f = Mat12::Identity();
  const Mat3 step = expSo3(rotation);
  f.block<3, 3>(kAttitude, kAttitude) = step;
  f.block<3, 3>(kAttitude, kAngularVelocity) = leftJacobianSo3(rotation) * dt_s;
  f.block<3, 3>(kPosition, kVelocity) = Mat3::Identity() * dt_s;
  m_covariance = f * m_covariance * f.transpose();
  const double qa = m_params.angular_accel_noise_deg * kRadPerDeg;
  addWhiteAcceleration(m_covariance, kAttitude, kAngularVelocity, qa * qa, dt_s);
  addWhiteAcceleration(m_covariance, kPosition, kVelocity,
                       m_params.linear_accel_noise * m_params.linear_accel_noise, dt_s);
  symmetrize();
  m_pose.R_c_m = step * m_pose.R_c_m;
  m_pose.t_c_m += m_velocity * dt_s;
  return Status::kOk;
}

FilterUpdate PoseFilter::gateResult(FilterUpdate result, double gate) {
  result.accepted = result.nis <= gate;
  if (result.accepted) {
    ++m_accepted;
    m_consecutive_rejections = 0;
  } else {
    ++m_rejected;
    ++m_consecutive_rejections;
  }
  return result;
}

FilterUpdate PoseFilter::update(const Pose& measured, const Mat6& covariance) {
  FilterUpdate result;
  result.dof = 6;
  const Mat6 r = 0.5 * (covariance + covariance.transpose());
  Eigen::LDLT<Mat6> r_factor;
  if (!m_initialised || !measured.R_c_m.allFinite() || !allFinite(measured.t_c_m) ||
      !factorPositive<6>(r, r_factor)) {
    result.status = Status::kInvalidArgument;
    return result;
  }
  if (!m_attitude_known) {
    // First attitude: fuse the position, then adopt the measured attitude with its own uncertainty.
    result = updatePosition(measured.t_c_m, r.bottomRightCorner<3, 3>());
    if (!result.accepted) return result;
    m_pose.R_c_m = measured.R_c_m;
    m_covariance.middleRows<3>(kAttitude).setZero();
    m_covariance.middleCols<3>(kAttitude).setZero();
    m_covariance.middleRows<3>(kAngularVelocity).setZero();
    m_covariance.middleCols<3>(kAngularVelocity).setZero();
    m_covariance.block<3, 3>(kAttitude, kAttitude) = r.topLeftCorner<3, 3>();
    const double sw = m_params.initial_angular_velocity_sigma_deg_s * kRadPerDeg;
    m_covariance.block<3, 3>(kAngularVelocity, kAngularVelocity) = Mat3::Identity() * sw * sw;
    m_angular_velocity.setZero();
    m_attitude_known = true;
    return result;
  }
  return correct<6>(kAttitude, m_pose.boxMinus(measured), r, m_params.pose_gate_chi2, result);
}

template <int M>
FilterUpdate PoseFilter::correct(int first, const Eigen::Matrix<double, M, 1>& y,
                                 const Eigen::Matrix<double, M, M>& r, double gate, FilterUpdate result) {
  const Eigen::Matrix<double, M, M> s = m_covariance.template block<M, M>(first, first) + r;
  Eigen::LDLT<Eigen::Matrix<double, M, M>> s_factor;
  if (!factorPositive<M>(s, s_factor)) {
    result.status = Status::kInvalidArgument;
    return result;
  }
  result.nis = y.dot(s_factor.solve(y));
  result = gateResult(result, gate);
  if (!result.accepted) return result;
  const Eigen::Matrix<double, 12, M> gain =
      s_factor.solve(m_covariance.template middleCols<M>(first).transpose()).transpose();
  Mat12 i_kh = Mat12::Identity();
  i_kh.template middleCols<M>(first) -= gain;
  // Joseph form: stays symmetric positive semi-definite whatever the rounding of the gain.
  m_covariance = i_kh * m_covariance * i_kh.transpose() + gain * r * gain.transpose();
  symmetrize();
  Vec12 dx = gain * y;
  if (!m_attitude_known) dx.template segment<3>(kAttitude).setZero();  // nothing to correct yet
  inject(dx);
  return result;
}

FilterUpdate PoseFilter::updatePosition(const Vec3& t_c_m, const Mat3& covariance) {
  FilterUpdate result;
  result.dof = 3;
  const Mat3 r = 0.5 * (covariance + covariance.transpose());
  Eigen::LDLT<Mat3> r_factor;
  if (!m_initialised || !allFinite(t_c_m) || !factorPositive<3>(r, r_factor)) {
    result.status = Status::kInvalidArgument;
    return result;
  }
  return correct<3>(kPosition, Vec3(t_c_m - m_pose.t_c_m), r, m_params.position_gate_chi2, result);
}

FilterUpdate PoseFilter::updateFarRange(const Vec3& direction_c, double distance_m) {
  FilterUpdate result;
  result.dof = 3;
  Vec3 t;
  Mat3 c;
  const double predicted_range = m_initialised ? m_pose.t_c_m.norm() : 0.0;
  if (!positionFromFarRange(direction_c, distance_m, m_params.far_direction_sigma_deg * kRadPerDeg,
                            m_params.far_distance_sigma_rel, t, c, predicted_range)) {
    result.status = Status::kInvalidArgument;
    return result;
  }
  return updatePosition(t, c);
}

void PoseFilter::inject(const Vec12& dx) {
  // The reset Jacobian of the attitude error (J_r^-1 of the correction: a second-order effect) is neglected,
  // as usual for the small corrections of a tracked target.
  m_pose = m_pose.boxPlus(dx.head<6>());
  m_angular_velocity += dx.segment<3>(kAngularVelocity);
  m_velocity += dx.segment<3>(kVelocity);
}

void PoseFilter::symmetrize() { m_covariance = 0.5 * (m_covariance + m_covariance.transpose()).eval(); }

bool positionFromFarRange(const Vec3& direction_c, double distance_m, double direction_sigma_rad,
                          double distance_sigma_rel, Vec3& t_c_m, Mat3& covariance, double sigma_range_m) {
  if (!allFinite(direction_c) || !std::isfinite(distance_m) || !(distance_m > 0.0) ||
      !(direction_sigma_rad > 0.0) || !(distance_sigma_rel > 0.0))
    return false;
  const double norm = direction_c.norm();
  if (!(norm > 0.0)) return false;
  const Vec3 u = direction_c / norm;
  if (!(u.z() > 1e-6)) return false;
  t_c_m = u * (distance_m / u.z());
  const double range = sigma_range_m > 0.0 ? sigma_range_m : t_c_m.norm();
  const double along = range * distance_sigma_rel;
  const double across = range * direction_sigma_rad;
  const Mat3 uu = u * u.transpose();
  covariance = along * along * uu + across * across * (Mat3::Identity() - uu);
  return true;
}

}  // namespace visnav::nav
