#include <gtest/gtest.h>

#include "visnav/geometry/camera.hpp"

namespace visnav {
namespace {

CameraIntrinsics distortedVga() {
  CameraIntrinsics k = CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.001, 320.0, 240.0);
  k.distortion = {-0.12, 0.05, -0.01, 0.0008, -0.0005};
  return k;
}

TEST(Camera, SiParametersGiveFocalLengthInPixels) {
  const CameraIntrinsics k = CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 7.5e-6, 0.0, 320.0, 240.0);
  EXPECT_DOUBLE_EQ(k.fx_px, 1000.0);
  EXPECT_DOUBLE_EQ(k.fy_px, 800.0);
}

TEST(Camera, OpticalAxisHitsPrincipalPoint) {
  const PinholeCamera cam(distortedVga());
  Vec2 px;
  ASSERT_TRUE(cam.project(Vec3(0, 0, 10), px));
  EXPECT_NEAR(px.x(), 320.0, 1e-12);
  EXPECT_NEAR(px.y(), 240.0, 1e-12);
}

TEST(Camera, PointBehindCameraIsRejected) {
  const PinholeCamera cam(distortedVga());
  Vec2 px;
  EXPECT_FALSE(cam.project(Vec3(0, 0, -1), px));
  EXPECT_FALSE(cam.projectIdeal(Vec3(1, 0, 0), px));
}

TEST(Camera, UndistortInvertsDistortAcrossTheImage) {
  const PinholeCamera cam(distortedVga());
  for (int y = 0; y <= 480; y += 60) {
    for (int x = 0; x <= 640; x += 80) {
      const Vec2 ideal(x, y);
      const Vec2 raw = cam.distortPixel(ideal);
      const Vec2 back = cam.undistortPixel(raw);
      EXPECT_NEAR((back - ideal).norm(), 0.0, 1e-6) << x << "," << y;
    }
  }
}

TEST(Camera, DistortionMovesCornersInwardForBarrelLens) {
  const PinholeCamera cam(distortedVga());
  const Vec2 raw = cam.distortPixel(Vec2(0.0, 0.0));
  EXPECT_GT(raw.x(), 0.5);
  EXPECT_GT(raw.y(), 0.5);
}

TEST(Camera, BearingRoundTripsWithProject) {
  const PinholeCamera cam(distortedVga());
  const Vec3 p(1.2, -0.7, 9.0);
  Vec2 px;
  ASSERT_TRUE(cam.project(p, px));
  EXPECT_NEAR((cam.bearing(px) - p.normalized()).norm(), 0.0, 1e-9);
}

TEST(Camera, IdealProjectionJacobianMatchesCentralDifferences) {
  const PinholeCamera cam(distortedVga());
  const Vec3 p(0.4, -0.3, 7.0);
  Vec2 px;
  Mat23 j;
  ASSERT_TRUE(cam.projectIdeal(p, px, &j));
  const double h = 1e-6;
  for (int c = 0; c < 3; ++c) {
    Vec3 dp = Vec3::Zero();
    dp[c] = h;
    Vec2 plus, minus;
    cam.projectIdeal(p + dp, plus);
    cam.projectIdeal(p - dp, minus);
    const Vec2 numeric = (plus - minus) / (2 * h);
    EXPECT_NEAR((numeric - j.col(c)).norm(), 0.0, 1e-5) << "column " << c;
  }
}

}  // namespace
}  // namespace visnav
