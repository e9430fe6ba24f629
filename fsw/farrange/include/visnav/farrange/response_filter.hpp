// The far-range filter stage (paper sec. III-B): each low-level filter maps the image (or a region of it) to
// a response in [0, 1]; eq. 13 sums them with weights that add up to 1 (eq. 14). Responses are 8-bit fixed
// point (255 = 1.0): thresholds of 0.9 / 0.5 need no finer steps, and 16 pixels fit one SIMD register.
// A filter is a small interface, so more can be added next to the edge and histogram filters.
#pragma once

#include <cstddef>
#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/image_view.hpp"

namespace visnav::far {

/// Pixel rectangle [x0, x0 + width) x [y0, y0 + height) of the image.
struct Roi {
  int x0 = 0;
  int y0 = 0;
  int width = 0;
  int height = 0;

  static Roi full(int w, int h) { return {0, 0, w, h}; }
  bool empty() const { return width <= 0 || height <= 0; }
  long long area() const { return static_cast<long long>(width) * height; }
  /// The part of this rectangle inside a w x h image.
  Roi clipped(int w, int h) const;
};

constexpr std::uint8_t kResponseOne = 255;  ///< fixed-point 1.0

/// A response map over one ROI, 8-bit fixed point, rows of the ROI width packed at a fixed stride
/// (capacity set at init, never reallocated).
class ResponseImage {
 public:
  /// Init-time: capacity for the largest ROI (the whole image).
  void init(int max_width, int max_height);
  /// Per frame: select the ROI this map covers (must fit the capacity). No allocation.
  bool setRoi(const Roi& roi);
  const Roi& roi() const { return m_roi; }
  std::uint8_t* row(int y_in_roi) { return m_data.data() + static_cast<std::ptrdiff_t>(y_in_roi) * m_stride; }
  const std::uint8_t* row(int y_in_roi) const {
    return m_data.data() + static_cast<std::ptrdiff_t>(y_in_roi) * m_stride;
  }
  /// Response at image pixel (x, y), which must lie in the ROI.
  std::uint8_t atImage(int x, int y) const { return row(y - m_roi.y0)[x - m_roi.x0]; }
  int stride() const { return m_stride; }

 private:
  BoundedBuffer<std::uint8_t> m_data;
  int m_stride = 0;
  int m_max_height = 0;
  Roi m_roi;
};

class ResponseFilter {
 public:
  virtual ~ResponseFilter() = default;
  virtual const char* name() const = 0;
  /// Writes the response of every ROI pixel into `out` (whose ROI the caller has set to `roi`).
  /// Allocation-free; `roi` lies inside the image.
  virtual void apply(const MonoImage& image, const Roi& roi, ResponseImage& out) = 0;
};

}  // namespace visnav::far
