// LibcameraCamera streaming: the completion hand-over from libcamera's thread, acquire() and release().
// Nothing here allocates (fixed queue, requests reused); what libcamera does inside reuse()/queueRequest() is
// its own (drivers/README.md).
#include <libcamera/control_ids.h>
#include <libcamera/framebuffer.h>

#include <cerrno>
#include <chrono>
#include <cstdio>

#include "libcamera_impl.hpp"
#include "visnav/camera/mono_view.hpp"

namespace visnav::camera {

void LibcameraCamera::Impl::onRequestCompleted(libcamera::Request* request) {
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (completed_count < kMaxRequests) {  // never full: at most one entry per request
      completed[static_cast<std::size_t>((completed_head + completed_count) % kMaxRequests)] = request;
      ++completed_count;
    }
  }
  completed_ready.notify_one();
}

void LibcameraCamera::Impl::onDisconnected() {
  {
    std::lock_guard<std::mutex> lock(mutex);
    disconnected = true;
  }
  completed_ready.notify_one();
}

AcquireResult LibcameraCamera::acquire(std::int64_t timeout_ns, Frame& frame) {
  Impl& impl = *m_impl;
  if (impl.state == CameraState::kLost || impl.state == CameraState::kRetrying)
    return AcquireResult::kDeviceLost;
  if (impl.state != CameraState::kStreaming || impl.held >= 0) {
    impl.last_error =
        impl.held >= 0 ? "acquire() before the previous frame was released" : "acquire() on a closed camera";
    ++impl.counters.errors;
    return AcquireResult::kError;
  }
  // Requests refused earlier go back first: a ring that only shrinks would starve the stream.
  if (impl.parked_count > 0 && !impl.requeueParked()) return AcquireResult::kDeviceLost;
  libcamera::Request* newest = nullptr;
  std::array<libcamera::Request*, Impl::kMaxRequests> older{};
  int older_count = 0;
  {
    std::unique_lock<std::mutex> lock(impl.mutex);
    const auto ready = [&impl] { return impl.completed_count > 0 || impl.disconnected.load(); };
    if (!impl.completed_ready.wait_for(lock, std::chrono::nanoseconds(timeout_ns > 0 ? timeout_ns : 0),
                                       ready)) {
      ++impl.counters.timeouts;
      return AcquireResult::kTimeout;
    }
    // Drain and keep the newest (as in the V4L2 driver): the older ones go straight back to the camera.
    while (impl.completed_count > 0) {
      if (newest != nullptr) older[static_cast<std::size_t>(older_count++)] = newest;
      newest = impl.completed[static_cast<std::size_t>(impl.completed_head)];
      impl.completed_head = (impl.completed_head + 1) % Impl::kMaxRequests;
      --impl.completed_count;
    }
  }
  if (impl.disconnected) {
    // The completed requests die with the camera: none may be requeued (stopCamera() frees them).
    return impl.lose("the camera was disconnected");
  }
  for (int i = 0; i < older_count; ++i) {
    ++impl.stale_skipped;
    if (!impl.requeue(older[static_cast<std::size_t>(i)]) && impl.state != CameraState::kStreaming)
      return AcquireResult::kDeviceLost;
  }
  const libcamera::FrameBuffer* buffer = newest->findBuffer(impl.stream);
  if (newest->status() != libcamera::Request::RequestComplete || buffer == nullptr ||
      buffer->metadata().status != libcamera::FrameMetadata::FrameSuccess) {
    impl.last_error = "libcamera completed a request without a good frame (cancelled or FrameError)";
    ++impl.counters.errors;
    if (!impl.requeue(newest) && impl.state != CameraState::kStreaming) return AcquireResult::kDeviceLost;
    return AcquireResult::kError;
  }
  impl.deliver(newest, frame);
  return AcquireResult::kFrame;
}

void LibcameraCamera::release(const Frame& frame) {
  Impl& impl = *m_impl;
  if (impl.held < 0 || frame.buffer_index != impl.held) {
    impl.last_error = "release() of a frame this camera did not hand out";
    ++impl.counters.errors;
    return;
  }
  libcamera::Request* request = impl.requests[static_cast<std::size_t>(impl.held)].get();
  impl.held = -1;
  if (impl.state == CameraState::kStreaming) impl.requeue(request);
}

