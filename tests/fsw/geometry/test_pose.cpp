#include <gtest/gtest.h>

#include <cmath>

#include "visnav/geometry/pose.hpp"

namespace visnav {
namespace {

TEST(Pose, YawAloneRotatesXTowardsY) {
  const Mat3 r = rotationFromYpr({90.0 * kRadPerDeg, 0.0, 0.0});
  EXPECT_NEAR((r * Vec3::UnitX() - Vec3::UnitY()).norm(), 0.0, 1e-12);
}

TEST(Pose, DinOrderIsYawThenPitchThenRoll) {
  const YawPitchRoll ypr{0.3, -0.2, 0.1};
  const Mat3 expected = (Eigen::AngleAxisd(0.3, Vec3::UnitZ()) * Eigen::AngleAxisd(-0.2, Vec3::UnitY()) *
                         Eigen::AngleAxisd(0.1, Vec3::UnitX()))
                            .toRotationMatrix();
  EXPECT_NEAR((rotationFromYpr(ypr) - expected).norm(), 0.0, 1e-12);
}

TEST(Pose, YprRoundTripsAwayFromGimbalLock) {
  for (double yaw = -3.0; yaw <= 3.0; yaw += 0.7)
    for (double pitch = -1.5; pitch <= 1.5; pitch += 0.5)
      for (double roll = -3.0; roll <= 3.0; roll += 0.9) {
        const YawPitchRoll back = yprFromRotation(rotationFromYpr({yaw, pitch, roll}));
        EXPECT_NEAR(back.yaw_rad, yaw, 1e-9);
        EXPECT_NEAR(back.pitch_rad, pitch, 1e-9);
        EXPECT_NEAR(back.roll_rad, roll, 1e-9);
      }
}

TEST(Pose, GimbalLockStillReproducesTheRotation) {
  const Mat3 r = rotationFromYpr({0.4, 0.5 * kPi, 0.3});
  const YawPitchRoll back = yprFromRotation(r);
  EXPECT_DOUBLE_EQ(back.roll_rad, 0.0);
  EXPECT_NEAR((rotationFromYpr(back) - r).norm(), 0.0, 1e-9);
}

TEST(Pose, ExpLogRoundTripIncludingNearPi) {
  const Vec3 axes[] = {Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8).normalized(), Vec3(0, 0, 1)};
  for (const Vec3& axis : axes)
    for (double angle : {0.0, 1e-9, 0.1, 1.0, 3.0, kPi - 1e-7}) {
      const Vec3 w = axis * angle;
      EXPECT_NEAR((logSo3(expSo3(w)) - w).norm(), 0.0, 1e-6) << angle;
      EXPECT_NEAR((expSo3(w) - Eigen::AngleAxisd(angle, axis).toRotationMatrix()).norm(), 0.0, 1e-12);
    }
}

TEST(Pose, BoxPlusAndBoxMinusAreInverse) {
  const Pose a = Pose::fromYpr({0.2, 0.1, -0.3}, Vec3(0.1, -0.2, 12.0));
  Vec6 d;
  d << 0.01, -0.02, 0.03, 0.1, 0.2, -0.3;
  const Pose b = a.boxPlus(d);
  EXPECT_NEAR((a.boxMinus(b) - d).norm(), 0.0, 1e-12);
}

TEST(Pose, QuaternionMatchesRotation) {
  const Pose p = Pose::fromYpr({0.2, 0.1, -0.3}, Vec3::Zero());
  const Pose q = Pose::fromQuaternion(p.quaternion(), Vec3::Zero());
  EXPECT_NEAR((p.R_c_m - q.R_c_m).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace visnav
