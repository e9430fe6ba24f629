// Exact area-coverage rasterisation of closed polygons made of straight segments in pixel coordinates, by
// signed-area accumulation per pixel cell (the font-rasteriser method): every segment deposits its signed
// area into per-row difference cells; a running sum along each row yields the covered area fraction of each
// pixel [u, u+1) x [v, v+1) (CONVENTIONS.md). Two channels are accumulated at once: plain coverage and
// coverage weighted by a per-polygon brightness, so several non-overlapping polygons resolve in one pass.
#pragma once

#include <vector>

#include "visnav/core/types.hpp"

namespace visnav::synthetic {

class CoverageRaster {
 public:
  /// Allocates the accumulators (init time).
  void init(int width_px, int height_px);
  int width() const { return m_width; }
  int height() const { return m_height; }

  /// Adds the directed segment p0 -> p1 of a closed polygon outline. `sign` (+1/-1) fixes the orientation so
  /// that the enclosed area accumulates positively; `weight` is the polygon's brightness. Segments may leave
  /// the image: they are clipped exactly (the area left of x = 0 still counts for the pixels to its right).
  void addSegment(const Vec2& p0, const Vec2& p1, double sign, double weight);

  /// Writes per-pixel coverage (clamped to [0, 1]) and weighted coverage (row-major, width x height) and
  /// clears the accumulators for the next frame. Untouched rows are written as zeros.
  void resolve(double* coverage, double* weighted);

 private:
  void addClipped(double x0, double y0, double x1, double y1, double sign, double weight);
  void addRowPiece(int row, double xa, double xb, double dy, double weight);

  int m_width = 0;
  int m_height = 0;
  int m_stride = 0;  // width + 2: cells u and u + 1 receive a segment in column u = width (clipped right)
  int m_row_min = 0;
  int m_row_max = -1;
  std::vector<double> m_acc_cov;
  std::vector<double> m_acc_weighted;
};

}  // namespace visnav::synthetic
