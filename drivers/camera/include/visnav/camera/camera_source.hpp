// The one small camera interface every driver implements (v4l2, libcamera, replay, synthetic), selected by
// config. Contract:
//  - open() does all allocation and OS setup (init time; may block; returns a message on failure);
//  - acquire() waits at most `timeout_ns` for the next frame and never allocates; kTimeout is not a fault
//    by itself (the caller counts it), kDeviceLost asks the caller to try recover();
//  - every frame returned by acquire() is handed back with release() before the next acquire();
//  - counters are cumulative since open();
//  - a live driver also reports its state and queues events (state changes, errors that cost no frame: a
//    buffer the kernel refused back) for the caller to drain and log once per cycle (camera_events.hpp).
#pragma once

#include <cstdint>
#include <string>

#include "visnav/camera/camera_events.hpp"
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
  /// Gives the frame's buffer back. A failure is counted (counters().errors), queued as an event and, for a
  /// buffer the kernel refused, retried by the next acquire(): no buffer is lost for good.
  virtual void release(const Frame& frame) = 0;
  /// Reopens a lost device when an attempt is due (one bounded attempt per call, spaced by RetryBackoff after
  /// the quick ones; no allocation beyond what open() sized); true when streaming. Never gives up.
  virtual bool recover() = 0;
  virtual void close() = 0;
  virtual const CameraCounters& counters() const = 0;
  /// Static text describing the last error (no allocation on the cycle path).
  virtual const char* lastError() const = 0;
  virtual const char* name() const = 0;
  /// Streaming, lost or retrying (playback sources: streaming once open).
  virtual CameraState state() const { return CameraState::kStreaming; }
  /// The oldest queued event; false when none (bounded: the queue holds CameraEventQueue::kCapacity).
  virtual bool nextEvent(CameraEvent& /*event*/) { return false; }
};

}  // namespace visnav::camera
