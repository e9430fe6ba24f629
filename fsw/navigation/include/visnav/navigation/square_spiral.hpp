// Cells of a square grid in the order of a spiral from its centre: cell 0 is (0, 0), ring n >= 1 holds the
// 8 n cells with max(|x|, |y|) = n, walked once round. The close-range acquisition's tiles over a searched
// disc (reacquire_acquisition_tiles) take their offsets from it.
#pragma once

#include <Eigen/Core>

namespace visnav::nav {

/// Number of cells in rings 0..rings: (2 rings + 1)^2.
constexpr int squareSpiralCells(int rings) { return rings < 0 ? 0 : (2 * rings + 1) * (2 * rings + 1); }

/// The cell of spiral index `index` (>= 0; a negative index is the centre).
inline Eigen::Vector2i squareSpiralCell(int index) {
  if (index <= 0) return {0, 0};
  int ring = 1;
  while (squareSpiralCells(ring) <= index) ++ring;    // bounded: ring^2 grows past index
  const int m = index - squareSpiralCells(ring - 1);  // 0 .. 8 ring - 1
  const int side = m / (2 * ring);
  const int along = m % (2 * ring);
  switch (side) {
    case 0: return {ring, -ring + 1 + along};    // right side, downwards in y
    case 1: return {ring - 1 - along, ring};     // bottom, leftwards
    case 2: return {-ring, ring - 1 - along};    // left side, upwards
    default: return {-ring + 1 + along, -ring};  // top, rightwards
  }
}

}  // namespace visnav::nav
