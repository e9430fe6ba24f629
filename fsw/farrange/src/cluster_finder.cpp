#include "visnav/farrange/cluster_finder.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::far {
namespace {

constexpr std::uint32_t packPixel(int x, int y) {
  return (static_cast<std::uint32_t>(y) << 16U) | static_cast<std::uint32_t>(x);
}
constexpr int pixelX(std::uint32_t p) { return static_cast<int>(p & 0xffffU); }
constexpr int pixelY(std::uint32_t p) { return static_cast<int>(p >> 16U); }

constexpr int kNeighbourDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
constexpr int kNeighbourDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

// sqrt of the eigenvalue ratio of the second moments of n unit pixel squares, from sums of their
// (relative) integer coordinates; each square adds 1/12 of variance per axis.
double axisRatio(double n, double sx, double sy, double sxx, double syy, double sxy) {
  const double mx = sx / n;
  const double my = sy / n;
  const double a = sxx / n - mx * mx + 1.0 / 12.0;
  const double b = sxy / n - mx * my;
  const double d = syy / n - my * my + 1.0 / 12.0;
  const double half_diff = 0.5 * (a - d);
  const double root = std::sqrt(half_diff * half_diff + b * b);
  const double l_max = 0.5 * (a + d) + root;
  const double l_min = std::max(0.5 * (a + d) - root, 1e-12);
  return std::sqrt(l_max / l_min);
}

}  // namespace

void ClusterFinder::init(int width, int height, int max_clusters, int max_pixels) {
  m_width = width;
  m_height = height;
  const auto n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  m_label.reserve(n);
  std::fill(m_label.data(), m_label.data() + n, static_cast<std::uint16_t>(0));
  m_clusters.reserve(static_cast<std::size_t>(max_clusters));
  m_pixels.reserve(static_cast<std::size_t>(max_pixels));
  // The padded box of fillHoles (one free ring) or of outlineHull (kMaxReachPx + 1).
  const auto padded = static_cast<std::size_t>(width + 2 + 2 * kMaxReachPx) *
                      static_cast<std::size_t>(height + 2 + 2 * kMaxReachPx);
  m_fill.reserve(padded);
  m_fill_stack.reserve(padded);
  // A hull's input: at most two points per image row; the monotone chain holds at most twice that.
  m_hull.reserve(4 * static_cast<std::size_t>(height) + 2);
  m_row_lo.reserve(static_cast<std::size_t>(height));
  m_row_hi.reserve(static_cast<std::size_t>(height));
}

void ClusterFinder::find(const ResponseImage& response, const std::uint8_t* row_max, std::uint8_t t_in_q,
                         std::uint8_t t_out_q, int min_keep_px) {
  // Forget the last frame's labels: only its cluster pixels were labelled.
  for (const std::uint32_t p : m_pixels) {
    m_label[static_cast<std::size_t>(pixelY(p)) * m_width + static_cast<std::size_t>(pixelX(p))] = 0;
  }
  m_pixels.clear();
  m_clusters.clear();
  m_seeds_skipped = 0;
  m_pixel_capacity_hit = false;
  const Roi& roi = response.roi();
  for (int ry = 0; ry < roi.height; ++ry) {
    if (row_max[ry] <= t_in_q) continue;  // no spawn pixel in this row
    const std::uint8_t* s = response.row(ry);
    const int y = roi.y0 + ry;
    const std::uint16_t* labels = m_label.data() + static_cast<std::size_t>(y) * m_width;
    for (int rx = 0; rx < roi.width; ++rx) {
      if (s[rx] <= t_in_q || labels[roi.x0 + rx] != 0) continue;
      if (m_clusters.full()) {
        ++m_seeds_skipped;
        continue;
      }
      grow(response, roi.x0 + rx, y, t_out_q, min_keep_px);
    }
  }
}

void ClusterFinder::grow(const ResponseImage& response, int seed_x, int seed_y, std::uint8_t t_out_q,
                         int min_keep_px) {
  const Roi& roi = response.roi();
  const auto id = static_cast<std::uint16_t>(m_clusters.size() + 1);
  Cluster c;
  c.first_pixel = static_cast<int>(m_pixels.size());
  c.x_min = c.x_max = seed_x;
  c.y_min = c.y_max = seed_y;
  if (!m_pixels.push(packPixel(seed_x, seed_y))) {
    m_pixel_capacity_hit = true;
    return;
  }
  m_label[static_cast<std::size_t>(seed_y) * m_width + static_cast<std::size_t>(seed_x)] = id;
  // Breadth-first: the pixel list is the queue. Each pixel enters once (labelled when pushed), so the loop
  // is bounded by the pixel capacity.
  for (std::size_t head = m_pixels.size() - 1; head < m_pixels.size(); ++head) {
    const int x = pixelX(m_pixels[head]);
    const int y = pixelY(m_pixels[head]);
    for (int k = 0; k < 8; ++k) {
      const int nx = x + kNeighbourDx[k];
      const int ny = y + kNeighbourDy[k];
      if (nx < roi.x0 || ny < roi.y0 || nx >= roi.x0 + roi.width || ny >= roi.y0 + roi.height) continue;
      std::uint16_t& label = m_label[static_cast<std::size_t>(ny) * m_width + static_cast<std::size_t>(nx)];
      if (label != 0 || response.atImage(nx, ny) <= t_out_q) continue;
      if (!m_pixels.push(packPixel(nx, ny))) {
        c.truncated = true;
        m_pixel_capacity_hit = true;
        continue;
      }
      label = id;
    }
  }
  c.pixel_count = static_cast<int>(m_pixels.size()) - c.first_pixel;
  // A dropped cluster's pixels stay in m_pixels (the next find() clears their labels) and its id is reused:
  // labels are only tested for zero.
  if (c.pixel_count < min_keep_px) return;
  measure(c, roi);
  for (int i = 0; i < c.pixel_count; ++i) {
    const std::uint32_t p = m_pixels[static_cast<std::size_t>(c.first_pixel) + static_cast<std::size_t>(i)];
    c.peak_response = std::max(c.peak_response, static_cast<int>(response.atImage(pixelX(p), pixelY(p))));
  }
  m_clusters.push(c);
}

