#include <gtest/gtest.h>

#include <cmath>

#include "visnav/geometry/line2d.hpp"

namespace visnav {
namespace {

TEST(Line2d, ThroughPointsContainsBoth) {
  const Vec2 a(10, 20), b(200, -35);
  const Line2d l = Line2d::throughPoints(a, b);
  EXPECT_NEAR(l.signedDistance(a), 0.0, 1e-9);
  EXPECT_NEAR(l.signedDistance(b), 0.0, 1e-9);
}

TEST(Line2d, FitRecoversVerticalAndHorizontalLines) {
  Vec2 pts[5];
  for (int i = 0; i < 5; ++i) pts[i] = Vec2(42.5, 10.0 * i);
  Line2d l;
  ASSERT_TRUE(Line2d::fit(pts, 5, l));
  EXPECT_NEAR(std::fabs(std::cos(l.theta_rad)), 1.0, 1e-12);
  EXPECT_NEAR(std::fabs(l.rho_px), 42.5, 1e-9);
  for (int i = 0; i < 5; ++i) pts[i] = Vec2(10.0 * i, 7.25);
  ASSERT_TRUE(Line2d::fit(pts, 5, l));
  EXPECT_NEAR(std::fabs(std::sin(l.theta_rad)), 1.0, 1e-12);
  EXPECT_NEAR(std::fabs(l.rho_px), 7.25, 1e-9);
}

TEST(Line2d, FitNeedsTwoDistinctPoints) {
  Vec2 pts[3] = {Vec2(1, 1), Vec2(1, 1), Vec2(1, 1)};
  Line2d l;
  EXPECT_FALSE(Line2d::fit(pts, 1, l));
  EXPECT_FALSE(Line2d::fit(pts, 3, l));
}

TEST(Line2d, IntersectionWorksWhenFirstLineIsVertical) {
  // The paper's eq. 6 divides by sin(theta1): a vertical first line (theta1 = 0) breaks it; ours must not.
  const Line2d vertical{0.0, 100.0};
  const Line2d slanted = Line2d::throughPoints(Vec2(0, 0), Vec2(200, 100));
  Vec2 p;
  ASSERT_TRUE(intersect(vertical, slanted, p));
  EXPECT_NEAR(p.x(), 100.0, 1e-9);
  EXPECT_NEAR(p.y(), 50.0, 1e-9);
}

TEST(Line2d, ParallelLinesDoNotIntersect) {
  Vec2 p;
  EXPECT_FALSE(intersect(Line2d{0.3, 1.0}, Line2d{0.3, 5.0}, p));
}

}  // namespace
}  // namespace visnav
