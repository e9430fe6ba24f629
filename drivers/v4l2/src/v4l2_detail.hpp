// Small helpers shared by the V4L2 driver's translation units (not part of the public interface).
#pragma once

#include <linux/videodev2.h>

#include <cerrno>
#include <cstdint>
#include <string>

#include "visnav/core/frame.hpp"

namespace visnav::camera::v4l2detail {

inline std::uint32_t fourccOf(PixelFormat format) {
  switch (format) {
    case PixelFormat::kGrey8: return V4L2_PIX_FMT_GREY;
    case PixelFormat::kY10: return V4L2_PIX_FMT_Y10;
    case PixelFormat::kY12: return V4L2_PIX_FMT_Y12;
    case PixelFormat::kY16: return V4L2_PIX_FMT_Y16;
    case PixelFormat::kYuyv: return V4L2_PIX_FMT_YUYV;
  }
  return 0;
}

/// "GREY", "Y10 " ...: the four characters of a fourcc (init-time messages only).
inline std::string fourccText(std::uint32_t fourcc) {
  std::string text(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const auto c = static_cast<char>((fourcc >> (8 * i)) & 0xFFU);
    text[static_cast<std::size_t>(i)] = (c >= 32 && c < 127) ? c : '?';
  }
  return text;
}

/// errno values meaning the device is gone (unplugged, driver unbound, hardware fault), not a usage error.
inline bool isDeviceGone(int error_number) {
  return error_number == ENODEV || error_number == EIO || error_number == ENXIO;
}

}  // namespace visnav::camera::v4l2detail
