// Live camera through Video4Linux2 (single-planar capture, mmap streaming). open() negotiates the format,
// sets the frame interval, maps a fixed ring of kernel buffers and starts streaming; acquire() polls with a
// bounded timeout and hands out the newest frame as a view into its mmap buffer (GREY, Y10, Y12, Y16) or into
// the Y plane copied at open()-sized storage (YUYV); release() queues the buffer again. Counters: sequence
// gaps between delivered frames are dropped frames. When the device goes away (ENODEV/EIO/ENXIO) the ring is
// torn down and acquire() says kDeviceLost until a recover() call reopens the same node with the same format
// (quick attempts, then a back-off capped at 2 s, for as long as it takes). A buffer the kernel refuses back
// (QBUF error) is kept and requeued by the next acquire(); a ring that stays short is restarted. State
// changes and such errors are queued as events (nextEvent). Every OS call goes through V4l2Os. Nothing
// allocates after open(). Design note: drivers/v4l2/README.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "visnav/camera/camera_events.hpp"
#include "visnav/camera/camera_params.hpp"
#include "visnav/camera/camera_source.hpp"
#include "visnav/camera/sequence_tracker.hpp"
#include "visnav/v4l2/v4l2_os.hpp"

namespace visnav::camera {

/// What the device granted at the last (re)open, for logs and health.
struct V4l2StreamInfo {
  char driver[16] = {};      ///< v4l2_capability::driver
  char card[32] = {};        ///< v4l2_capability::card
  std::uint32_t fourcc = 0;  ///< negotiated pixel format
  std::uint32_t width = 0;   ///< negotiated size [px]
  std::uint32_t height = 0;
  std::size_t bytes_per_line = 0;        ///< row stride of the device buffers
  std::size_t image_bytes = 0;           ///< sizeimage
  int buffer_count = 0;                  ///< buffers granted by VIDIOC_REQBUFS
  bool frame_interval_set = false;       ///< VIDIOC_S_PARM accepted (else the device runs at its own rate)
  std::uint32_t interval_numerator = 0;  ///< frame interval the device reports [s] = num / den
  std::uint32_t interval_denominator = 0;
};

class V4l2Camera final : public CameraSource {
 public:
  static constexpr int kMaxBuffers = 32;

  explicit V4l2Camera(const CameraParams& params, V4l2Os& os = realV4l2Os());
  ~V4l2Camera() override;
  V4l2Camera(const V4l2Camera&) = delete;
  V4l2Camera& operator=(const V4l2Camera&) = delete;

  LoadError open() override;
  AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) override;
  void release(const Frame& frame) override;
  bool recover() override;
  void close() override;
  const CameraCounters& counters() const override { return m_counters; }
  const char* lastError() const override { return m_last_error; }
  const char* name() const override { return "v4l2"; }
  CameraState state() const override { return m_state; }
  bool nextEvent(CameraEvent& event) override { return m_events.pop(event); }

  const V4l2StreamInfo& streamInfo() const { return m_info; }
  /// errno of the last failed OS call (0: none).
  int lastErrno() const { return m_last_errno; }
  /// Older ready frames requeued unseen because a newer one was ready (part of frames_dropped).
  std::uint64_t staleFramesSkipped() const { return m_stale_skipped; }
  /// Frames the driver flagged V4L2_BUF_FLAG_ERROR or delivered short (part of frames_dropped).
  std::uint64_t corruptFrames() const { return m_corrupt_frames; }
  /// Frames whose driver timestamp was not CLOCK_MONOTONIC, stamped at dequeue instead.
  std::uint64_t timestampFallbacks() const { return m_timestamp_fallbacks; }
  /// Buffers the kernel refused in VIDIOC_QBUF (each kept and retried, never lost).
  std::uint64_t requeueErrors() const { return m_requeue_errors; }
  /// Stream restarts because refused buffers left the ring short (each also a device loss + recovery).
  std::uint64_t streamRestarts() const { return m_stream_restarts; }
  /// Buffers waiting for a requeue now.
  int pendingRequeues() const { return m_pending_count; }
  /// Events dropped because the queue was full (the caller did not drain it).
  std::uint64_t eventsDropped() const { return m_events.dropped(); }
  /// Refused buffers are retried while the driver still has this many; fewer restart the stream.
  static constexpr int kMinDriverBuffers = 2;

 private:
  struct Slot {
    const std::uint8_t* start = nullptr;
    std::size_t length = 0;
  };
  enum class Dequeue : std::uint8_t { kFrame, kNothing, kCorruptOnly, kLost, kError };

  // Setup (v4l2_camera.cpp): each returns nullptr or a static reason, with m_last_errno set.
  const char* setUp(bool first_open);
  const char* queryCapabilities();
  const char* negotiateFormat(bool first_open);
  const char* setFrameInterval();
  const char* mapRing();
  void tearDown();
  std::string describeFailure(const char* reason) const;

  // Streaming (v4l2_stream.cpp).
  Dequeue dequeueNewest(int& index, std::uint32_t& sequence, std::int64_t& timestamp_ns);
  bool queueBuffer(int index);
  AcquireResult deviceFailure(const char* what, int error_number);
  /// A buffer the kernel refused (not a lost device): kept for a retry, counted, reported.
  void parkBuffer(int index, const char* what, int error_number);
  /// Counts one refused QBUF of buffer `index` (a first refusal or a retry's) and queues its event.
  void reportRefusedBuffer(int index, const char* what, int error_number);
  /// Retries the parked buffers; false when the stream had to be restarted or the device is gone.
  bool requeueParked();
  void setError(const char* what, int error_number);
  void changeState(CameraState to, std::int64_t now_ns);
  void deliver(int index, std::uint32_t sequence, std::int64_t timestamp_ns, Frame& frame);

  CameraParams m_params;
  V4l2Os& m_os;
  PixelFormat m_format;
  CameraState m_state = CameraState::kClosed;
  int m_fd = -1;
  std::array<Slot, kMaxBuffers> m_ring{};
  int m_ring_size = 0;
  int m_held = -1;                   // ring slot handed out by acquire(), -1 when none
  std::vector<std::uint8_t> m_luma;  // YUYV only: width * height, sized in open()
  V4l2StreamInfo m_info;
  SequenceTracker m_sequence;  // frame.sequence stays increasing across driver restarts (recover())
  RetryBackoff m_backoff;
  CameraEventQueue m_events;
  std::array<bool, kMaxBuffers> m_parked{};  // refused by VIDIOC_QBUF, requeued by the next acquire()
  int m_pending_count = 0;
  int m_requeue_rounds =
      0;  // acquire() calls in a row that still found a parked buffer refused (for the text)
  CameraCounters m_counters;
  std::uint64_t m_requeue_errors = 0;
  std::uint64_t m_stream_restarts = 0;
  std::uint64_t m_stale_skipped = 0;
  std::uint64_t m_corrupt_frames = 0;
  std::uint64_t m_timestamp_fallbacks = 0;
  const char* m_last_error = "";
  char m_error_text[CameraEvent::kTextCapacity] = {};  // m_last_error with the errno spelled out
  int m_last_errno = 0;
};

}  // namespace visnav::camera
