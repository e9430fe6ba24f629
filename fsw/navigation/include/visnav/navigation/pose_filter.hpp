// Relative-pose Kalman filter (paper sec. II-H suggests it for frames without a trackable surface):
// constant linear and angular velocity of the target in the camera frame, attitude as an error state on
// SO(3) with the left perturbation of Pose::boxPlus (CONVENTIONS.md). It predicts the pose the tracker
// projects with, propagates through frames without a usable measurement (missed frames: predict(2 T)),
// gates measurements by their normalised innovation squared (NIS) and runs through far range on
// position-only measurements. Fixed-size Eigen only: no allocation, no exceptions, no unbounded loop.
#pragma once

#include <cstdint>

#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/navigation/pose_filter_params.hpp"

namespace visnav::nav {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

/// What a gated-out 6-DOF innovation says about the motion model.
enum class RejectedInnovation : std::uint8_t {
  kRaisesProcessNoise,  ///< taken as unmodelled motion (a tumble that starts): the process noise adapts
  kIgnored,             ///< the measurement itself may be wrong: its innovation teaches the filter nothing
};

/// Outcome of one measurement update.
struct FilterUpdate {
  Status status = Status::kOk;  ///< kInvalidArgument: not initialised, non-finite or non-positive covariance
  bool accepted = false;        ///< false when gated out (state untouched) or invalid
  double nis = 0.0;             ///< y^T S^-1 y of the innovation y (chi-square with `dof` if consistent)
  int dof = 0;                  ///< measurement dimension used (6 pose, 3 position)
};

class PoseFilter {
 public:
  /// Error-state layout: the first six entries are exactly the pose delta (omega, dt) of CONVENTIONS.md, so
  /// the measurement matrix of a pose is [I6 0] and the tracker's 6x6 covariance is used as it comes.
  static constexpr int kAttitude = 0;         ///< omega [rad], left perturbation: R = exp(omega) R_hat
  static constexpr int kPosition = 3;         ///< t_c_m [m]
  static constexpr int kAngularVelocity = 6;  ///< w [rad/s], camera frame: R(t + dt) = exp(w dt) R(t)
  static constexpr int kVelocity = 9;         ///< d t_c_m / dt [m/s]

  /// Checks the parameters; the filter starts uninitialised.
  LoadError init(const PoseFilterParams& params);
  /// Back to uninitialised (e.g. target lost for good).
  void reset();

  /// Start from a 6-DOF pose (e.g. acquisition): velocities zero with the configured large uncertainty.
  Status initialise(const Pose& pose, const Mat6& pose_covariance);
  /// Start from three consecutive 6-DOF poses, `first_dt_s` and `second_dt_s` apart (a track the filter
  /// rejected but the image vouched for): as initialise() from `current`, except the velocity when the
  /// three show one: the difference of `oldest` and `current` over their span T, with covariance
  /// (P_oldest + P_current) / T^2 (position blocks) and cross-covariance P_current / T to the pose, taken
  /// when it is significant (its NIS against zero above restart_rate_chi2, under the fits' covariance and
  /// under the prior initial_velocity_sigma_m_s) and the two steps agree (the NIS
  /// of their difference at most restart_rate_chi2: one fit that jumped makes one step alone). The angular
  /// rate always starts at zero: single fits' attitude differences are biased beyond their covariance.
  /// kInvalidArgument (state untouched) on a non-finite pose, a covariance that is not positive definite,
  /// or an interval not positive or a span above max_prediction_s.
  Status initialiseFromThree(const Pose& oldest, const Mat6& oldest_covariance, const Pose& middle,
                             const Mat6& middle_covariance, const Pose& current,
                             const Mat6& current_covariance, double first_dt_s, double second_dt_s);
  /// Sets the angular velocity to `angular_velocity` with covariance `covariance`, uncorrelated with the
  /// rest: a rate carried over a restart (a reacquisition's find continuing the track the filter coasted,
  /// NavigationParams::reacquire_carry_angular_rate). Not a measurement: measurementEpoch() is kept.
  /// kInvalidArgument (state untouched) when uninitialised, the attitude is unknown, the rate is not
  /// finite or the covariance is not positive definite.
  Status carryAngularVelocity(const Vec3& angular_velocity, const Mat3& covariance);
  /// What dropInsignificantRates() set to zero (bit set).
  static constexpr std::uint32_t kDroppedVelocity = 1U;
  static constexpr std::uint32_t kDroppedAngularVelocity = 2U;
  /// Sets the velocity and the angular velocity each to zero unless it is significant: its NIS against zero
  /// under its own covariance above restart_rate_chi2, and for the velocity also against the start-at-rest
  /// prior (initial_velocity_sigma_m_s), as in initialiseFromThree. The covariance is kept. For a search:
  /// what the last fits could not tell from noise is not carried through it. Returns what was dropped
  /// (kDropped* bits; 0 when uninitialised or nothing was).
  std::uint32_t dropInsignificantRates();
  /// The rate of the range, t_c_m.normalized() . velocity [m/s] (negative: closing), when that component is
  /// significant on its own: its square over its variance above restart_rate_chi2. 0 otherwise, or when
  /// uninitialised or at zero range. Read before dropInsignificantRates() by a search that carries the range
  /// the track was closing or opening at (NavigationParams::reacquire_range_rate_rung).
  double significantRangeRate() const;
  /// Multiplies the velocity and the angular velocity by factor in [0, 1] (the covariance is kept): a
  /// search coasting for many frames carries a motion that fades instead of a straight line
  /// (NavigationParams::reacquire_motion_decay_s). kInvalidArgument (state untouched) for a factor outside
  /// [0, 1] or when uninitialised.
  Status scaleRates(double factor);
  /// Start from a position only (far range): attitude unknown until the first pose update adopts one.
  Status initialisePosition(const Vec3& t_c_m, const Mat3& position_covariance);

