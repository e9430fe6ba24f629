#include "visnav/synthetic/coverage_raster.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::synthetic {

void CoverageRaster::init(int width_px, int height_px) {
  m_width = width_px;
  m_height = height_px;
  m_stride = width_px + 2;
  const auto n = static_cast<std::size_t>(m_stride) * static_cast<std::size_t>(height_px);
  m_acc_cov.assign(n, 0.0);
  m_acc_weighted.assign(n, 0.0);
  m_row_min = 0;
  m_row_max = -1;
}

void CoverageRaster::addSegment(const Vec2& p0, const Vec2& p1, double sign, double weight) {
  if (!(p0.allFinite() && p1.allFinite())) return;
  if (p0.y() == p1.y()) return;  // horizontal segments enclose no area along a row
  // Split at x = 0 and x = W. Pieces left of the image collapse onto x = 0, where they still open/close the
  // winding of the pixels to their right; pieces right of it collapse onto x = W and touch nothing visible.
  const double w = m_width;
  const Vec2 d = p1 - p0;
  double ts[4] = {0.0, 0.0, 0.0, 1.0};
  int n = 1;
  for (const double xc : {0.0, w}) {
    if ((p0.x() < xc && p1.x() > xc) || (p0.x() > xc && p1.x() < xc)) ts[n++] = (xc - p0.x()) / d.x();
  }
  if (n == 3 && ts[1] > ts[2]) std::swap(ts[1], ts[2]);
  ts[n] = 1.0;
  for (int i = 0; i < n; ++i) {
    const Vec2 a = i == 0 ? p0 : Vec2(p0 + ts[i] * d);
    const Vec2 b = i == n - 1 ? p1 : Vec2(p0 + ts[i + 1] * d);
    const double xm = std::clamp(0.5 * (a.x() + b.x()), 0.0, w);
    const bool outside = xm == 0.0 || xm == w;
    const double xa = outside ? xm : std::clamp(a.x(), 0.0, w);
    const double xb = outside ? xm : std::clamp(b.x(), 0.0, w);
    addClipped(xa, a.y(), xb, b.y(), sign, weight);
  }
}

void CoverageRaster::addClipped(double x0, double y0, double x1, double y1, double sign, double weight) {
  // Rows outside [0, H) are independent of the visible ones: clip the y range and walk the rows.
  const double y_lo = std::max(std::min(y0, y1), 0.0);
  const double y_hi = std::min(std::max(y0, y1), static_cast<double>(m_height));
  if (!(y_lo < y_hi)) return;
  const double dxdy = (x1 - x0) / (y1 - y0);
  const double dir = y1 > y0 ? sign : -sign;
  const int r0 = static_cast<int>(std::floor(y_lo));
  const int r1 = std::min(static_cast<int>(std::ceil(y_hi)), m_height) - 1;
  for (int r = r0; r <= r1; ++r) {
    const double ya = std::max(y_lo, static_cast<double>(r));
    const double yb = std::min(y_hi, static_cast<double>(r + 1));
    if (!(ya < yb)) continue;
    const double xa = x0 + (ya - y0) * dxdy;
    const double xb = x0 + (yb - y0) * dxdy;
    addRowPiece(r, xa, xb, dir * (yb - ya), weight);
  }
  m_row_min = m_row_max < m_row_min ? r0 : std::min(m_row_min, r0);
  m_row_max = std::max(m_row_max, r1);
}

void CoverageRaster::addRowPiece(int row, double xa, double xb, double dy, double weight) {
  // Within one pixel cell c a straight piece covers dy * (c + 1 - x_mid) of that cell and dy of every cell
  // to its right: deposit the first part at c and the remainder at c + 1 (difference form).
  double* cov = m_acc_cov.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(m_stride);
  double* wei = m_acc_weighted.data() + static_cast<std::size_t>(row) * static_cast<std::size_t>(m_stride);
  const double lo = std::min(xa, xb);
  const double hi = std::max(xa, xb);
  const int c_lo = std::min(static_cast<int>(std::floor(lo)), m_width);
  const int c_hi = std::max(c_lo, std::min(static_cast<int>(std::ceil(hi)) - 1, m_width));
  const double span = hi - lo;
  for (int c = c_lo; c <= c_hi; ++c) {
    const double a = std::max(lo, static_cast<double>(c));
    const double b = std::min(hi, static_cast<double>(c + 1));
    const double part = span > 0.0 ? dy * (b - a) / span : dy;
    const double frac = 0.5 * (a + b) - c;  // position of the piece's midpoint inside the cell
    cov[c] += part * (1.0 - frac);
    cov[c + 1] += part * frac;
    wei[c] += weight * part * (1.0 - frac);
    wei[c + 1] += weight * part * frac;
  }
}

void CoverageRaster::resolve(double* coverage, double* weighted) {
  const auto w = static_cast<std::size_t>(m_width);
  for (int r = 0; r < m_height; ++r) {
    double* out_c = coverage + static_cast<std::size_t>(r) * w;
    double* out_w = weighted + static_cast<std::size_t>(r) * w;
    if (r < m_row_min || r > m_row_max) {
      std::fill(out_c, out_c + w, 0.0);
      std::fill(out_w, out_w + w, 0.0);
      continue;
    }
    double* cov = m_acc_cov.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(m_stride);
    double* wei = m_acc_weighted.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(m_stride);
    double sum_c = 0.0;
    double sum_w = 0.0;
    for (std::size_t c = 0; c < w; ++c) {
      sum_c += cov[c];
      sum_w += wei[c];
      // Round-off can leave +-1e-16 outside [0, 1]; the weighted channel follows the same clamp.
      const double cc = std::clamp(sum_c, 0.0, 1.0);
      out_c[c] = cc;
      out_w[c] = sum_c > 0.0 ? sum_w * (cc / sum_c) : 0.0;
    }
    std::fill(cov, cov + m_stride, 0.0);
    std::fill(wei, wei + m_stride, 0.0);
  }
  m_row_min = 0;
  m_row_max = -1;
}

}  // namespace visnav::synthetic
