// Which libcamera pixel formats the driver takes, how each becomes the mono view of a Frame, and in which
// order the driver tries them when the camera cannot deliver the requested one. Pure tables, testable without
// a camera.
//   - mono (R8 viewed in place, R10/R12 16-bit words in place): the sensor's own data, preferred;
//   - planar / semi-planar YUV (NV12, NV21, YUV420, YVU420, NV16): the first plane is the Y plane, viewed in
//     place (stride of the configuration);
//   - YUYV: Y every other byte, copied into a buffer sized at open();
//   - RGB (RGB888, BGR888, XRGB8888, XBGR8888): converted to BT.601 luma into a buffer sized at open(),
//     integer weights (77 R + 150 G + 29 B + 128) >> 8. Real pipelines (vimc) may offer nothing else.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "visnav/camera/camera_params.hpp"
#include "visnav/core/frame.hpp"

namespace visnav::camera {

enum class LibcameraFormat : std::uint8_t {
  kR8,
  kR10,
  kR12,
  kNv12,
  kNv21,
  kYuv420,
  kYvu420,
  kNv16,
  kYuyv,
  kXrgb8888,
  kXbgr8888,
  kRgb888,
  kBgr888,
};
constexpr int kLibcameraFormatCount = 13;

/// How the driver turns a buffer of the format into a mono view.
enum class LumaSource : std::uint8_t { kInPlace8, kInPlace16, kYuyv, kPackedRgb };

struct LibcameraFormatInfo {
  const char* name;       ///< libcamera 0.0.3 name ("R8", "NV12", "RGB888", ...)
  PixelFormat delivered;  ///< Frame::source_format (8-bit luma of YUV/RGB: kGrey8)
  LumaSource source;      ///< in place, YUYV copy, or RGB conversion
  int bytes_per_pixel;    ///< of the first plane
  int red, green, blue;   ///< byte offsets inside a pixel (kPackedRgb only)
};
const LibcameraFormatInfo& formatInfo(LibcameraFormat format);

/// libcamera name of a visnav format ("R8", "R10", "R12", "YUYV"), or nullptr when it has none (Y16).
const char* libcameraFormatName(PixelFormat format);
/// The libcamera format with that name; false for a name the driver cannot use.
bool libcameraFormatFromName(const char* name, LibcameraFormat& format);
/// Inverse of libcameraFormatName for the four visnav formats; false for any other name.
bool pixelFormatFromLibcameraName(const char* name, PixelFormat& format);

/// The requested format first, then mono (R8, R10, R12), the Y plane of YUV (NV12, NV21, YUV420, YVU420,
/// NV16), YUYV, then RGB converted to luma. Y16 requested: none (libcamera 0.0.3 has no 16-bit mono).
struct FormatCandidates {
  std::array<LibcameraFormat, kLibcameraFormatCount> formats{};
  int count = 0;
};
FormatCandidates formatCandidates(RequestedFormat requested);

/// Bytes the first plane needs for `height` rows of `stride_bytes`, the last `width` pixels wide.
std::size_t firstPlaneBytes(LibcameraFormat format, int width, int height, std::size_t stride_bytes);

const char* toString(LibcameraRole role);

}  // namespace visnav::camera
