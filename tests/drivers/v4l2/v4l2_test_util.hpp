// Shared set-up of the V4L2 driver tests: a small camera on the FAKE device.
#pragma once

#include <gtest/gtest.h>

#include "fake_v4l2_device.hpp"
#include "visnav/v4l2/v4l2_camera.hpp"

namespace visnav::test {

inline camera::CameraParams fakeCameraParams(
    camera::RequestedFormat format = camera::RequestedFormat::kGrey) {
  camera::CameraParams params;
  params.driver = static_cast<int>(camera::CameraDriver::kV4l2);
  params.device = "/dev/fake-video0";
  params.width_px = 64;
  params.height_px = 48;
  params.pixel_format = static_cast<int>(format);
  params.fps_hz = 5.0;
  params.buffer_count = 4;
  params.recovery_attempts = 5;
  return params;
}

/// Lets the fake finish one frame, then acquires it (10 ms timeout) and expects success.
inline void produceAndAcquire(FakeV4l2Device& device, camera::V4l2Camera& camera, Frame& frame) {
  ASSERT_TRUE(device.produceFrame());
  ASSERT_EQ(camera.acquire(10000000, frame), camera::AcquireResult::kFrame) << camera.lastError();
}

}  // namespace visnav::test