void ClusterFinder::measure(Cluster& c, const Roi& roi) const {
  // Moments relative to the seed keep the sums small and exact in 64-bit integers.
  const std::uint32_t* px = m_pixels.data() + c.first_pixel;
  const int ox = pixelX(px[0]);
  const int oy = pixelY(px[0]);
  std::int64_t sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int i = 0; i < c.pixel_count; ++i) {
    const int x = pixelX(px[i]);
    const int y = pixelY(px[i]);
    c.x_min = std::min(c.x_min, x);
    c.x_max = std::max(c.x_max, x);
    c.y_min = std::min(c.y_min, y);
    c.y_max = std::max(c.y_max, y);
    const std::int64_t dx = x - ox;
    const std::int64_t dy = y - oy;
    sx += dx;
    sy += dy;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  const double n = c.pixel_count;
  const double mx = static_cast<double>(sx) / n;
  const double my = static_cast<double>(sy) / n;
  c.com_px = Vec2(ox + mx + 0.5, oy + my + 0.5);
  c.axis_ratio = axisRatio(n, static_cast<double>(sx), static_cast<double>(sy), static_cast<double>(sxx),
                           static_cast<double>(syy), static_cast<double>(sxy));
  double r2_max = 0.0;
  for (int i = 0; i < c.pixel_count; ++i) {
    const double ex = pixelX(px[i]) + 0.5 - c.com_px.x();
    const double ey = pixelY(px[i]) + 0.5 - c.com_px.y();
    r2_max = std::max(r2_max, ex * ex + ey * ey);
  }
  c.max_radius_px = std::sqrt(r2_max);
  c.circularity = std::exp(-std::abs(std::sqrt(n / kPi) - c.max_radius_px));  // eq. 15
  c.at_roi_border = c.x_min == roi.x0 || c.y_min == roi.y0 || c.x_max == roi.x0 + roi.width - 1 ||
                    c.y_max == roi.y0 + roi.height - 1;
}

void ClusterFinder::fillHoles(Cluster& c) {
  c.sharpness_known = false;  // the filled centre is the one measured from
  // Padded box: one free ring around the bounding box, so the exterior is connected and seeded at (0, 0).
  const int bw = c.x_max - c.x_min + 3;
  const int bh = c.y_max - c.y_min + 3;
  const auto area = static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh);
  std::uint8_t* box = m_fill.data();
  std::fill(box, box + area, static_cast<std::uint8_t>(0));
  for (int i = 0; i < c.pixel_count; ++i) {
    const std::uint32_t p = m_pixels[static_cast<std::size_t>(c.first_pixel) + static_cast<std::size_t>(i)];
    box[static_cast<std::size_t>(pixelY(p) - c.y_min + 1) * bw +
        static_cast<std::size_t>(pixelX(p) - c.x_min + 1)] = 1;
  }
  // Exterior: 4-connected, the dual of the cluster's 8-connectivity (a diagonal step cannot leak through).
  constexpr std::uint8_t kExterior = 2;
  m_fill_stack.clear();
  box[0] = kExterior;
  m_fill_stack.push(packPixel(0, 0));
  std::size_t exterior = 0;
  while (!m_fill_stack.empty()) {
    const std::uint32_t at = m_fill_stack[m_fill_stack.size() - 1];
    m_fill_stack.truncate(m_fill_stack.size() - 1);
    ++exterior;
    const int x = pixelX(at);
    const int y = pixelY(at);
    const int nx[4] = {x - 1, x + 1, x, x};
    const int ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= bw || ny[k] >= bh) continue;
      std::uint8_t& cell = box[static_cast<std::size_t>(ny[k]) * bw + static_cast<std::size_t>(nx[k])];
      if (cell != 0) continue;
      cell = kExterior;  // marked when pushed: each cell enters the stack once (bounded by the box area)
      m_fill_stack.push(packPixel(nx[k], ny[k]));
    }
  }
  c.filled_count = static_cast<int>(area - exterior);
  double sx = 0.0;
  double sy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  double sxy = 0.0;
  int boundary = 0;
  for (int y = 1; y + 1 < bh; ++y) {
    const std::uint8_t* up = box + static_cast<std::size_t>(y - 1) * bw;
    const std::uint8_t* row = box + static_cast<std::size_t>(y) * bw;
    const std::uint8_t* down = box + static_cast<std::size_t>(y + 1) * bw;
    for (int x = 1; x + 1 < bw; ++x) {
      const int inside = row[x] != kExterior ? 1 : 0;
      sx += inside * x;
      sy += inside * y;
      sxx += inside * x * x;
      syy += inside * y * y;
      sxy += inside * x * y;
      const int touches = (up[x] == kExterior) | (down[x] == kExterior) | (row[x - 1] == kExterior) |
                          (row[x + 1] == kExterior);
      boundary += inside & touches;
    }
  }
  c.boundary_count = boundary;
  c.axis_ratio = axisRatio(c.filled_count, sx, sy, sxx, syy, sxy);  // the shape, not its outline
  c.filled_com_px = Vec2(c.x_min - 1 + sx / c.filled_count + 0.5, c.y_min - 1 + sy / c.filled_count + 0.5);
}

}  // namespace visnav::far
