// A small RGB raster for the evaluation plots: pixels, clipped lines, dots, rectangles and 5x7 bitmap text.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"

namespace visnav::eval {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// The 7 row masks of a glyph (bit 4 = leftmost column); '?' for characters the font lacks.
const std::uint8_t* glyph5x7(char c);

class Canvas {
 public:
  Canvas(int width, int height, Rgb background);

  int width() const { return m_width; }
  int height() const { return m_height; }
  const std::vector<std::uint8_t>& rgb() const { return m_rgb; }
  Rgb pixel(int x, int y) const;

  /// Drawing is limited to [x0, x1) x [y0, y1) until resetClip().
  void setClip(int x0, int y0, int x1, int y1);
  void resetClip() { setClip(0, 0, m_width, m_height); }

  void setPixel(int x, int y, Rgb c);
  void fillRect(int x0, int y0, int x1, int y1, Rgb c);  ///< [x0, x1) x [y0, y1)
  void rect(int x0, int y0, int x1, int y1, Rgb c);      ///< outline
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void dot(double x, double y, int radius, Rgb c);  ///< filled square of side 2 * radius + 1

  /// Text with its top-left corner at (x, y); each font pixel becomes scale x scale pixels.
  void text(int x, int y, const std::string& s, Rgb c, int scale = 1);
  static int textWidth(const std::string& s, int scale = 1) { return static_cast<int>(s.size()) * 6 * scale; }
  static int textHeight(int scale = 1) { return 7 * scale; }

  /// The canvas as a PNG file (tools/png: zlib-compressed).
  LoadError writePng(const std::string& path) const;

 private:
  int m_width;
  int m_height;
  int m_clip_x0 = 0, m_clip_y0 = 0, m_clip_x1 = 0, m_clip_y1 = 0;
  std::vector<std::uint8_t> m_rgb;
};

}  // namespace visnav::eval
