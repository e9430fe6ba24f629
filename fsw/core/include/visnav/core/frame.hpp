// One camera frame as it travels through a cycle (fsw/app/README.md, "The cycle"): a non-owning mono view
// into a driver-owned buffer plus the metadata the estimators and the telemetry need. The driver gets the
// buffer back when the cycle calls CameraSource::release().
#pragma once

#include <cstdint>

#include "visnav/core/image_view.hpp"

namespace visnav {

/// Pixel format delivered by the sensor, before conversion to the mono view.
enum class PixelFormat : std::uint8_t { kGrey8 = 0, kY10 = 1, kY12 = 2, kY16 = 3, kYuyv = 4 };
const char* toString(PixelFormat format);

struct Frame {
  MonoImage image;  ///< 8- or 16-bit mono view (driver memory or driver-side conversion buffer)
  std::int64_t exposure_time_ns = 0;  ///< mid-exposure (or driver) timestamp, CLOCK_MONOTONIC [ns]
  std::uint64_t sequence = 0;         ///< driver sequence number; gaps mean dropped frames
  PixelFormat source_format = PixelFormat::kGrey8;
  int buffer_index = -1;  ///< driver ring slot, handed back in release()
};

}  // namespace visnav