  /// Propagate by dt_s > 0 (one period, two after a missed frame, ...). kInvalidArgument when uninitialised
  /// or dt is not in (0, max_prediction_s]; the state is then untouched.
  Status predict(double dt_s);

  /// 6-DOF measurement (tracker pose and its 6x6 covariance over (omega, dt)). Innovation
  /// y = predicted.boxMinus(measured); rejected when NIS > pose_gate_chi2. Joseph-form covariance update.
  /// While the attitude is unknown, the measured attitude is adopted and only the position is gated/fused.
  /// `rejected` says whether a gated-out innovation may raise the process noise (a caller that cannot vouch
  /// for the measurement passes kIgnored: otherwise a wrong measurement repeated for a few frames inflates
  /// the noise until the gate lets it in).
  FilterUpdate update(const Pose& measured, const Mat6& covariance,
                      RejectedInnovation rejected = RejectedInnovation::kRaisesProcessNoise);
  /// Position-only measurement, gated by position_gate_chi2.
  FilterUpdate updatePosition(const Vec3& t_c_m, const Mat3& covariance);
  /// Far-range measurement (unit direction, distance = t_c_m.z) through positionFromFarRange with the
  /// configured sigmas. The distance error is relative to the true range, so the covariance is scaled with
  /// the predicted range: scaling with the measured one would trust short readings more and bias the range.
  FilterUpdate updateFarRange(const Vec3& direction_c, double distance_m);

  bool initialised() const { return m_initialised; }
  bool attitudeKnown() const { return m_attitude_known; }
  /// Current estimate (after predict: the prediction). Attitude is identity while unknown.
  const Pose& pose() const { return m_pose; }
  const Vec3& velocity() const { return m_velocity; }
  const Vec3& angularVelocity() const { return m_angular_velocity; }
  const Mat12& covariance() const { return m_covariance; }
  Mat6 poseCovariance() const { return m_covariance.topLeftCorner<6, 6>(); }
  const PoseFilterParams& params() const { return m_params; }

