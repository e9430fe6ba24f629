// LibcameraCamera streaming: the completion hand-over from libcamera's thread, acquire() and release().
// Nothing here allocates (fixed queue, requests reused); what libcamera does inside reuse()/queueRequest() is
// its own (drivers/README.md).
#include <libcamera/control_ids.h>
#include <libcamera/framebuffer.h>

#include <cerrno>
#include <chrono>

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
  if (impl.state == Impl::State::kLost) return AcquireResult::kDeviceLost;
  if (impl.state != Impl::State::kStreaming || impl.held >= 0) {
    impl.last_error =
        impl.held >= 0 ? "acquire() before the previous frame was released" : "acquire() on a closed camera";
    ++impl.counters.errors;
    return AcquireResult::kError;
  }
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
  if (impl.disconnected) return impl.lose("the camera was disconnected");
  for (int i = 0; i < older_count; ++i) {
    ++impl.stale_skipped;
    if (!impl.requeue(older[static_cast<std::size_t>(i)]))
      return impl.state == Impl::State::kLost ? AcquireResult::kDeviceLost : AcquireResult::kError;
  }
  const libcamera::FrameBuffer* buffer = newest->findBuffer(impl.stream);
  if (newest->status() != libcamera::Request::RequestComplete || buffer == nullptr ||
      buffer->metadata().status != libcamera::FrameMetadata::FrameSuccess) {
    impl.last_error = "libcamera completed a request without a good frame (cancelled or FrameError)";
    ++impl.counters.errors;
    if (!impl.requeue(newest) && impl.state == Impl::State::kLost) return AcquireResult::kDeviceLost;
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
  if (impl.state == Impl::State::kStreaming) impl.requeue(request);
}

bool LibcameraCamera::Impl::requeue(libcamera::Request* request) {
  request->reuse(libcamera::Request::ReuseBuffers);
  const int result = camera->queueRequest(request);
  if (result == 0) return true;
  if (result == -ENODEV) {
    lose("Camera::queueRequest: the camera is gone");
  } else {
    last_error = "Camera::queueRequest failed";
    ++counters.errors;
  }
  return false;
}

AcquireResult LibcameraCamera::Impl::lose(const char* what) {
  last_error = what;
  stopCamera();
  state = State::kLost;
  ++counters.device_losses;
  return AcquireResult::kDeviceLost;
}

void LibcameraCamera::Impl::deliver(libcamera::Request* request, Frame& frame) {
  const libcamera::FrameBuffer* buffer = request->findBuffer(stream);
  const libcamera::FrameMetadata& metadata = buffer->metadata();
  const auto index = static_cast<std::size_t>(request->cookie());
  const std::uint8_t* plane = mappings[index].plane;
  frame.image = isZeroCopy(format)
                    ? viewInPlace(format, plane, params.width_px, params.height_px, stride_bytes)
                    : extractLumaYuyv(plane, params.width_px, params.height_px, stride_bytes, luma.data());
  // Start of exposure when the pipeline reports it, else the buffer's (V4L2, CLOCK_MONOTONIC) timestamp.
  const std::optional<std::int64_t> sensor_ns = request->metadata().get(libcamera::controls::SensorTimestamp);
  frame.exposure_time_ns = sensor_ns ? *sensor_ns : static_cast<std::int64_t>(metadata.timestamp);
  frame.sequence = sequence.next(metadata.sequence, counters.frames_dropped);
  frame.source_format = format;
  frame.buffer_index = static_cast<int>(index);
  held = static_cast<int>(index);
  ++counters.frames_delivered;
}

}  // namespace visnav::camera