bool LibcameraCamera::Impl::requeue(libcamera::Request* request) {
  request->reuse(libcamera::Request::ReuseBuffers);
  const int result = camera->queueRequest(request);
  if (result == 0) return true;
  if (result == -ENODEV) {
    lose("Camera::queueRequest", result);
    return false;
  }
  // Refused but not gone: keep the request and retry it in the next acquire() (never lose a buffer).
  const auto index = static_cast<std::size_t>(request->cookie());
  if (!parked[index]) {
    parked[index] = true;
    ++parked_count;
  }
  ++requeue_errors;
  ++counters.errors;
  setError("Camera::queueRequest", result);
  CameraEvent event;
  event.kind = CameraEventKind::kReleaseError;
  event.from = event.to = state;
  event.time_ns = nowNs();
  event.pending = static_cast<std::uint32_t>(parked_count);
  std::snprintf(event.text, sizeof(event.text), "%s; request %zu kept for a retry", last_error, index);
  events.push(event);
  return false;
}

bool LibcameraCamera::Impl::requeueParked() {
  for (std::size_t i = 0; i < requests.size(); ++i) {
    if (!parked[i]) continue;
    const int result = camera->queueRequest(requests[i].get());
    if (result == 0) {
      parked[i] = false;
      --parked_count;
    } else if (result == -ENODEV) {
      lose("Camera::queueRequest (retry)", result);
      return false;
    } else {
      ++requeue_errors;
      ++counters.errors;
      setError("Camera::queueRequest (retry)", result);
    }
  }
  if (parked_count == 0) {
    parked_rounds = 0;
    return true;
  }
  // Still refused round after round, or too few requests left with the camera: restart (as after a loss).
  ++parked_rounds;
  const int with_camera = static_cast<int>(requests.size()) - parked_count;
  if (with_camera >= 2 && parked_rounds < 3) return true;
  CameraEvent event;
  event.kind = CameraEventKind::kStreamRestart;
  event.from = event.to = state;
  event.time_ns = nowNs();
  event.pending = static_cast<std::uint32_t>(parked_count);
  std::snprintf(event.text, sizeof(event.text), "%s; %d requests refused: restarting the camera", last_error,
                parked_count);
  events.push(event);
  lose("queueRequest kept refusing requests: camera restarted");
  return false;
}

AcquireResult LibcameraCamera::Impl::lose(const char* what, int negative_errno) {
  setError(what, negative_errno);
  stopCamera();
  ++counters.device_losses;
  changeState(CameraState::kLost);
  return AcquireResult::kDeviceLost;
}

void LibcameraCamera::Impl::deliver(libcamera::Request* request, Frame& frame) {
  const libcamera::FrameBuffer* buffer = request->findBuffer(stream);
  const libcamera::FrameMetadata& metadata = buffer->metadata();
  const auto index = static_cast<std::size_t>(request->cookie());
  const std::uint8_t* plane = mappings[index].plane;
  const LibcameraFormatInfo& info = formatInfo(format);
  switch (info.source) {
    case LumaSource::kInPlace8:
    case LumaSource::kInPlace16:
      frame.image = viewInPlace(info.delivered, plane, params.width_px, params.height_px, stride_bytes);
      break;
    case LumaSource::kYuyv:
      frame.image = extractLumaYuyv(plane, params.width_px, params.height_px, stride_bytes, luma.data());
      break;
    case LumaSource::kPackedRgb:
      frame.image =
          extractLumaRgb(plane, params.width_px, params.height_px, stride_bytes,
                         PackedRgbLayout{info.bytes_per_pixel, info.red, info.green, info.blue}, luma.data());
      break;
  }
  // Start of exposure when the pipeline reports it, else the buffer's (V4L2, CLOCK_MONOTONIC) timestamp.
  const std::optional<std::int64_t> sensor_ns = request->metadata().get(libcamera::controls::SensorTimestamp);
  frame.exposure_time_ns = sensor_ns ? *sensor_ns : static_cast<std::int64_t>(metadata.timestamp);
  frame.sequence = sequence.next(metadata.sequence, counters.frames_dropped);
  frame.source_format = info.delivered;
  frame.buffer_index = static_cast<int>(index);
  held = static_cast<int>(index);
  ++counters.frames_delivered;
}

}  // namespace visnav::camera
