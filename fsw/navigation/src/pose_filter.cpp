#include "visnav/navigation/pose_filter.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
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

/// The symmetric part 0.5 (m + m^T): what every covariance handed to the filter is taken as.
template <int N>
Eigen::Matrix<double, N, N> symmetricPart(const Eigen::Matrix<double, N, N>& m) {
  return 0.5 * (m + m.transpose());
}

Mat3 isotropic(double sigma) { return Mat3::Identity() * sigma * sigma; }

/// Prior of the angular velocity at a (re)start: zero with the configured sigma per axis.
Mat3 angularVelocityPrior(const PoseFilterParams& params) {
  return isotropic(params.initial_angular_velocity_sigma_deg_s * kRadPerDeg);
}

/// Covariance of a (re)start: `pose_block` over (omega, dt), both velocities at their configured prior,
/// nothing correlated with them.
Mat12 startCovariance(const Mat6& pose_block, const PoseFilterParams& params) {
  Mat12 p = Mat12::Zero();
  p.topLeftCorner<6, 6>() = pose_block;
  p.block<3, 3>(PoseFilter::kVelocity, PoseFilter::kVelocity) = isotropic(params.initial_velocity_sigma_m_s);
  p.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity) = angularVelocityPrior(params);
  return p;
}

/// Gives the three error-state entries from `first` the covariance `block`, uncorrelated with all others.
void setUncorrelatedBlock(Mat12& p, int first, const Mat3& block) {
  p.middleRows<3>(first).setZero();
  p.middleCols<3>(first).setZero();
  p.block<3, 3>(first, first) = block;
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
  ++m_epoch;
  ++m_track_epoch;
  m_initialised = false;
  m_attitude_known = false;
  m_pose = Pose{};
  m_velocity.setZero();
  m_angular_velocity.setZero();
  m_covariance.setIdentity();
  m_consecutive_rejections = 0;
  m_noise_scale = 1.0;
  m_nis_average = 1.0;
}

Status PoseFilter::initialise(const Pose& pose, const Mat6& pose_covariance) {
  const Mat6 p = symmetricPart<6>(pose_covariance);
  Eigen::LDLT<Mat6> ldlt;
  if (!pose.R_c_m.allFinite() || !allFinite(pose.t_c_m) || !factorPositive<6>(p, ldlt))
    return Status::kInvalidArgument;
  ++m_epoch;
  ++m_track_epoch;
  m_pose = pose;
  m_velocity.setZero();
  m_angular_velocity.setZero();
  m_covariance = startCovariance(p, m_params);
  m_initialised = true;
  m_attitude_known = true;
  m_consecutive_rejections = 0;
  return Status::kOk;
}

Status PoseFilter::initialiseFromThree(const Pose& oldest, const Mat6& oldest_covariance, const Pose& middle,
                                       const Mat6& middle_covariance, const Pose& current,
                                       const Mat6& current_covariance, double first_dt_s,
                                       double second_dt_s) {
  const Mat6 p0 = symmetricPart<6>(oldest_covariance);
  const Mat6 p1 = symmetricPart<6>(middle_covariance);
  const Mat6 p2 = symmetricPart<6>(current_covariance);
  Eigen::LDLT<Mat6> ldlt;
  const double span_s = first_dt_s + second_dt_s;
  if (!oldest.R_c_m.allFinite() || !allFinite(oldest.t_c_m) || !middle.R_c_m.allFinite() ||
      !allFinite(middle.t_c_m) || !factorPositive<6>(p0, ldlt) || !factorPositive<6>(p1, ldlt) ||
      !(first_dt_s > 0.0) || !(second_dt_s > 0.0) || !(span_s <= m_params.max_prediction_s))
    return Status::kInvalidArgument;
  const Status started = initialise(current, p2);
  if (started != Status::kOk) return started;
  // The velocity spans the outer two fits, their errors independent: cov(position, v) = P2 / T and
  // cov(v) = (P0 + P2) / T^2 over T = dt1 + dt2 (position blocks). The angular rate is not taken: the
  // attitude differences of single fits are biased beyond their covariance (case low_contrast_octagon: three
  // fits 1.3-2.5 deg 1-sigma read as 14 deg/s, and the next fit was rejected too); the filter learns it
  // from the following updates as after initialise().
  const Vec3 velocity = (current.t_c_m - oldest.t_c_m) / span_s;
  // The two steps must agree (constant velocity): their difference is noise, covariance
  // P0 / dt1^2 + P1 (1 / dt1 + 1 / dt2)^2 + P2 / dt2^2. A fit that jumped makes one step alone.
  const Vec3 step_change =
      (current.t_c_m - middle.t_c_m) / second_dt_s - (middle.t_c_m - oldest.t_c_m) / first_dt_s;
  const double middle_weight = 1.0 / first_dt_s + 1.0 / second_dt_s;
  const Mat3 q0 = p0.block<3, 3>(kPosition, kPosition);
  const Mat3 q1 = p1.block<3, 3>(kPosition, kPosition);
  const Mat3 q2 = p2.block<3, 3>(kPosition, kPosition);
  const Mat3 change_cov = q0 / (first_dt_s * first_dt_s) + q1 * (middle_weight * middle_weight) +
                          q2 / (second_dt_s * second_dt_s);
  const Mat3 velocity_cov = (q0 + q2) / (span_s * span_s);
  Eigen::LDLT<Mat3> velocity_factor;
  Eigen::LDLT<Mat3> change_factor;
  // Significant against the fits' noise and against the prior a restart at rest would keep (zero with
  // initial_velocity_sigma_m_s): below that the prior already covers it, and a few biased fits read as a
  // drift the prediction then carries through a whole search (campaign plate/107: 0.88 m/s from fits of a
  // plate closing at 0.25 m/s, lost on the next frame, never found again).
  const double prior_var = m_params.initial_velocity_sigma_m_s * m_params.initial_velocity_sigma_m_s;
  const bool significant = factorPositive<3>(velocity_cov, velocity_factor) &&
                           velocity.dot(velocity_factor.solve(velocity)) > m_params.restart_rate_chi2 &&
                           velocity.squaredNorm() / prior_var > m_params.restart_rate_chi2;
  const bool consistent = factorPositive<3>(change_cov, change_factor) &&
                          step_change.dot(change_factor.solve(step_change)) <= m_params.restart_rate_chi2;
  if (!(significant && consistent)) return Status::kOk;  // as initialise(): at rest with the prior
  m_velocity = velocity;
  Mat12 p = m_covariance;
  setUncorrelatedBlock(p, kVelocity, velocity_cov);
  // The velocity error (e2 - e0) / T correlates with the current pose error e2 (both its blocks).
  const Eigen::Matrix<double, 6, 3> cross = p2.middleCols<3>(kPosition) / span_s;
  p.block<6, 3>(0, kVelocity) = cross;
  p.block<3, 6>(kVelocity, 0) = cross.transpose();
  m_covariance = p;
  return Status::kOk;
}

