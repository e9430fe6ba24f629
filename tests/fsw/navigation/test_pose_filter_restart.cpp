// The two-point restart (PoseFilter::initialiseFromTwo): the rates of two consecutive fits where they are
// motion, zero where they are the fits' noise or a jump no target makes, and the covariance that says so.
#include <gtest/gtest.h>

#include "pose_filter_test_support.hpp"

namespace visnav::nav {
namespace {

using namespace pose_filter_test;  // NOLINT(google-build-using-namespace): the shared test helpers

Mat6 nearCovariance() {
  Vec6 sigma;
  sigma << 0.2 * kRadPerDeg, 0.2 * kRadPerDeg, 0.2 * kRadPerDeg, 0.02, 0.02, 0.1;
  return sigma.cwiseAbs2().asDiagonal();
}

// An approach at 7 m/s (case approach_smallsat near 60 m, 1.4 m a frame): started from one fit, the filter
// rejects the next fit; started from two, it accepts it, and over many noise draws the seeded velocity's
// error is consistent with its covariance (NEES mean 3 for 3 dof).
TEST(PoseFilterRestart, TwoFitsOfAnApproachSeedAVelocityTheNextFitAgreesWith) {
  const Mat6 cov = nearCovariance();
  const Vec3 velocity(0.3, -0.2, -7.0);
  Pcg32 rng(11);
  double nees_sum = 0.0;
  int accepted_from_one = 0;
  int accepted_from_two = 0;
  constexpr int kDraws = 400;
  for (int i = 0; i < kDraws; ++i) {
    const Pose p0 = Pose::fromYpr({0.2, -0.1, 0.3}, Vec3(0.4, -0.3, 60.0));
    Pose p1 = p0;
    p1.t_c_m += velocity * kDt;
    Pose p2 = p1;
    p2.t_c_m += velocity * kDt;
    const Pose m0 = measure(p0, cov, rng);
    const Pose m1 = measure(p1, cov, rng);
    const Pose m2 = measure(p2, cov, rng);

    PoseFilter one = makeFilter();
    ASSERT_EQ(one.initialise(m1, cov), Status::kOk);
    ASSERT_EQ(one.predict(kDt), Status::kOk);
    accepted_from_one += one.update(m2, cov).accepted ? 1 : 0;

    PoseFilter two = makeFilter();
    ASSERT_EQ(two.initialiseFromTwo(m0, cov, m1, cov, kDt), Status::kOk);
    const Vec3 err = two.velocity() - velocity;
    const Mat3 pv = two.covariance().block<3, 3>(PoseFilter::kVelocity, PoseFilter::kVelocity);
    nees_sum += err.dot(pv.ldlt().solve(err));
    ASSERT_EQ(two.predict(kDt), Status::kOk);
    accepted_from_two += two.update(m2, cov).accepted ? 1 : 0;
  }
  EXPECT_EQ(accepted_from_one, 0);
  EXPECT_GE(accepted_from_two, kDraws * 99 / 100);
  // NEES mean of 400 draws: 3 +- 3 * sqrt(2/3/400) ~ 3 +- 0.12 (1 sigma).
  EXPECT_NEAR(nees_sum / kDraws, 3.0, 0.5);
}

// The layout the documentation gives: pose block P_cur, cross-covariance P_cur / dt, rates
// (P_prev + P_cur) / dt^2, where both rates are seeded.
TEST(PoseFilterRestart, SeededRatesCarryTheTwoPointCovariance) {
  const Mat6 p_prev = nearCovariance() * 2.0;
  const Mat6 p_cur = nearCovariance();
  const Pose p0 = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 20.0));
  const Pose p1 = p0.boxPlus((Vec6() << 0.0, 0.0, 2.0 * kRadPerDeg, 0.0, 0.3, -1.0).finished());
  PoseFilter f = makeFilter();
  ASSERT_EQ(f.initialiseFromTwo(p0, p_prev, p1, p_cur, kDt), Status::kOk);
  EXPECT_NEAR(f.angularVelocity().z(), 10.0 * kRadPerDeg, 1e-12);
  EXPECT_LT((f.velocity() - Vec3(0.0, 1.5, -5.0)).norm(), 1e-12);
  EXPECT_LT((f.pose().boxMinus(p1)).norm(), 1e-15);
  Mat12 expected;
  expected << p_cur, p_cur / kDt, p_cur / kDt, (p_prev + p_cur) / (kDt * kDt);
  EXPECT_LT((f.covariance() - expected).cwiseAbs().maxCoeff(), 1e-12) << f.covariance();
}

