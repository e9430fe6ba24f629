#include "visnav/eval/canvas.hpp"

#include <algorithm>
#include <cmath>

#include "visnav/png/png_writer.hpp"

namespace visnav::eval {

Canvas::Canvas(int width, int height, Rgb background)
    : m_width(std::max(width, 1)), m_height(std::max(height, 1)) {
  m_rgb.resize(static_cast<std::size_t>(m_width) * m_height * 3U);
  for (std::size_t i = 0; i < m_rgb.size(); i += 3) {
    m_rgb[i] = background.r;
    m_rgb[i + 1] = background.g;
    m_rgb[i + 2] = background.b;
  }
  resetClip();
}

Rgb Canvas::pixel(int x, int y) const {
  if (x < 0 || y < 0 || x >= m_width || y >= m_height) return {};
  const std::size_t i = (static_cast<std::size_t>(y) * m_width + x) * 3U;
  return {m_rgb[i], m_rgb[i + 1], m_rgb[i + 2]};
}

void Canvas::setClip(int x0, int y0, int x1, int y1) {
  m_clip_x0 = std::clamp(x0, 0, m_width);
  m_clip_y0 = std::clamp(y0, 0, m_height);
  m_clip_x1 = std::clamp(x1, 0, m_width);
  m_clip_y1 = std::clamp(y1, 0, m_height);
}

void Canvas::setPixel(int x, int y, Rgb c) {
  if (x < m_clip_x0 || y < m_clip_y0 || x >= m_clip_x1 || y >= m_clip_y1) return;
  const std::size_t i = (static_cast<std::size_t>(y) * m_width + x) * 3U;
  m_rgb[i] = c.r;
  m_rgb[i + 1] = c.g;
  m_rgb[i + 2] = c.b;
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::max(y0, m_clip_y0); y < std::min(y1, m_clip_y1); ++y)
    for (int x = std::max(x0, m_clip_x0); x < std::min(x1, m_clip_x1); ++x) setPixel(x, y, c);
}

void Canvas::rect(int x0, int y0, int x1, int y1, Rgb c) {
  fillRect(x0, y0, x1, y0 + 1, c);
  fillRect(x0, y1 - 1, x1, y1, c);
  fillRect(x0, y0, x0 + 1, y1, c);
  fillRect(x1 - 1, y0, x1, y1, c);
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
  // Sample along the longer extent; lines far outside the canvas are clamped so the loop stays bounded.
  const double limit = 4.0 * (m_width + m_height);
  x0 = std::clamp(x0, -limit, limit);
  x1 = std::clamp(x1, -limit, limit);
  y0 = std::clamp(y0, -limit, limit);
  y1 = std::clamp(y1, -limit, limit);
  const int steps = static_cast<int>(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
  const int lo = -(thickness - 1) / 2;
  const int hi = lo + thickness;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    for (int dy = lo; dy < hi; ++dy)
      for (int dx = lo; dx < hi; ++dx) setPixel(x + dx, y + dy, c);
  }
}

void Canvas::dot(double x, double y, int radius, Rgb c) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  const int cx = static_cast<int>(std::lround(std::clamp(x, -1e6, 1e6)));
  const int cy = static_cast<int>(std::lround(std::clamp(y, -1e6, 1e6)));
  fillRect(cx - radius, cy - radius, cx + radius + 1, cy + radius + 1, c);
}

void Canvas::text(int x, int y, const std::string& s, Rgb c, int scale) {
  for (std::size_t k = 0; k < s.size(); ++k) {
    const std::uint8_t* rows = glyph5x7(s[k]);
    const int gx = x + static_cast<int>(k) * 6 * scale;
    for (int r = 0; r < 7; ++r)
      for (int col = 0; col < 5; ++col)
        if (((rows[r] >> (4 - col)) & 1U) != 0U)
          fillRect(gx + col * scale, y + r * scale, gx + (col + 1) * scale, y + (r + 1) * scale, c);
  }
}

LoadError Canvas::writePng(const std::string& path) const {
  return png::writeRgb(path, m_width, m_height, m_rgb);
}

}  // namespace visnav::eval
