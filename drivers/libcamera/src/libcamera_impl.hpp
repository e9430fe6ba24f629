// State of LibcameraCamera (private to the library: the only place libcamera's headers are included).
#pragma once

#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>
#include <libcamera/framebuffer_allocator.h>
#include <libcamera/request.h>
#include <libcamera/stream.h>

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "visnav/camera/camera_events.hpp"
#include "visnav/camera/sequence_tracker.hpp"
#include "visnav/libcamera/libcamera_camera.hpp"
#include "visnav/libcamera/libcamera_formats.hpp"

namespace visnav::camera {

struct LibcameraCamera::Impl {
  static constexpr int kMaxRequests = 32;

  explicit Impl(const CameraParams& camera_params) : params(camera_params) {}

  // Set-up (libcamera_camera.cpp). Each returns an empty string or the reason it failed.
  std::string startManager();
  std::string selectCamera();
  std::string configureStream(bool first_open);
  std::string allocateAndMap();
  std::string createRequests();
  std::string start();
  void stopCamera();  // everything camera-side, keeps the manager

  // Streaming (libcamera_stream.cpp).
  void onRequestCompleted(libcamera::Request* request);
  void onDisconnected();
  bool requeue(libcamera::Request* request);
  /// Retries the requests a queueRequest() refused; false when the camera is lost (or restarted).
  bool requeueParked();
  AcquireResult lose(const char* what, int negative_errno = 0);
  void deliver(libcamera::Request* request, Frame& frame);
  void setError(const char* what, int negative_errno);
  void changeState(CameraState to);
  static std::int64_t nowNs();

  CameraParams params;
  CameraState state = CameraState::kClosed;
  std::unique_ptr<libcamera::CameraManager> manager;
  std::shared_ptr<libcamera::Camera> camera;
  bool camera_acquired = false;
  bool camera_started = false;
  std::unique_ptr<libcamera::CameraConfiguration> configuration;
  libcamera::Stream* stream = nullptr;
  std::unique_ptr<libcamera::FrameBufferAllocator> allocator;
  std::vector<std::unique_ptr<libcamera::Request>> requests;  // cookie = index, created once
  struct Mapping {
    void* address = nullptr;
    std::size_t length = 0;
    const std::uint8_t* plane = nullptr;  // first plane inside the mapping
  };
  std::vector<Mapping> mappings;  // per request
  LibcameraFormat format = LibcameraFormat::kR8;
  std::size_t stride_bytes = 0;
  std::vector<std::uint8_t> luma;  // YUYV and RGB only: the converted luma, sized at open()
  std::string camera_id;
  std::string description;

  // Completed requests, filled on libcamera's thread. Capacity = number of requests: cannot overflow.
  std::mutex mutex;
  std::condition_variable completed_ready;
  std::array<libcamera::Request*, kMaxRequests> completed{};
  int completed_head = 0;
  int completed_count = 0;
  std::atomic<bool> disconnected{false};

  int held = -1;  // cookie of the request whose frame the caller holds
  SequenceTracker sequence;
  RetryBackoff backoff;
  CameraEventQueue events;
  std::array<bool, kMaxRequests> parked{};  // refused by queueRequest(), retried by the next acquire()
  int parked_count = 0;
  int parked_rounds = 0;
  CameraCounters counters;
  std::uint64_t stale_skipped = 0;
  std::uint64_t requeue_errors = 0;
  const char* last_error = "";
  char error_text[CameraEvent::kTextCapacity] = {};
};

}  // namespace visnav::camera