// A still target: the difference of two fits is their noise, so no rate is seeded and the start is exactly
// initialise()'s from the second fit.
TEST(PoseFilterRestart, NoiseBetweenTwoFitsOfAStillTargetSeedsNoRate) {
  const Mat6 cov = nearCovariance();
  Pcg32 rng(5);
  int seeded = 0;
  constexpr int kDraws = 200;
  for (int i = 0; i < kDraws; ++i) {
    const Pose truth = Pose::fromYpr({0.5, 0.1, -0.2}, Vec3(0.1, 0.2, 15.0));
    const Pose m0 = measure(truth, cov, rng);
    const Pose m1 = measure(truth, cov, rng);
    PoseFilter two = makeFilter();
    ASSERT_EQ(two.initialiseFromTwo(m0, cov, m1, cov, kDt), Status::kOk);
    if (!two.velocity().isZero() || !two.angularVelocity().isZero()) {
      ++seeded;
      continue;
    }
    PoseFilter one = makeFilter();
    ASSERT_EQ(one.initialise(m1, cov), Status::kOk);
    EXPECT_EQ(two.covariance(), one.covariance());
  }
  // Two 3-dof tests at 99 % each: ~2 % of draws seed one rate by chance.
  EXPECT_LE(seeded, kDraws * 5 / 100);
}

// Ten degrees in one frame (50 deg/s) is a fit that jumped, not a turn: the angular rate starts at zero with
// its prior and nothing correlated; the approach between the two fits is still taken.
TEST(PoseFilterRestart, AJumpNoTargetMakesIsNotTakenAsARate) {
  PoseFilterParams params;
  params.initial_angular_velocity_sigma_deg_s = 4.0;
  const Mat6 cov = nearCovariance();
  const Pose p0 = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 20.0));
  const Pose p1 = p0.boxPlus((Vec6() << 10.0 * kRadPerDeg, 0.0, 0.0, 0.0, 0.0, -1.0).finished());
  PoseFilter f = makeFilter(params);
  ASSERT_EQ(f.initialiseFromTwo(p0, cov, p1, cov, kDt), Status::kOk);
  EXPECT_TRUE(f.angularVelocity().isZero());
  EXPECT_NEAR(f.velocity().z(), -5.0, 1e-12);
  const Mat12& p = f.covariance();
  const double sw2 = std::pow(4.0 * kRadPerDeg, 2);
  EXPECT_EQ(Mat3(p.block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity)),
            Mat3(Mat3::Identity() * sw2));
  for (int i = 0; i < 12; ++i) {
    if (i >= PoseFilter::kAngularVelocity && i < PoseFilter::kAngularVelocity + 3) continue;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(p(PoseFilter::kAngularVelocity + k, i), 0.0);
  }
  // Raised above the jump's rate, the same pair seeds it.
  params.restart_max_rate_deg_s = 60.0;
  PoseFilter g = makeFilter(params);
  ASSERT_EQ(g.initialiseFromTwo(p0, cov, p1, cov, kDt), Status::kOk);
  EXPECT_NEAR(g.angularVelocity().norm(), 50.0 * kRadPerDeg, 1e-9);
}

TEST(PoseFilterRestart, RejectsInvalidInputsAndLeavesTheStateUntouched) {
  const Mat6 cov = nearCovariance();
  const Pose p0 = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 20.0));
  const Pose p1 = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 19.0));
  PoseFilter f = makeFilter();
  ASSERT_EQ(f.initialise(p0, cov), Status::kOk);
  const Mat12 before = f.covariance();
  Pose bad = p0;
  bad.t_c_m.x() = std::nan("");
  EXPECT_EQ(f.initialiseFromTwo(p0, cov, p1, cov, 0.0), Status::kInvalidArgument);
  EXPECT_EQ(f.initialiseFromTwo(p0, cov, p1, cov, -0.2), Status::kInvalidArgument);
  EXPECT_EQ(f.initialiseFromTwo(p0, cov, p1, cov, 1e3), Status::kInvalidArgument);  // > max_prediction_s
  EXPECT_EQ(f.initialiseFromTwo(bad, cov, p1, cov, kDt), Status::kInvalidArgument);
  EXPECT_EQ(f.initialiseFromTwo(p0, cov, bad, cov, kDt), Status::kInvalidArgument);
  EXPECT_EQ(f.initialiseFromTwo(p0, Mat6::Zero(), p1, cov, kDt), Status::kInvalidArgument);
  EXPECT_EQ(f.initialiseFromTwo(p0, cov, p1, -cov, kDt), Status::kInvalidArgument);
  EXPECT_EQ(f.covariance(), before);
  EXPECT_EQ(f.pose().t_c_m, p0.t_c_m);
  EXPECT_TRUE(f.velocity().isZero());
}

}  // namespace
}  // namespace visnav::nav
