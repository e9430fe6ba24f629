#include "visnav/libcamera/libcamera_formats.hpp"

#include <cstring>

namespace visnav::camera {
namespace {

// Indexed by LibcameraFormat. Byte order of the packed RGB formats follows DRM fourccs (libcamera's names):
// RGB888 is [23:0] R:G:B little-endian, so B, G, R in memory; BGR888 is R, G, B; XRGB8888 is B, G, R, X;
// XBGR8888 is R, G, B, X.
constexpr std::array<LibcameraFormatInfo, kLibcameraFormatCount> kFormats = {{
    {"R8", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"R10", PixelFormat::kY10, LumaSource::kInPlace16, 2, 0, 0, 0},
    {"R12", PixelFormat::kY12, LumaSource::kInPlace16, 2, 0, 0, 0},
    {"NV12", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"NV21", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"YUV420", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"YVU420", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"NV16", PixelFormat::kGrey8, LumaSource::kInPlace8, 1, 0, 0, 0},
    {"YUYV", PixelFormat::kYuyv, LumaSource::kYuyv, 2, 0, 0, 0},
    {"XRGB8888", PixelFormat::kGrey8, LumaSource::kPackedRgb, 4, 2, 1, 0},
    {"XBGR8888", PixelFormat::kGrey8, LumaSource::kPackedRgb, 4, 0, 1, 2},
    {"RGB888", PixelFormat::kGrey8, LumaSource::kPackedRgb, 3, 2, 1, 0},
    {"BGR888", PixelFormat::kGrey8, LumaSource::kPackedRgb, 3, 0, 1, 2},
}};

}  // namespace

const LibcameraFormatInfo& formatInfo(LibcameraFormat format) {
  return kFormats[static_cast<std::size_t>(format)];
}

const char* libcameraFormatName(PixelFormat format) {
  switch (format) {
    case PixelFormat::kGrey8: return "R8";
    case PixelFormat::kY10: return "R10";
    case PixelFormat::kY12: return "R12";
    case PixelFormat::kYuyv: return "YUYV";
    case PixelFormat::kY16: return nullptr;  // no 16-bit mono format in libcamera 0.0.3
  }
  return nullptr;
}

bool libcameraFormatFromName(const char* name, LibcameraFormat& format) {
  for (int i = 0; i < kLibcameraFormatCount; ++i) {
    if (std::strcmp(name, kFormats[static_cast<std::size_t>(i)].name) == 0) {
      format = static_cast<LibcameraFormat>(i);
      return true;
    }
  }
  return false;
}

bool pixelFormatFromLibcameraName(const char* name, PixelFormat& format) {
  for (const PixelFormat candidate :
       {PixelFormat::kGrey8, PixelFormat::kY10, PixelFormat::kY12, PixelFormat::kYuyv}) {
    if (std::strcmp(name, libcameraFormatName(candidate)) == 0) {
      format = candidate;
      return true;
    }
  }
  return false;
}

FormatCandidates formatCandidates(RequestedFormat requested) {
  FormatCandidates out;
  const char* wanted_name = libcameraFormatName(static_cast<PixelFormat>(requested));
  LibcameraFormat wanted = LibcameraFormat::kR8;
  if (wanted_name == nullptr || !libcameraFormatFromName(wanted_name, wanted)) return out;
  out.formats[static_cast<std::size_t>(out.count++)] = wanted;
  // The enum is in preference order: mono, Y plane, YUYV, RGB.
  for (int i = 0; i < kLibcameraFormatCount; ++i) {
    const auto format = static_cast<LibcameraFormat>(i);
    if (format != wanted) out.formats[static_cast<std::size_t>(out.count++)] = format;
  }
  return out;
}

std::size_t firstPlaneBytes(LibcameraFormat format, int width, int height, std::size_t stride_bytes) {
  if (width <= 0 || height <= 0) return 0;
  const auto row =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(formatInfo(format).bytes_per_pixel);
  return stride_bytes * static_cast<std::size_t>(height - 1) + row;
}

const char* toString(LibcameraRole role) {
  switch (role) {
    case LibcameraRole::kViewfinder: return "viewfinder";
    case LibcameraRole::kRaw: return "raw";
    case LibcameraRole::kStillCapture: return "still_capture";
  }
  return "unknown";
}

}  // namespace visnav::camera
