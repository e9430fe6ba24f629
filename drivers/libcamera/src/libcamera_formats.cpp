#include "visnav/libcamera/libcamera_formats.hpp"

#include <cstring>

namespace visnav::camera {

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
  const auto wanted = static_cast<PixelFormat>(requested);
  if (libcameraFormatName(wanted) == nullptr) return out;
  out.formats[static_cast<std::size_t>(out.count++)] = wanted;
  for (const PixelFormat fallback :
       {PixelFormat::kGrey8, PixelFormat::kY10, PixelFormat::kY12, PixelFormat::kYuyv})
    if (fallback != wanted) out.formats[static_cast<std::size_t>(out.count++)] = fallback;
  return out;
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
