// The one small camera interface every driver implements (v4l2, libcamera, replay, synthetic), selected by
// config. Contract:
//  - open() does all allocation and OS setup (init time; may block; returns a message on failure);
//  - acquire() waits at most `timeout_ns` for the next frame and never allocates; kTimeout is not a fault
//    by itself (the caller counts it), kDeviceLost asks the caller to try recover();
//  - every frame returned by acquire() is handed back with release() before the next acquire();
//  - counters are cumulative since open().
#pragma once

#include <cstdint>
#include <string>

#include "visnav/core/frame.hpp"
#include "visnav/core/status.hpp"

namespace visnav::camera {

enum class AcquireResult : std::uint8_t {
  kFrame = 0,        ///< a frame was delivered
  kTimeout = 1,      ///< nothing within the timeout
  kEndOfStream = 2,  ///< replay finished (never for live cameras)
  kDeviceLost = 3,   ///< the device went away; recover() may bring it back
  kError = 4,        ///< any other failure (counted; see lastError())
};
const char* toString(AcquireResult result);

struct CameraCounters {
  std::uint64_t frames_delivered = 0;
  std::uint64_t frames_dropped = 0;  ///< from sequence-number gaps
  std::uint64_t timeouts = 0;
  std::uint64_t errors = 0;
  std::uint64_t device_losses = 0;  ///< times acquire()/release() found the device gone
  std::uint64_t recoveries = 0;     ///< successful recover() calls
};

class CameraSource {
 public:
  virtual ~CameraSource() = default;
  virtual LoadError open() = 0;
  virtual AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) = 0;
  virtual void release(const Frame& frame) = 0;
  /// Bounded attempt to reopen a lost device (no allocation beyond what open() sized); true on success.
  virtual bool recover() = 0;
  virtual void close() = 0;
  virtual const CameraCounters& counters() const = 0;
  /// Static text describing the last error (no allocation on the cycle path).
  virtual const char* lastError() const = 0;
  virtual const char* name() const = 0;
};

}  // namespace visnav::camera
