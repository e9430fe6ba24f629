// Relative-pose Kalman filter: convergence, statistical consistency (NIS and NEES against their chi-square
// means), gating, missed-frame propagation, large rotations, no allocation. Far range and the adaptive
// process noise: test_pose_filter_ranges.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../../support/alloc_counter.hpp"
#include "pose_filter_test_support.hpp"

namespace visnav::nav {
namespace {

using namespace pose_filter_test;  // NOLINT(google-build-using-namespace): the shared test helpers

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

// measurementEpoch: what NavigationPipeline reads to know its prediction is the last valid pose carried by
// the motion model alone (find_prediction_look_deg). Prediction and a search's rate changes leave it; a
// correction applied, a gated-out one's absence, restarts and a reset are told apart.
TEST(PoseFilter, MeasurementEpochCountsOnlyWhatAMeasurementOrARestartChanged) {
  PoseFilter f = makeFilter();
  Pcg32 rng(5);
  Truth truth;
  truth.pose = Pose::fromYpr({0.1, 0.1, 3.1}, Vec3(0.0, 0.0, 10.0));
  truth.v = Vec3(0.0, 0.0, -0.1);
  const Mat6 r = trackerLikeCovariance();
  std::uint64_t epoch = f.measurementEpoch();
  ASSERT_EQ(f.initialise(truth.pose, r), Status::kOk);
  EXPECT_GT(f.measurementEpoch(), epoch) << "a restart";
  for (int k = 0; k < 5; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    ASSERT_EQ(f.predict(kDt), Status::kOk);
    epoch = f.measurementEpoch();
    ASSERT_TRUE(f.update(measure(truth.pose, r, rng), r).accepted);
    EXPECT_GT(f.measurementEpoch(), epoch) << "an accepted correction, frame " << k;
  }
  epoch = f.measurementEpoch();
  ASSERT_EQ(f.predict(kDt), Status::kOk);
  (void)f.dropInsignificantRates();
  ASSERT_EQ(f.scaleRates(0.5), Status::kOk);
  EXPECT_EQ(f.measurementEpoch(), epoch) << "coasting: the motion model alone";
  Vec6 jump;
  jump << 0.0, 0.0, 0.0, 0.3, 0.0, 0.0;  // 30 sigma of the tracker: gated out
  ASSERT_FALSE(f.update(truth.pose.boxPlus(jump), r).accepted);
  EXPECT_EQ(f.measurementEpoch(), epoch) << "a rejected measurement changed nothing";
  f.reset();
  EXPECT_GT(f.measurementEpoch(), epoch) << "a reset";
}

// trackEpoch changes on restarts only; poseNis is the NIS update() would gate on, and changes nothing.
TEST(PoseFilter, TrackEpochCountsRestartsAndPoseNisIsTheGatesWithoutAnUpdate) {
  PoseFilter f = makeFilter();
  Pcg32 rng(7);
  Truth truth;
  truth.pose = Pose::fromYpr({0.2, -0.1, 3.0}, Vec3(0.2, 0.0, 12.0));
  const Mat6 r = trackerLikeCovariance();
  EXPECT_LT(f.poseNis(truth.pose, r), 0.0) << "nothing to judge against";
  ASSERT_EQ(f.initialise(truth.pose, r), Status::kOk);
  const std::uint64_t track = f.trackEpoch();
  for (int k = 0; k < 5; ++k) {
    truth.step(kDt, 0.0, 0.0, rng);
    ASSERT_EQ(f.predict(kDt), Status::kOk);
    const Pose measured = measure(truth.pose, r, rng);
    const Mat12 before = f.covariance();
    const Pose predicted = f.pose();
    const double nis = f.poseNis(measured, r);
    EXPECT_EQ(f.covariance(), before) << "poseNis changed the state, frame " << k;
    EXPECT_EQ(f.pose().t_c_m, predicted.t_c_m);
    const FilterUpdate u = f.update(measured, r);
    ASSERT_TRUE(u.accepted);
    EXPECT_NEAR(nis, u.nis, 1e-9 * std::max(1.0, u.nis)) << "frame " << k;
  }
  EXPECT_EQ(f.trackEpoch(), track) << "accepted corrections continue the track";
  // A rival 20 deg turned is far outside the gate; the state it is judged against is left alone.
  Vec6 turn;
  turn << 0.0, 20.0 * kRadPerDeg, 0.0, 0.0, 0.0, 0.0;
  EXPECT_GT(f.poseNis(truth.pose.boxPlus(turn), r), f.params().pose_gate_chi2);
  Pose bad = truth.pose;
  bad.t_c_m.x() = std::nan("");
  EXPECT_LT(f.poseNis(bad, r), 0.0);
  ASSERT_EQ(f.initialise(truth.pose, r), Status::kOk);
  EXPECT_GT(f.trackEpoch(), track) << "a restart";
  const std::uint64_t restarted = f.trackEpoch();
  f.reset();
  EXPECT_GT(f.trackEpoch(), restarted) << "a reset";
}

// carryAngularVelocity: a rate carried over a restart, uncorrelated with the rest, and not a measurement.
TEST(PoseFilter, ACarriedAngularRateIsSetUncorrelatedAndCheckedAsAnInput) {
  PoseFilter f = makeFilter();
  const Vec3 rate(0.0, 0.13, 0.0);
  const Mat3 rate_cov = 1e-4 * Mat3::Identity();
  EXPECT_EQ(f.carryAngularVelocity(rate, rate_cov), Status::kInvalidArgument) << "uninitialised";
  ASSERT_EQ(f.initialise(Pose::fromYpr({0.1, 0.1, 3.1}, Vec3(0.0, 0.0, 10.0)), trackerLikeCovariance()),
            Status::kOk);
  const std::uint64_t epoch = f.measurementEpoch();
  const Mat12 before = f.covariance();
  EXPECT_EQ(f.carryAngularVelocity(Vec3(std::nan(""), 0.0, 0.0), rate_cov), Status::kInvalidArgument);
  EXPECT_EQ(f.carryAngularVelocity(rate, -rate_cov), Status::kInvalidArgument);
  EXPECT_TRUE(f.angularVelocity().isZero(0.0)) << "a refused input left the state";
  EXPECT_EQ(f.covariance(), before);
  ASSERT_EQ(f.carryAngularVelocity(rate, rate_cov), Status::kOk);
  EXPECT_EQ(f.angularVelocity(), rate);
  const Mat12& p = f.covariance();
  EXPECT_EQ(Mat3(p.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity)), rate_cov);
  EXPECT_TRUE((p.block<3, 6>(PoseFilter::kAngularVelocity, 0).isZero(0.0)));
  EXPECT_TRUE((p.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kVelocity).isZero(0.0)));
  EXPECT_EQ(Mat6(p.topLeftCorner<6, 6>()), Mat6(before.topLeftCorner<6, 6>())) << "the pose block untouched";
  EXPECT_EQ(f.measurementEpoch(), epoch) << "not a measurement";
  // Carried on: the prediction turns at that rate.
  const Pose start = f.pose();
  ASSERT_EQ(f.predict(1.0), Status::kOk);
  EXPECT_NEAR(Eigen::AngleAxisd(f.pose().R_c_m * start.R_c_m.transpose()).angle(), 0.13, 1e-9);
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
