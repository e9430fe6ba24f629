// Relative-pose Kalman filter: convergence, statistical consistency (NIS and NEES against their chi-square
// means), gating, missed-frame propagation, large rotations, far-range position updates, no allocation.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>

#include "../../support/alloc_counter.hpp"
#include "visnav/core/rng.hpp"
#include "visnav/navigation/pose_filter.hpp"

namespace visnav::nav {
namespace {

constexpr double kDt = 0.2;  // 5 Hz

double gauss(Pcg32& rng) {
  // Box-Muller; uniform() < 1 so 1 - u > 0.
  const double u1 = 1.0 - rng.uniform();
  const double u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

template <int N>
Eigen::Matrix<double, N, 1> sample(Pcg32& rng, const Eigen::Matrix<double, N, N>& cov) {
  Eigen::Matrix<double, N, 1> z;
  for (int i = 0; i < N; ++i) z[i] = gauss(rng);
  return Eigen::LLT<Eigen::Matrix<double, N, N>>(cov).matrixL() * z;
}

/// Ground truth driven by exactly the filter's process model: white accelerations of density q.
struct Truth {
  Pose pose;
  Vec3 w = Vec3::Zero();
  Vec3 v = Vec3::Zero();

  void step(double dt, double q_lin, double q_ang, Pcg32& rng) {
    Mat2 c;
    c << dt * dt * dt / 3.0, dt * dt / 2.0, dt * dt / 2.0, dt;
    const Mat2 l = Eigen::LLT<Mat2>(c).matrixL();
    Vec3 n_rot, n_w, n_pos, n_v;
    for (int i = 0; i < 3; ++i) {
      const Vec2 a = std::sqrt(q_ang) * l * Vec2(gauss(rng), gauss(rng));
      const Vec2 b = std::sqrt(q_lin) * l * Vec2(gauss(rng), gauss(rng));
      n_rot[i] = a[0];
      n_w[i] = a[1];
      n_pos[i] = b[0];
      n_v[i] = b[1];
    }
    pose.R_c_m = expSo3(n_rot) * expSo3(w * dt) * pose.R_c_m;
    pose.t_c_m += v * dt + n_pos;
    w += n_w;
    v += n_v;
  }
};

Mat6 trackerLikeCovariance() {
  Vec6 sigma;
  sigma << 0.3 * kRadPerDeg, 0.3 * kRadPerDeg, 0.1 * kRadPerDeg, 0.01, 0.01, 0.15;
  return sigma.cwiseAbs2().asDiagonal();
}

Pose measure(const Pose& truth, const Mat6& cov, Pcg32& rng) { return truth.boxPlus(sample<6>(rng, cov)); }

Vec12 stateError(const PoseFilter& f, const Truth& truth) {
  Vec12 e;
  e.head<6>() = f.pose().boxMinus(truth.pose);
  e.segment<3>(PoseFilter::kAngularVelocity) = truth.w - f.angularVelocity();
  e.segment<3>(PoseFilter::kVelocity) = truth.v - f.velocity();
  return e;
}

PoseFilter makeFilter(const PoseFilterParams& params = {}) {
  PoseFilter f;
  EXPECT_TRUE(f.init(params).ok);
  return f;
}

// The start covariances, entry by entry: the pose block as given (its symmetric part), the velocities at
// their configured priors, nothing correlated across; a position start has a nominal pi^2 attitude; the first
// attitude adopted later comes uncorrelated with the (by then correlated) position and velocity.
TEST(PoseFilter, StartCovariancesHaveTheDocumentedLayout) {
  PoseFilterParams params;
  params.initial_velocity_sigma_m_s = 0.7;
  params.initial_angular_velocity_sigma_deg_s = 3.0;
  const double sv2 = 0.7 * 0.7;
  const double sw2 = (3.0 * kRadPerDeg) * (3.0 * kRadPerDeg);
  Mat6 pose_cov = trackerLikeCovariance();
  pose_cov(0, 4) = 1e-6;  // asymmetric on purpose: the symmetric part is used
  pose_cov(4, 0) = 3e-6;
  PoseFilter f = makeFilter(params);
  ASSERT_EQ(f.initialise(Pose::fromYpr({0.1, 0.2, 0.3}, Vec3(0.1, 0.2, 9.0)), pose_cov), Status::kOk);
  Mat12 expected = Mat12::Zero();
  expected.topLeftCorner<6, 6>() = 0.5 * (pose_cov + pose_cov.transpose());
  expected.block<3, 3>(PoseFilter::kVelocity, PoseFilter::kVelocity) = Mat3::Identity() * sv2;
  expected.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity) = Mat3::Identity() * sw2;
  EXPECT_LT((f.covariance() - expected).cwiseAbs().maxCoeff(), 1e-15) << f.covariance();
  EXPECT_DOUBLE_EQ(f.covariance()(0, 4), 2e-6);
  EXPECT_TRUE(f.velocity().isZero());
  EXPECT_TRUE(f.angularVelocity().isZero());

  Mat3 pos_cov;
  pos_cov << 4.0, 0.5, 0.0, 0.5, 2.0, 0.1, 0.0, 0.1, 9.0;
  ASSERT_EQ(f.initialisePosition(Vec3(1.0, 2.0, 300.0), pos_cov), Status::kOk);
  expected.setZero();
  expected.block<3, 3>(PoseFilter::kAttitude, PoseFilter::kAttitude) = Mat3::Identity() * kPi * kPi;
  expected.block<3, 3>(PoseFilter::kPosition, PoseFilter::kPosition) = pos_cov;
  expected.block<3, 3>(PoseFilter::kVelocity, PoseFilter::kVelocity) = Mat3::Identity() * sv2;
  expected.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity) = Mat3::Identity() * sw2;
  EXPECT_LT((f.covariance() - expected).cwiseAbs().maxCoeff(), 1e-15) << f.covariance();

