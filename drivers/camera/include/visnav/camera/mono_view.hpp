// Turning a driver's frame buffer into the mono view a Frame carries (shared by the v4l2 and libcamera
// drivers). GREY/R8 and the 16-bit little-endian formats (Y10/R10, Y12/R12, Y16) are viewed in place with
// the driver's row stride: no copy. YUYV interleaves Y with chroma (Y every other byte), which no strided
// view can express, so its Y plane is copied into a buffer the driver allocated at open().
#pragma once

#include <cstddef>
#include <cstdint>

#include "visnav/core/frame.hpp"

namespace visnav::camera {

/// Bytes per pixel of the packed source format (YUYV: 2 per pixel, Y in the even bytes).
int bytesPerPixel(PixelFormat format);
/// Largest code of the sensor in the delivered view (255, 1023, 4095, 65535).
std::uint16_t maxCode(PixelFormat format);
/// True when the format is delivered as a view into the driver's buffer (no conversion).
bool isZeroCopy(PixelFormat format);
/// Smallest buffer length in bytes holding `height` rows of `stride_bytes` with the last one `width` wide.
std::size_t minimumBufferBytes(PixelFormat format, int width, int height, std::size_t stride_bytes);

/// A view into `data` for a zero-copy format; empty for YUYV. `data` must be 2-byte aligned for 16-bit
/// formats (mmap'd buffers are page aligned; `stride_bytes` must be even).
MonoImage viewInPlace(PixelFormat format, const void* data, int width, int height, std::size_t stride_bytes);

/// Copies the Y samples of a YUYV image into `luma` (width * height bytes, tightly packed) and returns the
/// 8-bit view of it. Bounded: width * height byte copies, no allocation.
MonoImage extractLumaYuyv(const std::uint8_t* yuyv, int width, int height, std::size_t stride_bytes,
                          std::uint8_t* luma);

/// Where R, G and B sit inside one pixel of a packed RGB format (bytes_per_pixel 3 or 4).
struct PackedRgbLayout {
  int bytes_per_pixel = 3;
  int red = 0;
  int green = 1;
  int blue = 2;
};
/// BT.601 luma of a packed RGB image into `luma` (width * height bytes, tightly packed), integer weights
/// Y = (77 R + 150 G + 29 B + 128) >> 8 (full range; the weights sum to 256, so white stays 255). Bounded,
/// no allocation.
MonoImage extractLumaRgb(const std::uint8_t* rgb, int width, int height, std::size_t stride_bytes,
                         const PackedRgbLayout& layout, std::uint8_t* luma);

}  // namespace visnav::camera
