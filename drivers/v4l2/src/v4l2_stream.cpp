// V4l2Camera streaming: acquire() and release(). No allocation, every loop bounded by the ring size or a
// small retry count.
#include <linux/videodev2.h>
#include <poll.h>

#include <cerrno>
#include <cstdio>

#include "v4l2_detail.hpp"
#include "visnav/camera/mono_view.hpp"
#include "visnav/camera/os_error.hpp"
#include "visnav/v4l2/v4l2_camera.hpp"

namespace visnav::camera {
namespace {

constexpr int kMaxPollRounds = 8;  // EINTR / spurious wake-ups tolerated within one acquire()

int remainingMs(std::int64_t deadline_ns, std::int64_t now_ns) {
  const std::int64_t left_ns = deadline_ns - now_ns;
  if (left_ns <= 0) return 0;
  const std::int64_t ms = (left_ns + 999999) / 1000000;  // round up: never return before the deadline
  return ms > 1000000000 ? 1000000000 : static_cast<int>(ms);
}

}  // namespace

AcquireResult V4l2Camera::acquire(std::int64_t timeout_ns, Frame& frame) {
  if (m_state == CameraState::kLost || m_state == CameraState::kRetrying) return AcquireResult::kDeviceLost;
  if (m_state != CameraState::kStreaming || m_held >= 0) {
    m_last_error =
        m_held >= 0 ? "acquire() before the previous frame was released" : "acquire() on a closed camera";
    ++m_counters.errors;
    return AcquireResult::kError;
  }
  // Buffers refused earlier go back first: a ring that only shrinks would starve the stream.
  if (m_pending_count > 0 && !requeueParked()) return AcquireResult::kDeviceLost;
  const std::int64_t deadline_ns = m_os.monotonicNs() + (timeout_ns > 0 ? timeout_ns : 0);
  for (int round = 0; round < kMaxPollRounds; ++round) {
    pollfd descriptor{m_fd, POLLIN, 0};
    const int ready = m_os.poll(&descriptor, 1, remainingMs(deadline_ns, m_os.monotonicNs()));
    if (ready < 0) {
      if (errno == EINTR) continue;
      return deviceFailure("poll on the device", errno);
    }
    if (ready == 0) break;
    // Readable, or POLLERR/POLLHUP: VIDIOC_DQBUF tells which (ENODEV when the device vanished).
    int index = -1;
    std::uint32_t sequence = 0;
    std::int64_t timestamp_ns = 0;
    switch (dequeueNewest(index, sequence, timestamp_ns)) {
      case Dequeue::kFrame: deliver(index, sequence, timestamp_ns, frame); return AcquireResult::kFrame;
      case Dequeue::kLost: return AcquireResult::kDeviceLost;
      case Dequeue::kError: return AcquireResult::kError;
      case Dequeue::kCorruptOnly:
        m_last_error = "the driver delivered only corrupt frames (V4L2_BUF_FLAG_ERROR or short)";
        ++m_counters.errors;
        return AcquireResult::kError;
      case Dequeue::kNothing:
        if ((descriptor.revents & (POLLERR | POLLHUP | POLLNVAL)) != 0) {
          m_last_error = "poll reports an error on the device but no buffer is ready";
          ++m_counters.errors;
          return AcquireResult::kError;
        }
        break;  // spurious wake-up: poll again for the time left
    }
    if (remainingMs(deadline_ns, m_os.monotonicNs()) == 0) break;
  }
  ++m_counters.timeouts;
  return AcquireResult::kTimeout;
}

void V4l2Camera::release(const Frame& frame) {
  if (m_held < 0 || frame.buffer_index != m_held) {
    m_last_error = "release() of a frame this camera did not hand out";
    ++m_counters.errors;
    return;
  }
  const int index = m_held;
  m_held = -1;
  if (m_state != CameraState::kStreaming) return;  // lost meanwhile: the ring is gone already
  if (!queueBuffer(index)) {
    if (v4l2detail::isDeviceGone(m_last_errno))
      deviceFailure("VIDIOC_QBUF", m_last_errno);
    else
      parkBuffer(index, "VIDIOC_QBUF (release)", m_last_errno);
  }
}

V4l2Camera::Dequeue V4l2Camera::dequeueNewest(int& index, std::uint32_t& sequence,
                                              std::int64_t& timestamp_ns) {
  // Drain what is ready and keep the newest: a cycle slower than the camera then sees the freshest frame, not
  // one ring-length old. Requeued older frames show up as sequence gaps (dropped) and in
  // staleFramesSkipped().
  const std::size_t needed =
      minimumBufferBytes(m_format, m_params.width_px, m_params.height_px, m_info.bytes_per_line);
  bool corrupt_seen = false;
  for (int round = 0; round < m_ring_size; ++round) {
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    if (m_os.ioctl(m_fd, VIDIOC_DQBUF, &buffer) < 0) {
      const int error_number = errno;
      if (error_number == EAGAIN) break;
      if (error_number == EINTR) continue;
      const AcquireResult result = deviceFailure("VIDIOC_DQBUF", error_number);
      return result == AcquireResult::kDeviceLost ? Dequeue::kLost : Dequeue::kError;
    }
    if (buffer.index >= static_cast<std::uint32_t>(m_ring_size)) {
      m_last_error = "VIDIOC_DQBUF returned a buffer index outside the ring";
      ++m_counters.errors;
      return Dequeue::kError;
    }
    const int dequeued = static_cast<int>(buffer.index);
    if ((buffer.flags & V4L2_BUF_FLAG_ERROR) != 0U || buffer.bytesused < needed) {
      ++m_corrupt_frames;
      corrupt_seen = true;
      if (!queueBuffer(dequeued)) {
        if (v4l2detail::isDeviceGone(m_last_errno)) {
          deviceFailure("VIDIOC_QBUF", m_last_errno);
          return Dequeue::kLost;
        }
        parkBuffer(dequeued, "VIDIOC_QBUF (corrupt frame)", m_last_errno);
      }
      continue;
    }
    if (index >= 0) {
      ++m_stale_skipped;
      if (!queueBuffer(index)) {
        if (v4l2detail::isDeviceGone(m_last_errno)) {
          deviceFailure("VIDIOC_QBUF", m_last_errno);
          return Dequeue::kLost;
        }
        parkBuffer(index, "VIDIOC_QBUF (stale frame)", m_last_errno);
      }
    }
    index = dequeued;
    sequence = buffer.sequence;
    if ((buffer.flags & V4L2_BUF_FLAG_TIMESTAMP_MASK) == V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC) {
      timestamp_ns = static_cast<std::int64_t>(buffer.timestamp.tv_sec) * 1000000000LL +
                     static_cast<std::int64_t>(buffer.timestamp.tv_usec) * 1000LL;
    } else {
      timestamp_ns = m_os.monotonicNs();  // unknown or copied clock: dequeue time is the best we have
      ++m_timestamp_fallbacks;
    }
  }
  if (index >= 0) return Dequeue::kFrame;
  return corrupt_seen ? Dequeue::kCorruptOnly : Dequeue::kNothing;
}

bool V4l2Camera::queueBuffer(int index) {
  v4l2_buffer buffer{};
  buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  buffer.memory = V4L2_MEMORY_MMAP;
  buffer.index = static_cast<std::uint32_t>(index);
  if (m_os.ioctl(m_fd, VIDIOC_QBUF, &buffer) < 0) {
    m_last_errno = errno;
    return false;
  }
  return true;
}

AcquireResult V4l2Camera::deviceFailure(const char* what, int error_number) {
  setError(what, error_number);
  m_last_errno = error_number;
  if (!v4l2detail::isDeviceGone(error_number)) {
    ++m_counters.errors;
    return AcquireResult::kError;
  }
  tearDown();
  m_held = -1;
  ++m_counters.device_losses;
  changeState(CameraState::kLost, m_os.monotonicNs());
  return AcquireResult::kDeviceLost;
}

void V4l2Camera::parkBuffer(int index, const char* what, int error_number) {
  const auto slot = static_cast<std::size_t>(index);
  if (!m_parked[slot]) {
    m_parked[slot] = true;
    ++m_pending_count;
  }
  reportRefusedBuffer(index, what, error_number);
}

void V4l2Camera::reportRefusedBuffer(int index, const char* what, int error_number) {
  // Every refusal is counted and reported, a retry's too: a fault monitor (or a test pressing vivid's
  // injection) must see each one, whichever QBUF it hit.
  ++m_requeue_errors;
  ++m_counters.errors;
  setError(what, error_number);
  CameraEvent event;
  event.kind = CameraEventKind::kReleaseError;
  event.from = event.to = m_state;
  event.time_ns = m_os.monotonicNs();
  event.pending = static_cast<std::uint32_t>(m_pending_count);
  std::snprintf(event.text, sizeof(event.text), "%s; buffer %d kept for a retry", m_last_error, index);
  m_events.push(event);
}

bool V4l2Camera::requeueParked() {
  for (int i = 0; i < m_ring_size; ++i) {
    const auto slot = static_cast<std::size_t>(i);
    if (!m_parked[slot]) continue;
    if (queueBuffer(i)) {
      m_parked[slot] = false;
      --m_pending_count;
    } else if (v4l2detail::isDeviceGone(m_last_errno)) {
      deviceFailure("VIDIOC_QBUF (retry)", m_last_errno);
      return false;
    } else {
      reportRefusedBuffer(i, "VIDIOC_QBUF (retry)", m_last_errno);
    }
  }
  if (m_pending_count == 0) {
    m_requeue_rounds = 0;
    return true;
  }
  // Still refused. While the driver keeps at least kMinDriverBuffers the stream runs and the next acquire()
  // retries; a ring that short no longer streams reliably, so a full restart (like a reopen after a loss)
  // gives the driver a fresh ring.
  ++m_requeue_rounds;
  const int with_driver = m_ring_size - m_pending_count;
  if (with_driver >= kMinDriverBuffers) return true;
  ++m_stream_restarts;
  CameraEvent event;
  event.kind = CameraEventKind::kStreamRestart;
  event.from = event.to = m_state;
  event.time_ns = m_os.monotonicNs();
  event.pending = static_cast<std::uint32_t>(m_pending_count);
  std::snprintf(event.text, sizeof(event.text),
                "%s; %d of %d buffers refused (%d retries): restarting the stream", m_last_error,
                m_pending_count, m_ring_size, m_requeue_rounds);
  m_events.push(event);
  const int refused_errno = m_last_errno;
  tearDown();
  m_held = -1;
  ++m_counters.device_losses;
  setError("VIDIOC_QBUF kept refusing buffers: stream restarted", refused_errno);
  changeState(CameraState::kLost, m_os.monotonicNs());
  return false;
}

void V4l2Camera::deliver(int index, std::uint32_t sequence, std::int64_t timestamp_ns, Frame& frame) {
  const std::uint64_t frame_sequence = m_sequence.next(sequence, m_counters.frames_dropped);
  const Slot& slot = m_ring[static_cast<std::size_t>(index)];
  frame.image = isZeroCopy(m_format) ? viewInPlace(m_format, slot.start, m_params.width_px,
                                                   m_params.height_px, m_info.bytes_per_line)
                                     : extractLumaYuyv(slot.start, m_params.width_px, m_params.height_px,
                                                       m_info.bytes_per_line, m_luma.data());
  frame.exposure_time_ns = timestamp_ns;
  frame.sequence = frame_sequence;
  frame.source_format = m_format;
  frame.buffer_index = index;
  m_held = index;
  ++m_counters.frames_delivered;
}

}  // namespace visnav::camera