  // Couple position and velocity, then adopt an attitude: its block is the measurement's, and it and the
  // restarted angular velocity are uncorrelated with everything else.
  ASSERT_EQ(f.predict(0.2), Status::kOk);
  Mat6 meas = trackerLikeCovariance();
  meas(0, 1) = meas(1, 0) = 1e-7;
  const FilterUpdate up = f.update(Pose::fromYpr({0.0, 0.0, 0.0}, f.pose().t_c_m), meas);
  ASSERT_TRUE(up.accepted);
  ASSERT_TRUE(f.attitudeKnown());
  const Mat12& p = f.covariance();
  EXPECT_EQ(Mat3(p.block<3, 3>(PoseFilter::kAttitude, PoseFilter::kAttitude)),
            Mat3(meas.topLeftCorner<3, 3>()));
  EXPECT_EQ(Mat3(p.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity)),
            Mat3(Mat3::Identity() * sw2));
  for (const int block : {PoseFilter::kAttitude, PoseFilter::kAngularVelocity}) {
    for (int i = 0; i < 12; ++i) {
      if (i >= block && i < block + 3) continue;
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p(block + k, i), 0.0) << "row " << block + k << " col " << i;
        EXPECT_EQ(p(i, block + k), 0.0) << "row " << i << " col " << block + k;
      }
    }
  }
  // Position and velocity stay correlated (the prediction coupled them).
  EXPECT_NE(p(PoseFilter::kPosition, PoseFilter::kVelocity), 0.0);
}

TEST(PoseFilter, LeftJacobianMatchesFiniteDifferences) {
  const Vec3 phi(0.7, -1.9, 1.2);  // ~2.4 rad: far from the small-angle branch
  const Mat3 jl = leftJacobianSo3(phi);
  for (int k = 0; k < 3; ++k) {
    const Vec3 d = Vec3::Unit(k) * 1e-6;
    const Vec3 numeric = logSo3(expSo3(phi + d) * expSo3(phi).transpose()) / 1e-6;
    EXPECT_NEAR((numeric - jl.col(k)).norm(), 0.0, 1e-5);
  }
  EXPECT_NEAR((leftJacobianSo3(Vec3(1e-8, 0, 0)) - Mat3::Identity()).norm(), 0.0, 1e-8);
}