  std::uint64_t acceptedUpdates() const { return m_accepted; }
  /// Counts every change of the state by a measurement or a restart (initialise*, reset, a correction
  /// applied); predict and the rate changes for a search leave it. Equal counts at two times: the later
  /// state is the earlier one propagated by the motion model alone.
  std::uint64_t measurementEpoch() const { return m_epoch; }
  /// Counts the restarts only (initialise*, reset): equal counts at two times say the later state is the
  /// earlier one carried on by prediction and accepted measurements, the same track.
  std::uint64_t trackEpoch() const { return m_track_epoch; }
  /// The NIS (6 dof) `measured` would have against this state, which is left unchanged: y^T S^-1 y with y =
  /// pose().boxMinus(measured) and S its pose covariance plus `covariance`, as update() gates it. -1 without
  /// a known attitude or with an invalid input.
  double poseNis(const Pose& measured, const Mat6& covariance) const;
  std::uint64_t rejectedUpdates() const { return m_rejected; }
  /// Gated-out updates since the last accepted one (FDIR input).
  std::uint32_t consecutiveRejections() const { return m_consecutive_rejections; }
  /// Current multiplier of the process noise (1 .. adaptive_noise_max_scale), adapted to the innovations.
  double processNoiseScale() const { return m_noise_scale; }

 private:
  void inject(const Vec12& dx);
  void adaptProcessNoise(const FilterUpdate& result, RejectedInnovation rejected);
  /// Adaptation constants: an exponential average of NIS / dof (weight 0.3: about the last 3 updates; on a
  /// consistent model it is 1 +- 0.24, so 2 is a 4-sigma event) above 2 raises the noise by 4x per frame
  /// (a tumble that starts is followed within 2-3 frames); otherwise it decays by 0.8x per frame (back to
  /// nominal in ~20 frames, 4 s at 5 Hz). Shapes of the adaptation, not scene tuning: the bound is the
  /// parameter.
  static constexpr double kAdaptAverageWeight = 0.3;
  static constexpr double kAdaptRaiseNisPerDof = 2.0;
  static constexpr double kAdaptRaiseFactor = 4.0;
  static constexpr double kAdaptDecayFactor = 0.8;
  void symmetrize();
  FilterUpdate gateResult(FilterUpdate result, double gate);
  /// The innovation covariance S = P + R of a measurement of M consecutive error-state entries from
  /// `first`, factored; false when S is not positive definite. Shared by correct() and poseNis().
  template <int M>
  bool factorInnovation(int first, const Eigen::Matrix<double, M, M>& r,
                        Eigen::LDLT<Eigen::Matrix<double, M, M>>& s_factor) const;
  /// The Kalman correction for a measurement of M consecutive error-state entries from `first` (H = [0 I 0]):
  /// innovation y, its covariance R; NIS gate, Joseph-form covariance update, state injection.
  template <int M>
  FilterUpdate correct(int first, const Eigen::Matrix<double, M, 1>& y, const Eigen::Matrix<double, M, M>& r,
                       double gate, FilterUpdate result);

  PoseFilterParams m_params;
  bool m_initialised = false;
  bool m_attitude_known = false;
  Pose m_pose;
  Vec3 m_velocity = Vec3::Zero();
  Vec3 m_angular_velocity = Vec3::Zero();
  Mat12 m_covariance = Mat12::Identity();
  std::uint64_t m_accepted = 0;
  std::uint64_t m_epoch = 0;
  std::uint64_t m_track_epoch = 0;
  std::uint64_t m_rejected = 0;
  std::uint32_t m_consecutive_rejections = 0;
  double m_noise_scale = 1.0;
  double m_nis_average = 1.0;  ///< exponential average of NIS / dof
};

/// Far-range direction (unit, camera frame) and distance (along the boresight: t_c_m.z, CONVENTIONS.md) as a
/// position measurement: t = u * distance / u.z, covariance tight across the line of sight
/// ((range * direction_sigma)^2) and loose along it ((range * distance_sigma_rel)^2). False when the
/// direction is not in front of the camera or the inputs are not finite. `sigma_range_m` > 0 replaces the
/// measured range in the two sigmas (e.g. the filter's predicted range).
bool positionFromFarRange(const Vec3& direction_c, double distance_m, double direction_sigma_rad,
                          double distance_sigma_rel, Vec3& t_c_m, Mat3& covariance,
                          double sigma_range_m = 0.0);

/// Left Jacobian of SO(3): exp(phi + d) ~ exp(J_l(phi) d) exp(phi) for small d.
Mat3 leftJacobianSo3(const Vec3& phi);

}  // namespace visnav::nav
