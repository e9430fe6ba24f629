// Live camera through libcamera (Debian 12's 0.0.3 API), the same contract as the V4L2 driver. open() starts
// a CameraManager, selects the camera by id, configures one stream (role from config, size, a mono or YUYV
// format with a stated fallback), allocates the frame buffers, maps their dmabuf planes and creates one
// request per buffer. libcamera completes requests on its own thread; they pass through a fixed-capacity
// mutex + condition-variable queue to acquire(), which waits at most its timeout and hands out the newest
// frame (R8, R10, R12 and the Y plane of NV12/NV21/YUV420/YVU420/NV16 viewed in place; YUYV's Y and the luma
// of RGB888/BGR888/XRGB8888/XBGR8888 written into storage sized at open()). release() reuses the request with
// its buffer and queues it again. Our code allocates nothing per frame; libcamera itself may (see
// drivers/README.md). Only one instance may be open per process (libcamera allows one CameraManager).
#pragma once

#include <memory>
#include <string>

#include "visnav/camera/camera_params.hpp"
#include "visnav/camera/camera_source.hpp"

namespace visnav::camera {

class LibcameraCamera final : public CameraSource {
 public:
  explicit LibcameraCamera(const CameraParams& params);
  ~LibcameraCamera() override;
  LibcameraCamera(const LibcameraCamera&) = delete;
  LibcameraCamera& operator=(const LibcameraCamera&) = delete;

  LoadError open() override;
  AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) override;
  void release(const Frame& frame) override;
  /// Looks the camera up again by id and redoes the camera part of open() when an attempt is due (quick
  /// attempts, then RetryBackoff's spacing up to 2 s, never giving up). Unlike V4L2 this allocates: libcamera
  /// rebuilds its objects.
  bool recover() override;
  void close() override;
  const CameraCounters& counters() const override;
  const char* lastError() const override;
  const char* name() const override { return "libcamera"; }
  CameraState state() const override;
  bool nextEvent(CameraEvent& event) override;

  /// After open(): what was configured, e.g. "camera '/base/...' viewfinder R8 640x480 stride 640, 4
  /// buffers"; plus a note when the requested format had to be replaced.
  const std::string& description() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> m_impl;
};

}  // namespace visnav::camera