TEST(PoseFilter, ConvergesOnConstantVelocityTruth) {
  // The truth has no process noise: a filter told so keeps averaging instead of forgetting.
  PoseFilterParams params;
  params.linear_accel_noise = 1e-4;
  params.angular_accel_noise_deg = 1e-3;
  PoseFilter f = makeFilter(params);
  Pcg32 rng(1);
  Truth truth;
  truth.pose = Pose::fromYpr({0.3, -0.2, 2.9}, Vec3(0.3, -0.2, 20.0));
  truth.v = Vec3(0.01, -0.02, -0.3);
  truth.w = Vec3(0.5, -1.0, 2.0) * kRadPerDeg;
  const Mat6 r = trackerLikeCovariance();
  ASSERT_EQ(f.initialise(measure(truth.pose, r, rng), r), Status::kOk);
  for (int k = 0; k < 300; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    ASSERT_EQ(f.predict(kDt), Status::kOk);
    ASSERT_TRUE(f.update(measure(truth.pose, r, rng), r).accepted) << k;
  }
  // Averaging 300 measurements: the filter beats the single-frame noise by far on the noisy axes.
  const Vec12 e = stateError(f, truth);
  EXPECT_LT((truth.v - f.velocity()).norm(), 0.01);
  EXPECT_LT((truth.w - f.angularVelocity()).norm() * kDegPerRad, 0.05);
  EXPECT_LT(std::fabs(e[5]), 0.05);                        // range: single measurement sigma 0.15 m
  EXPECT_LT(std::sqrt(f.covariance()(5, 5)), 0.15 / 3.0);  // and the filter knows it
  EXPECT_LT(e.head<3>().norm() * kDegPerRad, 0.15);
}

TEST(PoseFilter, InnovationsAndErrorsAreChiSquareOnAConsistentModel) {
  PoseFilterParams params;
  params.linear_accel_noise = 0.02;
  params.angular_accel_noise_deg = 1.0;
  PoseFilter f = makeFilter(params);
  const double q_lin = params.linear_accel_noise * params.linear_accel_noise;
  const double q_ang = std::pow(params.angular_accel_noise_deg * kRadPerDeg, 2);
  Pcg32 rng(7);
  Truth truth;
  truth.pose = Pose::fromYpr({-0.4, 0.3, 3.0}, Vec3(0.1, 0.2, 12.0));
  truth.w = Vec3(2.0, -3.0, 5.0) * kRadPerDeg;
  const Mat6 r = trackerLikeCovariance();
  ASSERT_EQ(f.initialise(measure(truth.pose, r, rng), r), Status::kOk);
  constexpr int kSteps = 3000;
  constexpr int kSkip = 100;  // initial transient (the initial velocity covariance is deliberately loose)
  double nis_sum = 0.0, nees_sum = 0.0;
  int gated = 0;
  for (int k = 0; k < kSteps; ++k) {
    truth.step(kDt, q_lin, q_ang, rng);
    f.predict(kDt);
    const FilterUpdate u = f.update(measure(truth.pose, r, rng), r);
    gated += u.accepted ? 0 : 1;
    if (k < kSkip) continue;
    nis_sum += u.nis;
    const Vec12 e = stateError(f, truth);
    nees_sum += e.dot(f.covariance().ldlt().solve(e));
  }
  const double n = kSteps - kSkip;
  std::printf("NIS mean %.3f (chi2 6 dof: 6), NEES mean %.3f (chi2 12 dof: 12), gated %d of %d\n",
              nis_sum / n, nees_sum / n, gated, kSteps);
  // Means of chi-square(6) and chi-square(12); the standard error of the mean over 2900 white samples is
  // ~0.06 (NIS) and ~0.09 (NEES, correlated in time: allow more).
  EXPECT_NEAR(nis_sum / n, 6.0, 0.35);
  EXPECT_NEAR(nees_sum / n, 12.0, 1.0);
  EXPECT_LE(gated, 12);  // 99.9 % gate: ~3 expected false rejections in 3000
}

