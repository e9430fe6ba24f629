// The square spiral that orders the close-range acquisition's tiles (square_spiral.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <utility>

#include "visnav/navigation/square_spiral.hpp"

namespace visnav::nav {
namespace {

TEST(SquareSpiral, VisitsEveryCellOfEachRingOnceRingByRing) {
  for (int rings = 0; rings <= 6; ++rings) {
    std::set<std::pair<int, int>> seen;
    for (int k = 0; k < squareSpiralCells(rings); ++k) {
      const Eigen::Vector2i c = squareSpiralCell(k);
      const int ring = std::max(std::abs(c.x()), std::abs(c.y()));
      // Index k belongs to the ring whose cells it counts past: the walk never leaves a ring early.
      EXPECT_LE(ring, rings) << "index " << k;
      EXPECT_GE(k, squareSpiralCells(ring - 1)) << "index " << k << " left ring " << ring - 1 << " early";
      EXPECT_LT(k, squareSpiralCells(ring)) << "index " << k;
      EXPECT_TRUE(seen.insert({c.x(), c.y()}).second) << "cell (" << c.x() << ", " << c.y() << ") twice";
    }
    EXPECT_EQ(static_cast<int>(seen.size()), (2 * rings + 1) * (2 * rings + 1));
  }
}

TEST(SquareSpiral, NeighbouringIndicesAreNeighbouringCellsWithinARing) {
  // Walked round, not scattered: consecutive cells of one ring touch (8-neighbourhood), so a window walk
  // sweeps the disc instead of jumping across it.
  for (int k = 1; k < squareSpiralCells(5) - 1; ++k) {
    const Eigen::Vector2i a = squareSpiralCell(k);
    const Eigen::Vector2i b = squareSpiralCell(k + 1);
    const bool same_ring =
        std::max(std::abs(a.x()), std::abs(a.y())) == std::max(std::abs(b.x()), std::abs(b.y()));
    if (!same_ring) continue;
    EXPECT_LE(std::abs(a.x() - b.x()), 1) << "index " << k;
    EXPECT_LE(std::abs(a.y() - b.y()), 1) << "index " << k;
  }
  EXPECT_EQ(squareSpiralCell(0), Eigen::Vector2i(0, 0));
  EXPECT_EQ(squareSpiralCell(-3), Eigen::Vector2i(0, 0));
  EXPECT_EQ(squareSpiralCells(-1), 0);
}

}  // namespace
}  // namespace visnav::nav
