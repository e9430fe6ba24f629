// V4L2 driver against the FAKE device: the device vanishing mid-stream and coming back, bounded recovery,
// and the zero-allocation guarantee of acquire()/release()/recover() after open().
#include <gtest/gtest.h>

#include <cstring>

#include "../../support/alloc_counter.hpp"
#include "v4l2_test_util.hpp"

namespace visnav::test {
namespace {

using camera::AcquireResult;
using camera::V4l2Camera;

class V4l2Recovery : public ::testing::Test {
 protected:
  V4l2Recovery() : device(FakeV4l2Device::Config{}), camera(fakeCameraParams(), device) {}
  void SetUp() override { ASSERT_TRUE(camera.open().ok); }
  std::uint64_t cycle() {
    Frame frame;
    produceAndAcquire(device, camera, frame);
    camera.release(frame);
    return frame.sequence;
  }
  FakeV4l2Device device;
  V4l2Camera camera;
};

TEST_F(V4l2Recovery, UnplugMidStreamIsDeviceLostAndTheRingIsTornDown) {
  EXPECT_EQ(cycle(), 0U);
  device.unplug();
  Frame frame;
  EXPECT_EQ(camera.acquire(10000000, frame), AcquireResult::kDeviceLost);
  EXPECT_EQ(camera.counters().device_losses, 1U);
  EXPECT_EQ(camera.counters().errors, 0U);
  EXPECT_EQ(camera.lastErrno(), ENODEV);
  EXPECT_EQ(device.mappedBuffers(), 0);
  EXPECT_EQ(device.openFds(), 0);
  // While lost, acquire() answers at once without touching the OS.
  const int polls = device.pollCalls();
  const int ioctls = device.ioctlCalls();
  EXPECT_EQ(camera.acquire(10000000, frame), AcquireResult::kDeviceLost);
  EXPECT_EQ(device.pollCalls(), polls);
  EXPECT_EQ(device.ioctlCalls(), ioctls);
}

TEST_F(V4l2Recovery, RecoverReopensTheSameNodeWithTheSameFormatAndRing) {
  EXPECT_EQ(cycle(), 0U);
  EXPECT_EQ(cycle(), 1U);
  device.unplug();
  Frame frame;
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
  EXPECT_FALSE(camera.recover());  // still gone
  EXPECT_NE(std::strstr(camera.lastError(), "cannot open the device node"), nullptr) << camera.lastError();
  EXPECT_NE(std::strstr(camera.lastError(), ": ENOENT (No such file or directory)"), nullptr)
      << camera.lastError();
  device.replug();  // the driver's sequence restarts at 0
  ASSERT_TRUE(camera.recover()) << camera.lastError();
  EXPECT_EQ(camera.counters().recoveries, 1U);
  EXPECT_EQ(device.grantedBuffers(), 4U);
  EXPECT_EQ(device.mappedBuffers(), 4);
  EXPECT_EQ(device.format().pixelformat, static_cast<std::uint32_t>(V4L2_PIX_FMT_GREY));
  EXPECT_EQ(device.format().width, 64U);
  EXPECT_EQ(device.frameInterval().denominator, 5U);
  EXPECT_EQ(cycle(), 2U);  // frame.sequence keeps increasing across the restart
  device.skipFrames(1);
  EXPECT_EQ(cycle(), 4U);  // gaps after the restart count again
  EXPECT_EQ(camera.counters().frames_dropped, 1U);
}

TEST_F(V4l2Recovery, ALossSeenWhenReleasingIsReportedByTheNextAcquire) {
  Frame frame;
  produceAndAcquire(device, camera, frame);
  device.unplug();
  camera.release(frame);  // VIDIOC_QBUF -> ENODEV
  EXPECT_EQ(camera.counters().device_losses, 1U);
  EXPECT_EQ(device.mappedBuffers(), 0);
  EXPECT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
}

TEST_F(V4l2Recovery, RecoveryNeverGivesUpAndComesBackAfterALongLoss) {
  device.setNowNs(1'000'000'000);
  device.unplug();
  Frame frame;
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
  // 60 s away at one recover() call per 200 ms cycle: far past the 5 quick attempts.
  for (int i = 0; i < 300; ++i) {
    EXPECT_FALSE(camera.recover());
    device.advanceNs(200'000'000);
  }
  EXPECT_EQ(camera.state(), camera::CameraState::kRetrying);
  device.replug();
  int calls = 0;
  while (!camera.recover() && calls < 100) {
    device.advanceNs(200'000'000);
    ++calls;
  }
  EXPECT_LE(calls, 10);  // back within the 2 s cap
  EXPECT_EQ(camera.state(), camera::CameraState::kStreaming);
  EXPECT_EQ(camera.counters().recoveries, 1U);
  EXPECT_EQ(cycle(), 0U);  // the first frame ever delivered
}

TEST_F(V4l2Recovery, ADeviceBackWithAnotherFormatIsNotAccepted) {
  device.unplug();
  Frame frame;
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
  device.replug();
  device.offerOnly(V4L2_PIX_FMT_YUYV);
  EXPECT_FALSE(camera.recover());
  EXPECT_NE(std::strstr(camera.lastError(), "different format"), nullptr) << camera.lastError();
  EXPECT_EQ(device.openFds(), 0);
  EXPECT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
}

TEST(V4l2NoAlloc, AcquireReleaseAndRecoverAllocateNothingAfterOpen) {
  for (const auto format :
       {camera::RequestedFormat::kGrey, camera::RequestedFormat::kY10, camera::RequestedFormat::kYuyv}) {
    FakeV4l2Device device(FakeV4l2Device::Config{});
    V4l2Camera camera(fakeCameraParams(format), device);
    ASSERT_TRUE(camera.open().ok);
    int delivered = 0;
    const std::uint64_t before = allocationCount();
    for (int i = 0; i < 600; ++i) {
      if (i % 50 == 7) device.skipFrames(2);
      if (i % 40 == 3) device.produceFrame();  // a stale frame to skip
      if (i % 90 == 11) device.corruptNextFrame();
      if (i % 200 == 100) device.unplug();
      if (i % 200 == 102) device.replug();
      if (i % 70 == 13) device.failQbuf(1);     // a refused buffer, parked and requeued
      if (i % 30 != 29) device.produceFrame();  // else: a timeout
      Frame frame;
      const AcquireResult result = camera.acquire(0, frame);
      if (result == AcquireResult::kFrame) {
        ++delivered;
        camera.release(frame);
      } else if (result == AcquireResult::kDeviceLost) {
        camera.recover();
      }
      camera::CameraEvent event;
      char line[256];
      while (camera.nextEvent(event)) camera::formatEvent(event, line, sizeof(line));
    }
    const std::uint64_t after = allocationCount();
    EXPECT_EQ(after - before, 0U) << "malloc counted: " << countsMalloc();
    // The loop really exercised every path.
    EXPECT_GT(delivered, 450);
    EXPECT_GT(camera.counters().frames_dropped, 20U);
    EXPECT_GT(camera.counters().timeouts, 10U);
    EXPECT_EQ(camera.counters().device_losses, 3U);
    EXPECT_EQ(camera.counters().recoveries, 3U);
    EXPECT_GT(camera.corruptFrames(), 3U);
    EXPECT_GT(camera.requeueErrors(), 5U);
  }
}

TEST(V4l2NoAlloc, TheCounterSeesAllocations) {
  const std::uint64_t before = allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav::test