TEST(PoseFilter, OutlierIsGatedAndLeavesTheStateUntouched) {
  PoseFilter f = makeFilter();
  Pcg32 rng(3);
  Truth truth;
  truth.pose = Pose::fromYpr({0.1, 0.1, 3.1}, Vec3(0.0, 0.0, 10.0));
  truth.v = Vec3(0.0, 0.0, -0.1);
  const Mat6 r = trackerLikeCovariance();
  f.initialise(truth.pose, r);
  for (int k = 0; k < 50; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    f.predict(kDt);
    f.update(measure(truth.pose, r, rng), r);
  }
  truth.step(kDt, 0.0, 0.0, rng);
  f.predict(kDt);
  const Pose predicted = f.pose();
  const Mat12 p_before = f.covariance();
  Vec6 jump;
  jump << 0.0, 0.0, 0.0, 0.3, 0.0, 0.0;  // 30 cm sideways: 30 sigma of the tracker
  const FilterUpdate u = f.update(truth.pose.boxPlus(jump), r);
  EXPECT_EQ(u.status, Status::kOk);
  EXPECT_FALSE(u.accepted);
  EXPECT_GT(u.nis, 100.0);
  EXPECT_EQ(f.pose().t_c_m, predicted.t_c_m);
  EXPECT_EQ(f.covariance(), p_before);
  EXPECT_EQ(f.consecutiveRejections(), 1U);
  truth.step(kDt, 0.0, 0.0, rng);
  f.predict(kDt);
  EXPECT_TRUE(f.update(measure(truth.pose, r, rng), r).accepted);
  EXPECT_EQ(f.consecutiveRejections(), 0U);
}

