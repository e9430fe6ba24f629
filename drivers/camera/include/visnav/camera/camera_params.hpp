// Settings of the camera a run uses, shared by every driver (v4l2, libcamera, replay, synthetic): the
// [camera] table of a config. The generated reference is config/PARAMETERS.md. Each driver reads the fields
// that apply to it and ignores the others (the description says which).
#pragma once

#include <cstdint>
#include <string>

#include "visnav/core/param_visitor.hpp"

namespace visnav::camera {

enum class CameraDriver : int { kV4l2 = 0, kLibcamera = 1, kReplay = 2, kSynthetic = 3 };
/// Requested sensor format; the order matches the names list in visit() and visnav::PixelFormat.
enum class RequestedFormat : int { kGrey = 0, kY10 = 1, kY12 = 2, kY16 = 3, kYuyv = 4 };
enum class LibcameraRole : int { kViewfinder = 0, kRaw = 1, kStillCapture = 2 };

struct CameraParams {
  int driver = static_cast<int>(CameraDriver::kSynthetic);
  std::string device;  ///< v4l2: device node; libcamera: camera id; replay: sequence directory
  int width_px = 640;
  int height_px = 480;
  int pixel_format = static_cast<int>(RequestedFormat::kGrey);
  double fps_hz = 5.0;
  int buffer_count = 4;
  double acquire_timeout_ms = 100.0;
  int recovery_attempts = 25;
  int libcamera_role = static_cast<int>(LibcameraRole::kViewfinder);

  CameraDriver driverKind() const { return static_cast<CameraDriver>(driver); }
  RequestedFormat format() const { return static_cast<RequestedFormat>(pixel_format); }
  std::int64_t acquireTimeoutNs() const { return static_cast<std::int64_t>(acquire_timeout_ms * 1e6); }

  template <typename Visitor>
  void visit(Visitor& v) {
    v.enumeration({"camera", "driver", "-", 0, 3,
                   "frame source: a V4L2 device, a libcamera camera, a recorded sequence, or the built-in "
                   "renderer"},
                  "v4l2|libcamera|replay|synthetic", driver);
    v.text({"camera", "device", "-", 0, 4095,
            "v4l2: device node (/dev/video0); libcamera: camera id (empty: the first camera); replay: "
            "sequence directory; synthetic: unused"},
           device);
    v.integer({"camera", "width_px", "px", 16, 8192, "image width requested from the sensor"}, width_px);
    v.integer({"camera", "height_px", "px", 16, 8192, "image height requested from the sensor"}, height_px);
    v.enumeration({"camera", "pixel_format", "-", 0, 4,
                   "sensor format (v4l2, libcamera): grey 8-bit and y10/y12/y16 (16-bit words) are read "
                   "in place; yuyv is reduced to its Y plane; libcamera has no y16"},
                  "grey|y10|y12|y16|yuyv", pixel_format);
    v.real({"camera", "fps_hz", "Hz", 0.1, 240.0,
            "frame rate asked of the sensor (v4l2 frame interval, libcamera frame duration); replay and "
            "synthetic: see their README"},
           fps_hz);
    v.integer({"camera", "buffer_count", "count", 2, 32,
               "frame buffers in the driver ring, allocated at open (v4l2, libcamera)"},
              buffer_count);
    v.real({"camera", "acquire_timeout_ms", "ms", 0.0, 10000.0,
            "longest wait for a frame in one cycle; a late camera is counted, never allowed to block the "
            "cycle"},
           acquire_timeout_ms);
    v.integer({"camera", "recovery_attempts", "count", 0, 100000,
               "quick reopen attempts (one per recover() call) after the device is lost; then retries "
               "back off to one every 2 s at most, for as long as the device is away"},
              recovery_attempts);
    v.enumeration(
        {"camera", "libcamera_role", "-", 0, 2,
         "libcamera stream role: viewfinder (processed, YUYV/R8), raw (sensor data), still_capture"},
        "viewfinder|raw|still_capture", libcamera_role);
  }

  /// Cross-field checks the per-field ranges cannot express. Returns nullptr when valid.
  const char* crossCheck() const {
    if (driverKind() == CameraDriver::kV4l2 && device.empty())
      return "[camera] device must name the V4L2 node (e.g. /dev/video0) when driver = \"v4l2\"";
    if (driverKind() == CameraDriver::kReplay && device.empty())
      return "[camera] device must name the sequence directory when driver = \"replay\"";
    if (driverKind() == CameraDriver::kLibcamera && format() == RequestedFormat::kY16)
      return "[camera] pixel_format y16 has no libcamera 0.0.3 equivalent (use grey, y10, y12 or yuyv)";
    return nullptr;
  }
};

}  // namespace visnav::camera
