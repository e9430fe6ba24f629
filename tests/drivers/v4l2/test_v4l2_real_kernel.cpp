// V4L2 driver through the REAL seam against this machine's kernel (no camera here: /dev/video* is absent).
// What the kernel can say without a camera: a missing node, and a node that is not V4L2. With a camera, or
// vivid in the VM of the kernel-driver issue, set VISNAV_V4L2_DEVICE=/dev/videoN to stream a few frames.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "visnav/v4l2/v4l2_camera.hpp"

namespace visnav::camera {
namespace {

CameraParams realParams(const std::string& device) {
  CameraParams params;
  params.driver = static_cast<int>(CameraDriver::kV4l2);
  params.device = device;
  return params;
}

TEST(V4l2RealKernel, AMissingNodeGivesAClearError) {
  V4l2Camera camera(realParams("/dev/visnav-no-such-video0"));
  const LoadError error = camera.open();
  ASSERT_FALSE(error.ok);
  EXPECT_NE(error.message.find("v4l2 /dev/visnav-no-such-video0: cannot open the device node"),
            std::string::npos)
      << error.message;
  EXPECT_NE(error.message.find(": ENOENT (No such file or directory)"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("v4l2-ctl --list-devices"), std::string::npos) << error.message;
}

TEST(V4l2RealKernel, ANodeThatIsNotV4l2IsNamedSo) {
  V4l2Camera camera(realParams("/dev/null"));
  const LoadError error = camera.open();
  ASSERT_FALSE(error.ok);
  EXPECT_NE(error.message.find("not a V4L2 device"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find(": ENOTTY (Inappropriate ioctl for device)"), std::string::npos)
      << error.message;  // ENOTTY
}

TEST(V4l2RealKernel, StreamsFromADeviceWhenOneIsGiven) {
  const char* device = std::getenv("VISNAV_V4L2_DEVICE");
  if (device == nullptr) GTEST_SKIP() << "no camera here; set VISNAV_V4L2_DEVICE=/dev/videoN to run";
  V4l2Camera camera(realParams(device));
  const LoadError error = camera.open();
  ASSERT_TRUE(error.ok) << error.message;
  std::uint64_t last_sequence = 0;
  std::int64_t last_time_ns = 0;
  for (int i = 0; i < 5; ++i) {
    Frame frame;
    ASSERT_EQ(camera.acquire(2000000000, frame), AcquireResult::kFrame) << camera.lastError();
    EXPECT_EQ(frame.image.width(), 640);
    if (i > 0) {
      EXPECT_GT(frame.sequence, last_sequence);
      EXPECT_GT(frame.exposure_time_ns, last_time_ns);
    }
    last_sequence = frame.sequence;
    last_time_ns = frame.exposure_time_ns;
    camera.release(frame);
  }
}

}  // namespace
}  // namespace visnav::camera