std::uint32_t PoseFilter::dropInsignificantRates() {
  // A rate the filter cannot tell from zero (its NIS against zero under its own covariance at most
  // restart_rate_chi2) is the noise of the last fits, and a search predicted with it drifts away from a
  // target that did not move (campaign box/129: lost at 22.4 m with 0.8 m/s and 3.4 deg/s from fits the
  // filter had rejected, the prediction 19 m and 82 deg off 100 frames later, never found). The velocity
  // must also exceed what the start-at-rest prior covers, as in the restart (initialiseFromThree): biased
  // fits agree on a drift their covariance calls significant (campaign box/4: 7 wrong frames without this
  // test, none with it). The angular rate is not held to its prior: a 4.5 deg/s tumble the track had
  // measured, dropped, left the search 20 deg behind the target when it turned back into view (cao/52).
  if (!m_initialised) return 0U;
  const auto significant = [this](const Vec3& rate, int block) {
    const Mat3 cov = symmetricPart<3>(Mat3(m_covariance.block<3, 3>(block, block)));
    Eigen::LDLT<Mat3> factor;
    return factorPositive<3>(cov, factor) && rate.dot(factor.solve(rate)) > m_params.restart_rate_chi2;
  };
  const double prior_var = m_params.initial_velocity_sigma_m_s * m_params.initial_velocity_sigma_m_s;
  std::uint32_t dropped = 0U;
  if (!m_velocity.isZero(0.0) && !(significant(m_velocity, kVelocity) &&
                                   m_velocity.squaredNorm() > m_params.restart_rate_chi2 * prior_var)) {
    m_velocity.setZero();
    dropped |= kDroppedVelocity;
  }
  if (m_attitude_known && !m_angular_velocity.isZero(0.0) &&
      !significant(m_angular_velocity, kAngularVelocity)) {
    m_angular_velocity.setZero();
    dropped |= kDroppedAngularVelocity;
  }
  return dropped;
}

double PoseFilter::significantRangeRate() const {
  const double range_m = m_pose.t_c_m.norm();
  if (!m_initialised || !(range_m > 0.0)) return 0.0;
  const Vec3 line_of_sight = m_pose.t_c_m / range_m;
  const double rate_m_s = line_of_sight.dot(m_velocity);
  const double variance = line_of_sight.dot(m_covariance.block<3, 3>(kVelocity, kVelocity) * line_of_sight);
  return variance > 0.0 && rate_m_s * rate_m_s > m_params.restart_rate_chi2 * variance ? rate_m_s : 0.0;
}

Status PoseFilter::carryAngularVelocity(const Vec3& angular_velocity, const Mat3& covariance) {
  const Mat3 p = symmetricPart<3>(covariance);
  Eigen::LDLT<Mat3> ldlt;
  if (!m_initialised || !m_attitude_known || !allFinite(angular_velocity) || !factorPositive<3>(p, ldlt))
    return Status::kInvalidArgument;
  m_angular_velocity = angular_velocity;
  setUncorrelatedBlock(m_covariance, kAngularVelocity, p);
  return Status::kOk;
}

