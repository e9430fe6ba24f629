// Which libcamera pixel format stands for which visnav format, and in which order the driver tries them when
// the camera cannot deliver the requested one. Pure tables, testable without a camera.
#pragma once

#include <array>

#include "visnav/camera/camera_params.hpp"
#include "visnav/core/frame.hpp"

namespace visnav::camera {

/// libcamera 0.0.3 name ("R8", "R10", "R12", "YUYV"), or nullptr when it has none (Y16).
const char* libcameraFormatName(PixelFormat format);
/// Inverse of libcameraFormatName; false for a name with no visnav meaning.
bool pixelFormatFromLibcameraName(const char* name, PixelFormat& format);

/// The requested format first, then the others mono-first (R8, R10, R12, YUYV); Y16 requested: none valid.
struct FormatCandidates {
  std::array<PixelFormat, 4> formats{};
  int count = 0;
};
FormatCandidates formatCandidates(RequestedFormat requested);

const char* toString(LibcameraRole role);

}  // namespace visnav::camera
