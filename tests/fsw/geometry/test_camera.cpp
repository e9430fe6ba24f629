#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

// Issue 13 item 11: intrinsics outside a physical range and a fold-over distortion are not a camera.
TEST(CameraCheck, AcceptsRealCameras) {
  std::string problem;
  EXPECT_TRUE(checkIntrinsics(distortedVga(), problem)) << problem;
  CameraIntrinsics plain = distortedVga();
  plain.distortion = Distortion{};
  EXPECT_TRUE(checkIntrinsics(plain, problem)) << problem;
}

TEST(CameraCheck, RejectsIntrinsicsOutsideThePhysicalRange) {
  const auto rejected = [](void (*edit)(CameraIntrinsics&), const char* word) {
    CameraIntrinsics k = distortedVga();
    edit(k);
    std::string problem;
    EXPECT_FALSE(checkIntrinsics(k, problem)) << word;
    EXPECT_NE(problem.find(word), std::string::npos) << problem << " (expected '" << word << "')";
  };
  rejected([](CameraIntrinsics& k) { k.fx_px = 1e308; }, "fx_px");
  rejected([](CameraIntrinsics& k) { k.fy_px = 1e-308; }, "fy_px");
  rejected([](CameraIntrinsics& k) { k.fx_px = 0.5; }, "fx_px");
  rejected([](CameraIntrinsics& k) { k.fx_px = 20.0 * k.fy_px; }, "fx_px / fy_px");
  rejected([](CameraIntrinsics& k) { k.skew = 1e300; }, "skew");
  rejected([](CameraIntrinsics& k) { k.cx_px = 1e300; }, "principal point");
  rejected([](CameraIntrinsics& k) { k.cy_px = -481.0; }, "principal point");
  rejected([](CameraIntrinsics& k) { k.width_px = 0; }, "image size");
  rejected([](CameraIntrinsics& k) { k.distortion.k2 = std::nan(""); }, "not finite");
}

TEST(CameraCheck, RejectsFoldOverDistortion) {
  CameraIntrinsics k = distortedVga();
  k.distortion = {-50.0, 0.0, 0.0, 0.0,
                  0.0};  // r (1 - 50 r^2) turns back at r = 0.08; the corners sit at 0.4
  std::string problem;
  EXPECT_FALSE(checkIntrinsics(k, problem));
  EXPECT_NE(problem.find("folds over"), std::string::npos) << problem;
  // Mild pincushion and barrel lenses are fine; a strong k2 that turns the map back inside the image is not.
  k.distortion = {0.3, 0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(checkIntrinsics(k, problem)) << problem;
  k.distortion = {0.0, -8.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(checkIntrinsics(k, problem));
}

TEST(CameraCheck, RejectsDistortionTheUndistortionCannotInvert) {
  CameraIntrinsics k = distortedVga();
  k.distortion = {0.0, 0.0, 0.0, 2.0, 0.0};  // tangential only: passes the radial test
  std::string problem;
  EXPECT_FALSE(checkIntrinsics(k, problem));
  EXPECT_NE(problem.find("cannot be inverted"), std::string::npos) << problem;
}

}  // namespace
}  // namespace visnav
