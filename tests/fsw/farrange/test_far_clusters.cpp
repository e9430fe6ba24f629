// Cluster analysis (sec. III-B): spawn/grow thresholds, 8-connectivity, eq. 15, hole filling, capacities.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "visnav/farrange/cluster_finder.hpp"

namespace visnav::far {
namespace {

struct Response {
  ResponseImage image;
  std::vector<std::uint8_t> row_max;
  Response(int w, int h) : row_max(static_cast<std::size_t>(h), 0) {
    image.init(w, h);
    image.setRoi(Roi::full(w, h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) image.row(y)[x] = 0;
  }
  void set(int x, int y, std::uint8_t v) {
    image.row(y)[x] = v;
    row_max[static_cast<std::size_t>(y)] = std::max(row_max[static_cast<std::size_t>(y)], v);
  }
};

constexpr std::uint8_t kIn = 229;   // t_in = 0.9
constexpr std::uint8_t kOut = 127;  // t_out = 0.5

TEST(ClusterFinder, SpawnsAboveTinAndGrowsAboveTout) {
  Response r(20, 10);
  for (int x = 2; x < 8; ++x) r.set(x, 3, 200);    // above t_out only...
  r.set(5, 3, 240);                                // ...with one spawn pixel
  for (int x = 12; x < 16; ++x) r.set(x, 6, 200);  // above t_out, no spawn pixel: no cluster
  r.set(9, 3, 127);                                // exactly t_out: not above it
  ClusterFinder finder;
  finder.init(20, 10, 8, 100);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  const Cluster& c = finder.clusters()[0];
  EXPECT_EQ(c.pixel_count, 6);
  EXPECT_NEAR(c.com_px.x(), 5.0, 1e-12);  // columns 2..7: centres 2.5 .. 7.5
  EXPECT_NEAR(c.com_px.y(), 3.5, 1e-12);
  EXPECT_EQ(c.peak_response, 240);
}

TEST(ClusterFinder, DiagonalNeighboursJoin) {
  Response r(10, 10);
  for (int i = 0; i < 5; ++i) r.set(2 + i, 2 + i, 255);
  ClusterFinder finder;
  finder.init(10, 10, 8, 100);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  EXPECT_EQ(finder.clusters()[0].pixel_count, 5);
  // Pixels (i, i): variances 2 + 1/12, covariance 2 -> eigenvalues 4 + 1/12 and 1/12, axis ratio 7.
  EXPECT_NEAR(finder.clusters()[0].axis_ratio, 7.0, 1e-9);
}

TEST(ClusterFinder, CircularityIsEq15) {
  Response r(40, 40);
  int n = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      if (std::hypot(x + 0.5 - 20.0, y + 0.5 - 20.0) <= 8.0) {
        r.set(x, y, 255);
        ++n;
      }
  ClusterFinder finder;
  finder.init(40, 40, 8, 1000);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  const Cluster& c = finder.clusters()[0];
  EXPECT_EQ(c.pixel_count, n);
  double r_max = 0.0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x)
      if (r.image.row(y)[x] > kOut) r_max = std::max(r_max, std::hypot(x + 0.5 - 20.0, y + 0.5 - 20.0));
  EXPECT_NEAR(c.max_radius_px, r_max, 1e-9);
  EXPECT_NEAR(c.circularity, std::exp(-std::abs(std::sqrt(n / kPi) - r_max)), 1e-12);
  EXPECT_NEAR(c.axis_ratio, 1.0, 0.01);
}

TEST(ClusterFinder, FillHolesCountsTheEnclosedAreaAndItsOutline) {
  // A 10 x 8 rectangle outline (1 px wide) with a separate pixel inside: filled = 80, outline = 32.
  Response r(30, 30);
  for (int x = 5; x < 15; ++x) {
    r.set(x, 5, 255);
    r.set(x, 12, 255);
  }
  for (int y = 5; y < 13; ++y) {
    r.set(5, y, 255);
    r.set(14, y, 255);
  }
  r.set(9, 8, 255);  // its own cluster, inside the hole
  ClusterFinder finder;
  finder.init(30, 30, 8, 1000);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 2U);
  Cluster& ring = finder.clusters()[0];
  EXPECT_EQ(ring.pixel_count, 32);
  finder.fillHoles(ring);
  EXPECT_EQ(ring.filled_count, 80);
  EXPECT_EQ(ring.boundary_count, 32);
  EXPECT_NEAR(ring.axis_ratio, 10.0 / 8.0, 1e-9);  // of the filled 10 x 8 block, not of its outline
  EXPECT_NEAR(ring.filled_com_px.x(), 10.0, 1e-12);
  EXPECT_NEAR(ring.filled_com_px.y(), 9.0, 1e-12);
  // An open ring (a gap in the outline) encloses nothing.
  r.image.row(12)[10] = 0;
  r.image.row(12)[11] = 0;
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  Cluster& open = finder.clusters()[0];
  finder.fillHoles(open);
  EXPECT_EQ(open.filled_count, open.pixel_count);
}

// A 20 x 16 rectangle outline, 1 px wide, at (5, 5)..(24, 20), without the pixels of `gaps` on its bottom
// row.
Response rectangleOutline(const std::vector<int>& gaps) {
  Response r(40, 40);
  for (int x = 5; x < 25; ++x) {
    r.set(x, 5, 255);
    if (std::find(gaps.begin(), gaps.end(), x) == gaps.end()) r.set(x, 20, 255);
  }
  for (int y = 6; y < 20; ++y) {
    r.set(5, y, 255);
    r.set(24, y, 255);
  }
  return r;
}

TEST(ClusterFinder, TheHullOfAnOutlineWithAGapIsItsSilhouetteAndTheGapIsWhatItMisses) {
  // 8 px missing from the bottom side: the flood fill encloses nothing, the hull is the 20 x 16 block.
  Response r = rectangleOutline({11, 12, 13, 14, 15, 16, 17, 18});
  ClusterFinder finder;
  finder.init(40, 40, 8, 1000);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  Cluster& c = finder.clusters()[0];
  EXPECT_EQ(c.pixel_count, 2 * 20 + 2 * 14 - 8);
  finder.fillHoles(c);
  EXPECT_EQ(c.filled_count, c.pixel_count);
  const int members[1] = {0};
  OutlineHull h;
  ASSERT_TRUE(finder.outlineHull(members, 1, 2, 0.0, h));
  EXPECT_NEAR(h.area_px, 20.0 * 16.0, 1e-9);  // 19 x 15 over pixel centres, plus half the perimeter and 1
  EXPECT_NEAR(h.perimeter_px, 2.0 * (19.0 + 15.0), 1e-9);
  EXPECT_NEAR(h.centre_px.x(), 15.0, 1e-9);
  EXPECT_NEAR(h.centre_px.y(), 13.0, 1e-9);
  EXPECT_NEAR(h.max_radius_px, std::hypot(9.5, 7.5), 1e-9);
  EXPECT_EQ(h.pixel_count, c.pixel_count);
  // Of the 68 1-px steps around it, those more than 2 px from an outline pixel: x = 13..16 on the bottom.
  EXPECT_NEAR(h.coverage, 64.0 / 68.0, 1e-12);
  EXPECT_DOUBLE_EQ(h.concentration, 1.0);  // every outline pixel lies on the hull
  EXPECT_EQ(h.x_min, 5);
  EXPECT_EQ(h.y_min, 5);
  EXPECT_EQ(h.x_max, 24);
  EXPECT_EQ(h.y_max, 20);
}

TEST(ClusterFinder, AnOpenArcCoversLittleOfItsHullAndTwoPartsOfAnOutlineCoverTheirs) {
  // The top and left sides only (an "L"): the hull is a triangle whose long side has no outline near it.
  Response arc(40, 40);
  for (int x = 5; x < 25; ++x) arc.set(x, 5, 255);
  for (int y = 6; y < 21; ++y) arc.set(5, y, 255);
  ClusterFinder finder;
  finder.init(40, 40, 8, 1000);
  finder.find(arc.image, arc.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  const int one[1] = {0};
  OutlineHull h;
  ASSERT_TRUE(finder.outlineHull(one, 1, 2, 0.0, h));
  EXPECT_LT(h.coverage, 0.75);  // [farrange] outline_min_coverage is 0.8
  EXPECT_NEAR(h.area_px, 0.5 * 19.0 * 15.0 + 0.5 * h.perimeter_px + 1.0, 1e-9);
  // The rectangle broken on its bottom and on its right side: two clusters, whose joint hull is the block.
  Response broken = rectangleOutline({14, 15, 16});
  broken.image.row(12)[24] = 0;
  broken.image.row(13)[24] = 0;
  finder.find(broken.image, broken.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 2U);
  const int both[2] = {0, 1};
  ASSERT_TRUE(finder.outlineHull(both, 2, 2, 0.0, h));
  EXPECT_NEAR(h.area_px, 20.0 * 16.0, 1e-9);
  EXPECT_EQ(h.pixel_count, 2 * 20 + 2 * 14 - 3 - 2);
  EXPECT_DOUBLE_EQ(h.coverage, 1.0);  // no gap wider than twice the reach
  // A line has no hull.
  Response line(40, 40);
  for (int x = 5; x < 25; ++x) line.set(x, 9, 255);
  finder.find(line.image, line.row_max.data(), kIn, kOut);
  EXPECT_FALSE(finder.outlineHull(one, 1, 2, 0.0, h));
}

TEST(ClusterFinder, MostPixelsOfAnOutlineLieAlongItsHullNotThoseOfAFrameAroundABlob) {
  // A 40 x 40 frame (156 px) holding a 20 x 20 block (400 px) joined to its top side by a 9 px line: the
  // frame covers the hull's whole boundary, but of the 565 pixels only the frame's and the line's first 3
  // lie within 3 px of it. With a min_coverage the hull does not reach, the concentration is not computed.
  Response r(60, 60);
  for (int i = 5; i < 45; ++i) {
    r.set(i, 5, 255);
    r.set(i, 44, 255);
    r.set(5, i, 255);
    r.set(44, i, 255);
  }
  for (int y = 6; y < 15; ++y) r.set(24, y, 255);
  for (int y = 15; y < 35; ++y)
    for (int x = 15; x < 35; ++x) r.set(x, y, 255);
  ClusterFinder finder;
  finder.init(60, 60, 8, 4000);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  ASSERT_EQ(finder.clusters().size(), 1U);
  ASSERT_EQ(finder.clusters()[0].pixel_count, 565);
  const int one[1] = {0};
  OutlineHull h;
  ASSERT_TRUE(finder.outlineHull(one, 1, 2, 0.8, h));
  EXPECT_DOUBLE_EQ(h.coverage, 1.0);
  EXPECT_NEAR(h.concentration, 159.0 / 565.0, 1e-12);
  ASSERT_TRUE(finder.outlineHull(one, 1, 2, 1.5, h));
  EXPECT_EQ(h.concentration, 0.0);
}

TEST(ClusterFinder, CapacitiesAreReportedNotExceeded) {
  Response r(20, 20);
  for (int y = 0; y < 20; y += 2)
    for (int x = 0; x < 20; x += 2) r.set(x, y, 255);  // 100 isolated spawn pixels
  ClusterFinder finder;
  finder.init(20, 20, 10, 1000);
  finder.find(r.image, r.row_max.data(), kIn, kOut);
  EXPECT_EQ(finder.clusters().size(), 10U);
  EXPECT_EQ(finder.seedsSkipped(), 90);
  Response big(20, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) big.set(x, y, 255);
  ClusterFinder small;
  small.init(20, 20, 10, 50);
  small.find(big.image, big.row_max.data(), kIn, kOut);
  EXPECT_TRUE(small.pixelCapacityHit());
  ASSERT_GE(small.clusters().size(), 1U);
  EXPECT_TRUE(small.clusters()[0].truncated);
  EXPECT_EQ(small.pixels().size(), 50U);
}

TEST(ClusterFinder, StaysInsideTheRoiAndForgetsTheLastFrame) {
  Response r(30, 30);
  for (int x = 0; x < 30; ++x) r.set(x, 10, 255);
  r.image.setRoi(Roi{5, 5, 10, 10});  // rows/columns 5..14 of the same map
  ResponseImage roi_image;
  roi_image.init(30, 30);
  roi_image.setRoi(Roi{5, 5, 10, 10});
  std::vector<std::uint8_t> row_max(10, 0);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      roi_image.row(y)[x] = (y + 5 == 10) ? 255 : 0;
      row_max[static_cast<std::size_t>(y)] =
          std::max(row_max[static_cast<std::size_t>(y)], roi_image.row(y)[x]);
    }
  ClusterFinder finder;
  finder.init(30, 30, 8, 100);
  for (int frame = 0; frame < 3; ++frame) {  // labels from the last frame must not block this one
    finder.find(roi_image, row_max.data(), kIn, kOut);
    ASSERT_EQ(finder.clusters().size(), 1U);
    EXPECT_EQ(finder.clusters()[0].pixel_count, 10);
    EXPECT_TRUE(finder.clusters()[0].at_roi_border);
  }
}

}  // namespace
}  // namespace visnav::far
