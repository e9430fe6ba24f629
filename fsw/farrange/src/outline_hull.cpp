// The convex hull of one or two clusters of an outline search, how much of the hull's boundary the clusters
// cover, and how much of the clusters lies along it: an outline with gaps (a contrast that passes near zero
// against a gradient, noise) fills nothing, but its hull is the silhouette of a convex target when the
// outline runs along most of it. Design notes: fsw/farrange/README.md, robust method item 9.
#include <algorithm>
#include <cmath>

#include "visnav/farrange/cluster_finder.hpp"

namespace visnav::far {
namespace {

// Points packed as (x << 16) | y sort by x, then y (monotone chain order).
constexpr std::uint32_t packXy(int x, int y) {
  return (static_cast<std::uint32_t>(x) << 16U) | static_cast<std::uint32_t>(y);
}
constexpr int packedX(std::uint32_t p) { return static_cast<int>(p >> 16U); }
constexpr int packedY(std::uint32_t p) { return static_cast<int>(p & 0xffffU); }
// Image pixels as ClusterFinder stores them: (y << 16) | x.
constexpr int storedX(std::uint32_t p) { return static_cast<int>(p & 0xffffU); }
constexpr int storedY(std::uint32_t p) { return static_cast<int>(p >> 16U); }

std::int64_t cross(std::uint32_t o, std::uint32_t a, std::uint32_t b) {
  return static_cast<std::int64_t>(packedX(a) - packedX(o)) * (packedY(b) - packedY(o)) -
         static_cast<std::int64_t>(packedY(a) - packedY(o)) * (packedX(b) - packedX(o));
}

}  // namespace

bool ClusterFinder::outlineHull(const int* members, int count, int reach_px, double min_coverage,
                                OutlineHull& out) {
  out = OutlineHull{};
  if (count <= 0 || count > 2) return false;
  const Cluster& first = m_clusters[static_cast<std::size_t>(members[0])];
  out.x_min = first.x_min;
  out.y_min = first.y_min;
  out.x_max = first.x_max;
  out.y_max = first.y_max;
  for (int m = 1; m < count; ++m) {
    const Cluster& c = m_clusters[static_cast<std::size_t>(members[m])];
    out.x_min = std::min(out.x_min, c.x_min);
    out.y_min = std::min(out.y_min, c.y_min);
    out.x_max = std::max(out.x_max, c.x_max);
    out.y_max = std::max(out.y_max, c.y_max);
  }
  // Each row's leftmost and rightmost member pixel: the hull of those is the hull of all members.
  const int rows = out.y_max - out.y_min + 1;
  int* lo = m_row_lo.data();
  int* hi = m_row_hi.data();
  std::fill(lo, lo + rows, m_width);
  std::fill(hi, hi + rows, -1);
  // The members' pixels are also rasterised into a padded box for the coverage test below.
  const int pad = std::clamp(reach_px, 0, kMaxReachPx) + 1;
  const int bw = out.x_max - out.x_min + 1 + 2 * pad;
  const int bh = rows + 2 * pad;
  std::uint8_t* box = m_fill.data();
  std::fill(box, box + static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh), std::uint8_t{0});
  for (int m = 0; m < count; ++m) {
    const Cluster& c = m_clusters[static_cast<std::size_t>(members[m])];
    out.pixel_count += c.pixel_count;
    for (int i = 0; i < c.pixel_count; ++i) {
      const std::uint32_t p = m_pixels[static_cast<std::size_t>(c.first_pixel) + static_cast<std::size_t>(i)];
      const int x = storedX(p);
      const int r = storedY(p) - out.y_min;
      lo[r] = std::min(lo[r], x);
      hi[r] = std::max(hi[r], x);
      box[static_cast<std::size_t>(r + pad) * bw + static_cast<std::size_t>(x - out.x_min + pad)] = 1;
    }
  }
  m_fill_stack.clear();
  for (int r = 0; r < rows; ++r) {
    if (hi[r] < 0) continue;
    m_fill_stack.push(packXy(lo[r], out.y_min + r));
    if (hi[r] != lo[r]) m_fill_stack.push(packXy(hi[r], out.y_min + r));
  }
  std::uint32_t* pts = m_fill_stack.data();
  const int n = static_cast<int>(m_fill_stack.size());
  if (n < 3) return false;
  std::sort(pts, pts + n);
  // Andrew's monotone chain: lower hull left to right, then upper hull back (counter-clockwise, y down).
  std::uint32_t* hull = m_hull.data();
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  const int vertices = k - 1;  // the last point repeats the first
  if (vertices < 3) return false;
  double area2 = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  for (int i = 0; i < vertices; ++i) {
    const double x0 = packedX(hull[i]);
    const double y0 = packedY(hull[i]);
    const double x1 = packedX(hull[i + 1]);
    const double y1 = packedY(hull[i + 1]);
    const double a = x0 * y1 - x1 * y0;
    area2 += a;
    cx += (x0 + x1) * a;
    cy += (y0 + y1) * a;
    out.perimeter_px += std::hypot(x1 - x0, y1 - y0);
  }
  if (!(std::abs(area2) > 2.0)) return false;
  cx /= 3.0 * area2;
  cy /= 3.0 * area2;
  // Pixel centres span the polygon; the pixels themselves reach half a pixel beyond it.
  out.area_px = 0.5 * std::abs(area2) + 0.5 * out.perimeter_px + 1.0;
  out.centre_px = Vec2(cx + 0.5, cy + 0.5);
  // Coverage: 1-px steps along the hull with a member pixel within reach (a square window of the box).
  const int reach = pad - 1;
  int steps_total = 0;
  int covered = 0;
  for (int i = 0; i < vertices; ++i) {
    const double x0 = packedX(hull[i]);
    const double y0 = packedY(hull[i]);
    const double dx = packedX(hull[i + 1]) - x0;
    const double dy = packedY(hull[i + 1]) - y0;
    const double r2 = (x0 - cx) * (x0 - cx) + (y0 - cy) * (y0 - cy);
    out.max_radius_px = std::max(out.max_radius_px, std::sqrt(r2));
    const int steps = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy))));
    for (int s = 0; s < steps; ++s) {
      const int bx = static_cast<int>(std::lround(x0 + dx * s / steps)) - out.x_min + pad;
      const int by = static_cast<int>(std::lround(y0 + dy * s / steps)) - out.y_min + pad;
      bool hit = false;
      for (int wy = by - reach; wy <= by + reach && !hit; ++wy) {
        const std::uint8_t* row = box + static_cast<std::size_t>(wy) * bw;
        for (int wx = bx - reach; wx <= bx + reach && !hit; ++wx) hit = row[wx] != 0;
      }
      covered += hit ? 1 : 0;
      ++steps_total;
    }
  }
  out.coverage = steps_total > 0 ? static_cast<double>(covered) / steps_total : 0.0;
  // Concentration: the members' pixels within reach of the hull's boundary (an outline lies along its hull;
  // a line with noise attached spreads over it). Only when the coverage leaves it worth knowing.
  if (out.coverage < min_coverage) return true;
  int near = 0;
  const double limit2 = static_cast<double>(reach + 1) * (reach + 1);
  for (int m = 0; m < count; ++m) {
    const Cluster& c = m_clusters[static_cast<std::size_t>(members[m])];
    for (int i = 0; i < c.pixel_count; ++i) {
      const std::uint32_t p = m_pixels[static_cast<std::size_t>(c.first_pixel) + static_cast<std::size_t>(i)];
      const double px = storedX(p);
      const double py = storedY(p);
      bool close = false;
      for (int v = 0; v < vertices && !close; ++v) {
        const double ax = packedX(hull[v]);
        const double ay = packedY(hull[v]);
        const double ex = packedX(hull[v + 1]) - ax;
        const double ey = packedY(hull[v + 1]) - ay;
        const double len2 = ex * ex + ey * ey;
        const double t = len2 > 0.0 ? std::clamp(((px - ax) * ex + (py - ay) * ey) / len2, 0.0, 1.0) : 0.0;
        const double dx = px - (ax + t * ex);
        const double dy = py - (ay + t * ey);
        close = dx * dx + dy * dy <= limit2;
      }
      near += close ? 1 : 0;
    }
  }
  out.concentration = static_cast<double>(near) / out.pixel_count;
  return true;
}

}  // namespace visnav::far