TEST(PoseFilter, MissedFramePropagatesTwoPeriodsAndGrowsTheCovariance) {
  PoseFilterParams params;
  PoseFilter one = makeFilter(params), two = makeFilter(params);
  const Pose start = Pose::fromYpr({0.0, 0.2, 3.0}, Vec3(1.0, 0.5, 15.0));
  const Mat6 r = trackerLikeCovariance();
  one.initialise(start, r);
  two.initialise(start, r);
  ASSERT_EQ(one.predict(kDt), Status::kOk);
  ASSERT_EQ(two.predict(2.0 * kDt), Status::kOk);
  // From the initial P (no position/velocity correlation): P_tt(T) = P_tt + T^2 sv^2 + q T^3 / 3 per axis.
  const double sv2 = std::pow(params.initial_velocity_sigma_m_s, 2);
  const double q = std::pow(params.linear_accel_noise, 2);
  for (const double t : {kDt, 2.0 * kDt}) {
    const PoseFilter& f = t == kDt ? one : two;
    EXPECT_NEAR(f.covariance()(5, 5), r(5, 5) + t * t * sv2 + q * t * t * t / 3.0, 1e-12);
  }
  EXPECT_GT(two.poseCovariance().trace(), one.poseCovariance().trace());
  EXPECT_GT(two.covariance()(0, 0), one.covariance()(0, 0));  // attitude grows with the rate uncertainty
  // With a velocity learned, the prediction moves by v * 2T.
  PoseFilter f = makeFilter(params);
  Pcg32 rng(5);
  Truth truth;
  truth.pose = start;
  truth.v = Vec3(0.05, 0.0, -0.2);
  f.initialise(start, r);
  for (int k = 0; k < 100; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    f.predict(kDt);
    f.update(measure(truth.pose, r, rng), r);
  }
  const Vec3 before = f.pose().t_c_m;
  const Vec3 v = f.velocity();
  truth.step(kDt, 0.0, 0.0, rng);  // this frame is missed
  truth.step(kDt, 0.0, 0.0, rng);
  f.predict(2.0 * kDt);
  EXPECT_NEAR((f.pose().t_c_m - (before + v * 2.0 * kDt)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(f.update(measure(truth.pose, r, rng), r).accepted);
}

TEST(PoseFilter, TracksFastRotationThroughEveryAttitudeWithoutSingularity) {
  // The rate is unknown at start: its initial uncertainty must cover it, or the first frames are gated out.
  PoseFilterParams params;
  params.initial_angular_velocity_sigma_deg_s = 100.0;
  params.angular_accel_noise_deg = 1e-2;
  PoseFilter f = makeFilter(params);
  Pcg32 rng(11);
  Truth truth;
  truth.pose = Pose::fromYpr({0.5, 0.5 * kPi, 0.0}, Vec3(0.0, 0.0, 8.0));  // start in gimbal lock
  truth.w = Vec3(40.0, -25.0, 60.0) * kRadPerDeg;                          // ~15 deg per frame
  const Mat6 r = trackerLikeCovariance();
  f.initialise(measure(truth.pose, r, rng), r);
  int rejected = 0;
  double worst_deg = 0.0;
  double max_abs_pitch = 0.0;
  for (int k = 0; k < 400; ++k) {  // 80 s: ~17 full turns
    truth.step(kDt, 0.0, 0.0, rng);
    f.predict(kDt);
    rejected += f.update(measure(truth.pose, r, rng), r).accepted ? 0 : 1;
    const double pitch = std::fabs(truth.pose.ypr().pitch_rad);
    max_abs_pitch = std::max(max_abs_pitch, pitch);
    if (k >= 20) worst_deg = std::max(worst_deg, f.pose().boxMinus(truth.pose).head<3>().norm() * kDegPerRad);
  }
  EXPECT_EQ(rejected, 0);
  EXPECT_LT(worst_deg, 0.3);  // single-frame noise: 0.3 deg per axis
  // Rate: inside the filter's own 3 sigma, and far better than differencing two frames (~2 deg/s).
  const Mat3 p_rate = f.covariance().block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity);
  EXPECT_LT((f.angularVelocity() - truth.w).norm(), 3.0 * std::sqrt(p_rate.trace()));
  EXPECT_LT(std::sqrt(p_rate.trace()) * kDegPerRad, 0.1);
  EXPECT_GT(max_abs_pitch * kDegPerRad, 85.0);  // the run really crossed the Euler singularity region
}

TEST(PoseFilter, FarRangePositionHasTightCrossAndLooseAlongLineOfSight) {
  const Vec3 u = Vec3(0.05, -0.03, 1.0).normalized();
  Vec3 t;
  Mat3 c;
  ASSERT_TRUE(positionFromFarRange(u, 300.0, 0.1 * kRadPerDeg, 0.2, t, c));
  EXPECT_NEAR(t.z(), 300.0, 1e-9);  // distance is t_c_m.z (CONVENTIONS.md)
  EXPECT_NEAR((t.normalized() - u).norm(), 0.0, 1e-12);
  const double range = t.norm();
  EXPECT_NEAR((c * u - std::pow(0.2 * range, 2) * u).norm(), 0.0, 1e-9);
  const Vec3 across = u.cross(Vec3::UnitX()).normalized();
  EXPECT_NEAR((c * across - std::pow(range * 0.1 * kRadPerDeg, 2) * across).norm(), 0.0, 1e-9);
  EXPECT_FALSE(positionFromFarRange(Vec3(0, 0, -1), 300.0, 0.001, 0.2, t, c));
  EXPECT_FALSE(positionFromFarRange(u, -1.0, 0.001, 0.2, t, c));
}

TEST(PoseFilter, RunsThroughFarRangeOnPositionsAndAdoptsTheFirstAttitude) {
  PoseFilterParams params;
  PoseFilter f = makeFilter(params);
  Pcg32 rng(13);
  Truth truth;
  truth.pose.t_c_m = Vec3(5.0, -3.0, 300.0);
  truth.v = Vec3(0.02, 0.01, -2.0);
  const double dir_sigma = params.far_direction_sigma_deg * kRadPerDeg;
  const double dist_sigma = params.far_distance_sigma_rel;
  // Far-range cue: direction within 0.1 deg, distance (t_c_m.z) within 20 %, both relative to the truth.
  Vec3 u;
  double d = 0.0;
  auto farMeasurement = [&]() {
    u = expSo3(Vec3(gauss(rng), gauss(rng), 0.0) * dir_sigma) * truth.pose.t_c_m.normalized();
    d = truth.pose.t_c_m.z() * (1.0 + dist_sigma * gauss(rng));
  };
  farMeasurement();
  Vec3 t;
  Mat3 c;
  ASSERT_TRUE(positionFromFarRange(u, d, dir_sigma, dist_sigma, t, c));
  ASSERT_EQ(f.initialisePosition(t, c), Status::kOk);
  EXPECT_FALSE(f.attitudeKnown());
  int rejected = 0;
  double nis_sum = 0.0;
  for (int k = 0; k < 400; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    f.predict(kDt);
    farMeasurement();
    const FilterUpdate up = f.updateFarRange(u, d);
    rejected += up.accepted ? 0 : 1;
    nis_sum += up.nis;
  }
  EXPECT_LE(rejected, 2);
  EXPECT_NEAR(nis_sum / 400.0, 3.0, 0.5);
  const Vec3 los = truth.pose.t_c_m.normalized();
  const Vec3 err = f.pose().t_c_m - truth.pose.t_c_m;
  const double range = truth.pose.t_c_m.norm();
  const Mat3 p_pos = f.covariance().block<3, 3>(3, 3);
  const double var_along = los.dot(p_pos * los);
  const Vec3 x_perp = los.cross(Vec3::UnitY()).normalized();
  const double var_across = x_perp.dot(p_pos * x_perp);
  // The filter beats one measurement by averaging, and its error is inside its own 3 sigma.
  EXPECT_LT(std::sqrt(var_along), 0.5 * dist_sigma * range);
  EXPECT_LT(std::sqrt(var_across), 0.5 * dir_sigma * range);
  EXPECT_LT(std::fabs(err.dot(los)), 3.0 * std::sqrt(var_along));
  EXPECT_LT((err - err.dot(los) * los).norm(), 3.0 * std::sqrt(2.0 * var_across));
  EXPECT_LT((f.velocity() - truth.v).norm(), 0.5);
  EXPECT_GT(var_along, 100.0 * var_across);  // anisotropic: tight across, loose along the line of sight
  // The first 6-DOF measurement brings the attitude; position and velocity are kept and fused.
  truth.pose.R_c_m = rotationFromYpr({0.2, 0.1, 3.0});
  const Mat6 r = trackerLikeCovariance();
  const Vec3 v_before = f.velocity();
  f.predict(kDt);
  truth.step(kDt, 0.0, 0.0, rng);
  const FilterUpdate first = f.update(truth.pose, r);
  EXPECT_TRUE(first.accepted);
  EXPECT_EQ(first.dof, 3);
  EXPECT_TRUE(f.attitudeKnown());
  EXPECT_NEAR(f.pose().boxMinus(truth.pose).head<3>().norm(), 0.0, 1e-12);
  EXPECT_LT((f.velocity() - v_before).norm(), 0.5);
  f.predict(kDt);
  truth.step(kDt, 0.0, 0.0, rng);
  EXPECT_EQ(f.update(measure(truth.pose, r, rng), r).dof, 6);
}

// Adaptive process noise: a target that starts to tumble (angular acceleration the constant-velocity model
// does not expect) raises the noise within a few frames, the filter follows, and the noise decays back once
// the motion is steady again; with adaptive_noise_max_scale = 1 it never moves.
TEST(PoseFilter, ProcessNoiseFollowsATumbleThatStartsAndDecaysBack) {
  for (const double max_scale : {100.0, 1.0}) {
    PoseFilterParams params;
    params.adaptive_noise_max_scale = max_scale;
    PoseFilter f = makeFilter(params);
    Pcg32 rng(7, 3);
    const Mat6 cov = trackerLikeCovariance();
    Truth truth;
    truth.pose = Pose::fromYpr({0.2, 0.1, kPi}, Vec3(0.0, 0.0, 10.0));
    ASSERT_EQ(f.initialise(truth.pose, cov), Status::kOk);
    double peak = 1.0;
    int rejected_late = 0;
    for (int k = 1; k <= 120; ++k) {
      if (k == 20) truth.w = Vec3(0.0, 6.0, 2.0) * kRadPerDeg;  // a 6.3 deg/s tumble starts at once
      truth.step(kDt, 0.0, 0.0, rng);
      ASSERT_EQ(f.predict(kDt), Status::kOk);
      const FilterUpdate u = f.update(measure(truth.pose, cov, rng), cov);
      if (k < 20) {
        EXPECT_DOUBLE_EQ(f.processNoiseScale(), 1.0) << "steady target, frame " << k;
      }
      if (k >= 20 && k < 30) peak = std::max(peak, f.processNoiseScale());
      if (k >= 30 && k < 60 && !u.accepted) ++rejected_late;
    }
    std::printf(
        "adaptive noise up to %.0f: peak scale %.1f, rejected 2-8 s after the start %d, final scale %.2f\n",
        max_scale, peak, rejected_late, f.processNoiseScale());
    if (max_scale > 1.0) {
      EXPECT_GE(peak, 4.0) << "the noise was raised when the tumble started";
      EXPECT_EQ(rejected_late, 0) << "the filter followed the tumble";
      EXPECT_LT(f.processNoiseScale(), 2.0) << "and decayed back on the steady tumble";
    } else {
      EXPECT_DOUBLE_EQ(peak, 1.0);
      EXPECT_DOUBLE_EQ(f.processNoiseScale(), 1.0);
      EXPECT_GT(rejected_late, 10) << "control: with fixed noise the filter does not follow the tumble";
    }
  }
}

TEST(PoseFilter, RejectsInvalidInputs) {
  PoseFilter f = makeFilter();
  const Mat6 r = trackerLikeCovariance();
  EXPECT_EQ(f.predict(kDt), Status::kInvalidArgument);  // not initialised
  EXPECT_EQ(f.update(Pose{}, r).status, Status::kInvalidArgument);
  Mat6 bad = r;
  bad(5, 5) = -1.0;
  EXPECT_EQ(f.initialise(Pose{}, bad), Status::kInvalidArgument);
  ASSERT_EQ(f.initialise(Pose::fromYpr({}, Vec3(0, 0, 10)), r), Status::kOk);
  EXPECT_EQ(f.predict(0.0), Status::kInvalidArgument);
  EXPECT_EQ(f.predict(-kDt), Status::kInvalidArgument);
  EXPECT_EQ(f.predict(1e3), Status::kInvalidArgument);
  Pose nan_pose = f.pose();
  nan_pose.t_c_m.x() = std::nan("");
  const FilterUpdate u = f.update(nan_pose, r);
  EXPECT_EQ(u.status, Status::kInvalidArgument);
  EXPECT_FALSE(u.accepted);
  EXPECT_EQ(f.update(f.pose(), bad).status, Status::kInvalidArgument);
  EXPECT_EQ(f.acceptedUpdates() + f.rejectedUpdates(), 0U);  // invalid input is neither
}

TEST(PoseFilter, CovarianceStaysSymmetricAndAllocatesNothing) {
  PoseFilter f = makeFilter();
  Pcg32 rng(17);
  Truth truth;
  truth.pose = Pose::fromYpr({0.1, 0.2, 3.0}, Vec3(0.0, 0.0, 10.0));
  truth.w = Vec3(3.0, 1.0, -2.0) * kRadPerDeg;
  const Mat6 r = trackerLikeCovariance();
  Vec3 t;
  Mat3 c;
  positionFromFarRange(Vec3(0.0, 0.0, 1.0), 10.0, 0.001, 0.1, t, c);
  f.initialise(truth.pose, r);
  const std::uint64_t before = test::allocationCount();
  for (int k = 0; k < 500; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    f.predict(k % 10 == 9 ? 2.0 * kDt : kDt);
    f.update(measure(truth.pose, r, rng), r);
    if (k % 50 == 0) f.updatePosition(truth.pose.t_c_m, c);
  }
  EXPECT_EQ(test::allocationCount() - before, 0U);
  EXPECT_EQ(f.covariance(), f.covariance().transpose());
  EXPECT_GT(f.covariance().ldlt().vectorD().minCoeff(), 0.0);
}

}  // namespace
}  // namespace visnav::nav
