#include "visnav/camera/camera_source.hpp"

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

}  // namespace visnav::camera
