// What a live driver tells its caller besides frames: its state (streaming, lost, retrying), every change of
// it, and errors that cost no frame (a buffer the kernel refused to take back). The driver queues events in a
// fixed ring; the caller drains them once per cycle (CameraSource::nextEvent) and logs them. The reopen
// back-off after a loss is here too, so both live drivers retry on the same schedule.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace visnav::camera {

enum class CameraState : std::uint8_t {
  kClosed = 0,
  kStreaming = 1,
  kLost = 2,      ///< the device went away; a reopen is tried on every recover() call
  kRetrying = 3,  ///< the quick attempts failed; reopens continue on the back-off schedule, never give up
};
const char* toString(CameraState state);

enum class CameraEventKind : std::uint8_t {
  kStateChange = 0,   ///< from -> to (log event camera_state)
  kReleaseError = 1,  ///< the kernel refused a buffer back; kept for a retry (log event camera_release_error)
  kStreamRestart =
      2,  ///< too few buffers left in the ring: the stream is restarted (log event camera_restart)
};
const char* eventName(CameraEventKind kind);

struct CameraEvent {
  static constexpr std::size_t kTextCapacity = 160;
  CameraEventKind kind = CameraEventKind::kStateChange;
  CameraState from = CameraState::kClosed;
  CameraState to = CameraState::kClosed;
  std::int64_t time_ns = 0;            ///< CLOCK_MONOTONIC (the driver's clock)
  std::uint32_t attempts = 0;          ///< reopen attempts since the loss
  std::int64_t down_ns = 0;            ///< back to streaming: time since the loss
  std::int64_t retry_interval_ns = 0;  ///< kRetrying: current spacing of the attempts
  std::uint32_t pending = 0;           ///< buffers waiting for a requeue (release errors, restarts)
  char text[kTextCapacity] = {};       ///< the cause, with errno name and text where there is one
};

/// "from=lost to=retrying attempts=25 retry_interval_ms=200 down_ms=5012 pending=0 error=\"...\"" (the
/// fields that apply), into `out`; quotes in the text become '. Returns `out`.
const char* formatEvent(const CameraEvent& event, char* out, std::size_t capacity);

/// Fixed ring of events. When full, the newest event is dropped and counted (the oldest ones say how the
/// trouble started; the state is always readable from the driver).
class CameraEventQueue {
 public:
  static constexpr int kCapacity = 16;
  void push(const CameraEvent& event) {
    if (m_count == kCapacity) {
      ++m_dropped;
      return;
    }
    m_events[static_cast<std::size_t>((m_head + m_count) % kCapacity)] = event;
    ++m_count;
  }
  bool pop(CameraEvent& event) {
    if (m_count == 0) return false;
    event = m_events[static_cast<std::size_t>(m_head)];
    m_head = (m_head + 1) % kCapacity;
    --m_count;
    return true;
  }
  int size() const { return m_count; }
  std::uint64_t dropped() const { return m_dropped; }
  void clear() { m_head = m_count = 0; }

 private:
  std::array<CameraEvent, kCapacity> m_events{};
  int m_head = 0;
  int m_count = 0;
  std::uint64_t m_dropped = 0;
};

/// When the next reopen attempt after a loss is due. The first `quick_attempts` attempts run on every call
/// (the caller calls once per cycle); after that the spacing starts at kFirstIntervalNs and doubles up to
/// kMaxIntervalNs, where it stays for as long as the device is away: a flight camera can come back at any
/// time, and 2 s bounds how long it then waits for us. Pure: the caller passes the time.
class RetryBackoff {
 public:
  static constexpr std::int64_t kFirstIntervalNs = 250'000'000;
  static constexpr std::int64_t kMaxIntervalNs = 2'000'000'000;

  void start(std::int64_t now_ns, int quick_attempts) {
    m_lost_ns = now_ns;
    m_next_ns = now_ns;
    m_quick = quick_attempts < 0 ? 0 : quick_attempts;
    m_attempts = 0;
    m_interval_ns = 0;
  }
  bool due(std::int64_t now_ns) const { return now_ns >= m_next_ns; }
  /// Counts an attempt made at `now_ns` that failed and schedules the next one.
  void failed(std::int64_t now_ns) {
    ++m_attempts;
    if (m_attempts < static_cast<std::uint32_t>(m_quick)) {
      m_next_ns = now_ns;
      return;
    }
    m_interval_ns = m_interval_ns == 0
                        ? kFirstIntervalNs
                        : (m_interval_ns >= kMaxIntervalNs / 2 ? kMaxIntervalNs : 2 * m_interval_ns);
    m_next_ns = now_ns + m_interval_ns;
  }
  /// True once the quick attempts are used up (the caller reports kRetrying).
  bool backingOff() const { return m_attempts >= static_cast<std::uint32_t>(m_quick); }
  std::uint32_t attempts() const { return m_attempts; }
  std::int64_t intervalNs() const { return m_interval_ns; }
  std::int64_t lostNs() const { return m_lost_ns; }

 private:
  std::int64_t m_lost_ns = 0;
  std::int64_t m_next_ns = 0;
  std::int64_t m_interval_ns = 0;
  std::uint32_t m_attempts = 0;
  int m_quick = 0;
};

/// The event of a driver's state change `from` -> `to` at `now_ns`, with the back-off's attempt count and
/// spacing, the time down (since the loss), the buffers waiting for a requeue and the cause `text`.
CameraEvent stateChangeEvent(CameraState from, CameraState to, std::int64_t now_ns,
                             const RetryBackoff& backoff, std::uint32_t pending, const char* text);

}  // namespace visnav::camera