Status PoseFilter::scaleRates(double factor) {
  if (!m_initialised || !(factor >= 0.0 && factor <= 1.0)) return Status::kInvalidArgument;
  m_velocity *= factor;
  m_angular_velocity *= factor;
  return Status::kOk;
}

Status PoseFilter::initialisePosition(const Vec3& t_c_m, const Mat3& position_covariance) {
  const Mat3 p = symmetricPart<3>(position_covariance);
  Eigen::LDLT<Mat3> ldlt;
  if (!allFinite(t_c_m) || !factorPositive<3>(p, ldlt)) return Status::kInvalidArgument;
  ++m_epoch;
  ++m_track_epoch;
  m_pose = Pose{};
  m_pose.t_c_m = t_c_m;
  m_velocity.setZero();
  m_angular_velocity.setZero();
  // Attitude unknown: a nominal +-pi per axis keeps the matrix well defined; nothing couples it to position.
  Mat6 pose_block = Mat6::Zero();
  pose_block.topLeftCorner<3, 3>() = isotropic(kPi);
  pose_block.bottomRightCorner<3, 3>() = p;
  m_covariance = startCovariance(pose_block, m_params);
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
  addWhiteAcceleration(m_covariance, kAttitude, kAngularVelocity, m_noise_scale * qa * qa, dt_s);
  addWhiteAcceleration(m_covariance, kPosition, kVelocity,
                       m_noise_scale * m_params.linear_accel_noise * m_params.linear_accel_noise, dt_s);
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

FilterUpdate PoseFilter::update(const Pose& measured, const Mat6& covariance, RejectedInnovation rejected) {
  FilterUpdate result;
  result.dof = 6;
  const Mat6 r = symmetricPart<6>(covariance);
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
    ++m_track_epoch;  // the attitude's track starts here
    setUncorrelatedBlock(m_covariance, kAttitude, r.topLeftCorner<3, 3>());
    setUncorrelatedBlock(m_covariance, kAngularVelocity, angularVelocityPrior(m_params));
    m_angular_velocity.setZero();
    m_attitude_known = true;
    return result;
  }
  result = correct<6>(kAttitude, m_pose.boxMinus(measured), r, m_params.pose_gate_chi2, result);
  adaptProcessNoise(result, rejected);
  return result;
}

template <int M>
bool PoseFilter::factorInnovation(int first, const Eigen::Matrix<double, M, M>& r,
                                  Eigen::LDLT<Eigen::Matrix<double, M, M>>& s_factor) const {
  const Eigen::Matrix<double, M, M> s = m_covariance.template block<M, M>(first, first) + r;
  return factorPositive<M>(s, s_factor);
}

double PoseFilter::poseNis(const Pose& measured, const Mat6& covariance) const {
  if (!m_initialised || !m_attitude_known || !measured.R_c_m.allFinite() || !allFinite(measured.t_c_m))
    return -1.0;
  Eigen::LDLT<Mat6> s_factor;
  if (!factorInnovation<6>(kAttitude, symmetricPart<6>(covariance), s_factor)) return -1.0;
  const Vec6 y = m_pose.boxMinus(measured);
  return y.dot(s_factor.solve(y));
}

void PoseFilter::adaptProcessNoise(const FilterUpdate& result, RejectedInnovation rejected) {
  // Covariance matching: innovations well above their expected value (E[NIS] = dof) say the motion model
  // is too confident (the target tumbles faster, or accelerates): raise the process noise quickly; let it
  // fall back slowly while the innovations are consistent. Bounded by adaptive_noise_max_scale. A gated-out
  // innovation the caller cannot vouch for is left out: after a slew the tracker fitted a wrong pose four
  // frames running (NIS 1794, 588, 181, 50) and the raised noise let the fifth in, 7.7 deg off (campaign
  // smallsat/128).
  if (result.status != Status::kOk || result.dof <= 0) return;
  if (!result.accepted && rejected == RejectedInnovation::kIgnored) return;
  m_nis_average += kAdaptAverageWeight * (result.nis / result.dof - m_nis_average);
  if (m_nis_average > kAdaptRaiseNisPerDof)
    m_noise_scale = std::min(m_params.adaptive_noise_max_scale, m_noise_scale * kAdaptRaiseFactor);
  else
    m_noise_scale = std::max(1.0, m_noise_scale * kAdaptDecayFactor);
}

template <int M>
FilterUpdate PoseFilter::correct(int first, const Eigen::Matrix<double, M, 1>& y,
                                 const Eigen::Matrix<double, M, M>& r, double gate, FilterUpdate result) {
  Eigen::LDLT<Eigen::Matrix<double, M, M>> s_factor;
  if (!factorInnovation<M>(first, r, s_factor)) {
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
  const Mat3 r = symmetricPart<3>(covariance);
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
  ++m_epoch;
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
