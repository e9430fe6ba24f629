#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "visnav/nearrange/ransac_line.hpp"
#include "visnav/nearrange/surface_visibility.hpp"

namespace visnav {
namespace {

TEST(RansacLine, RejectsOutliersAndRefits) {
  Vec2 pts[40];
  Pcg32 noise(3);
  for (int i = 0; i < 40; ++i) {
    const double x = 10.0 + 5.0 * i;
    pts[i] = Vec2(x, 0.5 * x + 20.0 + 0.1 * (noise.uniform() - 0.5));
  }
  pts[3].y() += 15.0;
  pts[17].y() -= 6.0;
  pts[30].y() += 3.0;
  std::uint8_t inlier[40];
  Vec2 scratch[40];
  Pcg32 rng(11);
  const RansacResult r = fitLineRansac(pts, 40, RansacParams{}, rng, inlier, scratch);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.inliers, 37);
  EXPECT_EQ(inlier[3], 0);
  EXPECT_EQ(inlier[17], 0);
  EXPECT_EQ(inlier[30], 0);
  EXPECT_LT(std::fabs(r.line.signedDistance(Vec2(100.0, 70.0))), 0.05);
  EXPECT_LT(r.rms_px, 0.05);
}

TEST(RansacLine, SameSeedSameResult) {
  Vec2 pts[25];
  Pcg32 gen(5);
  for (int i = 0; i < 25; ++i) pts[i] = Vec2(gen.uniform() * 100.0, gen.uniform() * 100.0);
  std::uint8_t in1[25], in2[25];
  Vec2 scratch[25];
  Pcg32 a(42), b(42);
  const RansacResult r1 = fitLineRansac(pts, 25, RansacParams{}, a, in1, scratch);
  const RansacResult r2 = fitLineRansac(pts, 25, RansacParams{}, b, in2, scratch);
  EXPECT_EQ(r1.line.theta_rad, r2.line.theta_rad);
  EXPECT_EQ(r1.line.rho_px, r2.line.rho_px);
  EXPECT_EQ(0, std::memcmp(in1, in2, sizeof(in1)));
}

TEST(RansacLine, TooFewPointsFails) {
  Vec2 pts[1] = {Vec2(1, 2)};
  std::uint8_t inlier[1];
  Vec2 scratch[1];
  Pcg32 rng(1);
  EXPECT_FALSE(fitLineRansac(pts, 1, RansacParams{}, rng, inlier, scratch).ok);
}

/// Plate facing the camera, tilted about the model y axis by `obliquity_deg`.
Pose plateTilted(double obliquity_deg) {
  return Pose::fromYpr({0.0, obliquity_deg * kRadPerDeg, kPi}, Vec3(0.0, 0.0, 10.0));
}

// The consensus set's scatter, cut at the threshold, gives back the points' own sigma.
TEST(RansacLine, UncutScatterGivesBackTheSigmaTheThresholdCut) {
  constexpr double kThreshold = 0.9;
  for (const double sigma : {0.45, 0.6, 0.8}) {
    Pcg32 gen(17);
    double sum_sq = 0.0;
    int kept = 0;
    for (int i = 0; i < 200000; ++i) {
      // Box-Muller normal draw.
      const double u1 = 1.0 - gen.uniform();
      const double d = sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * gen.uniform());
      if (std::fabs(d) > kThreshold) continue;
      sum_sq += d * d;
      ++kept;
    }
    const double cut_variance = sum_sq / kept;
    EXPECT_LT(std::sqrt(cut_variance), 0.9 * sigma) << "the cut must shrink sigma " << sigma;
    EXPECT_NEAR(std::sqrt(uncutScatterVariance(cut_variance, kThreshold)), sigma, 0.03 * sigma) << sigma;
  }
}

TEST(RansacLine, UncutScatterKeepsASmallScatterAndCapsAFullBand) {
  EXPECT_EQ(uncutScatterVariance(0.1 * 0.1, 0.9), 0.1 * 0.1);  // a tenth of the threshold: no cut to undo
  // A uniform band fills the threshold: any sigma above twice the threshold looks the same.
  EXPECT_DOUBLE_EQ(uncutScatterVariance(0.9 * 0.9 / 3.0, 0.9), 1.8 * 1.8);
  EXPECT_EQ(uncutScatterVariance(0.0, 0.9), 0.0);
  EXPECT_EQ(uncutScatterVariance(-1.0, 0.9), 0.0);
  EXPECT_EQ(uncutScatterVariance(0.1, 0.0), 0.0);
  EXPECT_EQ(uncutScatterVariance(std::nan(""), 0.9), 0.0);
}

TEST(SurfaceVisibility, HeadOnIsNinetyDegrees) {
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  const SurfaceView view = viewSurface(plate.surfaces()[0], plateTilted(0.0));
  EXPECT_TRUE(view.front_facing);
  EXPECT_NEAR(view.v_deg, 90.0, 1e-9);
}

TEST(SurfaceVisibility, HysteresisStartsAt45AndStopsAt40) {
  const PolygonModel plate = makeRectanglePlate(0.01, 0.01);  // tiny: line of sight ~ optical axis
  const ModelSurface& s = plate.surfaces()[0];
  const VisibilityThresholds t;
  for (double sign : {-1.0, 1.0}) {
    // obliquity 42 deg => v = 48 or 132: inside the enter band.
    EXPECT_TRUE(updateVisibility(false, viewSurface(s, plateTilted(sign * 42.0)), t));
    // obliquity 47 deg => v = 43 or 137: a tracked surface stays, an untracked one does not start.
    EXPECT_TRUE(updateVisibility(true, viewSurface(s, plateTilted(sign * 47.0)), t));
    EXPECT_FALSE(updateVisibility(false, viewSurface(s, plateTilted(sign * 47.0)), t));
    // obliquity 52 deg => v = 38 or 142: tracking stops.
    EXPECT_FALSE(updateVisibility(true, viewSurface(s, plateTilted(sign * 52.0)), t));
  }
  const SurfaceView v1 = viewSurface(s, plateTilted(-47.0));
  const SurfaceView v2 = viewSurface(s, plateTilted(47.0));
  EXPECT_NEAR(v1.v_deg + v2.v_deg, 180.0, 1e-6);  // the two sides of the fold
}

TEST(SurfaceVisibility, BackFaceIsNeverTracked) {
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  const Pose away = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 10.0));  // normal +z_c: facing away
  const SurfaceView view = viewSurface(plate.surfaces()[0], away);
  EXPECT_FALSE(view.front_facing);
  EXPECT_FALSE(updateVisibility(true, view, VisibilityThresholds{}));
  EXPECT_FALSE(updateVisibility(false, view, VisibilityThresholds{}));
}

}  // namespace
}  // namespace visnav
