// Non-owning views of 8- and 16-bit monochrome images with a row stride in bytes, so a view can point
// straight into a driver's buffer (padding rows included). The view never frees anything.
#pragma once

#include <cstddef>
#include <cstdint>

namespace visnav {

template <typename PixelT>
class ImageView {
 public:
  ImageView() = default;
  ImageView(const PixelT* data, int width, int height, std::ptrdiff_t stride_bytes)
      : m_data(data), m_width(width), m_height(height), m_stride_bytes(stride_bytes) {}
  /// Tightly packed rows.
  ImageView(const PixelT* data, int width, int height)
      : ImageView(data, width, height, static_cast<std::ptrdiff_t>(width) * sizeof(PixelT)) {}

  const PixelT* row(int y) const {
    return reinterpret_cast<const PixelT*>(reinterpret_cast<const std::uint8_t*>(m_data) +
                                           m_stride_bytes * y);
  }
  PixelT at(int x, int y) const { return row(y)[x]; }

  int width() const { return m_width; }
  int height() const { return m_height; }
  std::ptrdiff_t strideBytes() const { return m_stride_bytes; }
  const PixelT* data() const { return m_data; }
  bool empty() const { return m_data == nullptr || m_width <= 0 || m_height <= 0; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }

 private:
  const PixelT* m_data = nullptr;
  int m_width = 0;
  int m_height = 0;
  std::ptrdiff_t m_stride_bytes = 0;
};

using ImageView8 = ImageView<std::uint8_t>;
using ImageView16 = ImageView<std::uint16_t>;

/// A mono frame of either depth; the estimators read brightness normalised to [0, 1] (paper sec. I-C).
struct MonoImage {
  enum class Depth : std::uint8_t { kU8, kU16 };
  Depth depth = Depth::kU8;
  ImageView8 u8;
  ImageView16 u16;
  /// Largest code of the sensor (255, 1023 for Y10, 4095 for Y12, 65535 for Y16).
  std::uint16_t max_code = 255;

  static MonoImage from8(const ImageView8& view) {
    MonoImage image;
    image.depth = Depth::kU8;
    image.u8 = view;
    image.max_code = 255;
    return image;
  }
  static MonoImage from16(const ImageView16& view, std::uint16_t max_code) {
    MonoImage image;
    image.depth = Depth::kU16;
    image.u16 = view;
    image.max_code = max_code;
    return image;
  }
  int width() const { return depth == Depth::kU8 ? u8.width() : u16.width(); }
  int height() const { return depth == Depth::kU8 ? u8.height() : u16.height(); }
  bool empty() const { return depth == Depth::kU8 ? u8.empty() : u16.empty(); }
};

}  // namespace visnav
