#include "visnav/camera/camera_source.hpp"

#include <cinttypes>
#include <cstdio>

namespace visnav::camera {

const char* toString(AcquireResult result) {
  switch (result) {
    case AcquireResult::kFrame: return "frame";
    case AcquireResult::kTimeout: return "timeout";
    case AcquireResult::kEndOfStream: return "end_of_stream";
    case AcquireResult::kDeviceLost: return "device_lost";
    case AcquireResult::kError: return "error";
  }
  return "unknown";
}

const char* toString(CameraState state) {
  switch (state) {
    case CameraState::kClosed: return "closed";
    case CameraState::kStreaming: return "streaming";
    case CameraState::kLost: return "lost";
    case CameraState::kRetrying: return "retrying";
  }
  return "unknown";
}

const char* eventName(CameraEventKind kind) {
  switch (kind) {
    case CameraEventKind::kStateChange: return "camera_state";
    case CameraEventKind::kReleaseError: return "camera_release_error";
    case CameraEventKind::kStreamRestart: return "camera_restart";
  }
  return "camera_event";
}

const char* formatEvent(const CameraEvent& event, char* out, std::size_t capacity) {
  if (capacity == 0) return out;
  char text[CameraEvent::kTextCapacity];
  std::size_t n = 0;
  for (; n + 1 < sizeof(text) && event.text[n] != '\0'; ++n)
    text[n] = event.text[n] == '"' ? '\'' : event.text[n];
  text[n] = '\0';
  const auto ms = [](std::int64_t ns) { return static_cast<long long>(ns / 1000000); };
  if (event.kind == CameraEventKind::kStateChange)
    std::snprintf(out, capacity,
                  "from=%s to=%s attempts=%" PRIu32 " retry_interval_ms=%lld down_ms=%lld error=\"%s\"",
                  toString(event.from), toString(event.to), event.attempts, ms(event.retry_interval_ns),
                  ms(event.down_ns), text);
  else
    std::snprintf(out, capacity, "pending=%" PRIu32 " error=\"%s\"", event.pending, text);
  return out;
}

CameraEvent stateChangeEvent(CameraState from, CameraState to, std::int64_t now_ns,
                             const RetryBackoff& backoff, std::uint32_t pending, const char* text) {
  CameraEvent event;
  event.kind = CameraEventKind::kStateChange;
  event.from = from;
  event.to = to;
  event.time_ns = now_ns;
  event.attempts = backoff.attempts() + (to == CameraState::kStreaming ? 1U : 0U);  // the one that worked
  event.retry_interval_ns = backoff.intervalNs();
  event.down_ns = to == CameraState::kLost ? 0 : now_ns - backoff.lostNs();
  event.pending = pending;
  std::snprintf(event.text, sizeof(event.text), "%s", text != nullptr ? text : "");
  return event;
}

}  // namespace visnav::camera
