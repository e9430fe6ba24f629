// V4L2 driver against the FAKE device: sequence numbers, dropped frames, newest-frame delivery, timestamps,
// bounded waits, corrupt frames and contract misuse.
#include <gtest/gtest.h>

#include <ctime>

#include "v4l2_test_util.hpp"

namespace visnav::test {
namespace {

using camera::AcquireResult;
using camera::V4l2Camera;

std::int64_t nowNs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1000000000LL + t.tv_nsec;
}

class V4l2Streaming : public ::testing::Test {
 protected:
  explicit V4l2Streaming(FakeV4l2Device::Config config = {})
      : device(config), camera(fakeCameraParams(), device) {}
  void SetUp() override { ASSERT_TRUE(camera.open().ok); }
  /// Produces and consumes one frame; returns its sequence.
  std::uint64_t cycle() {
    Frame frame;
    produceAndAcquire(device, camera, frame);
    camera.release(frame);
    return frame.sequence;
  }
  FakeV4l2Device device;
  V4l2Camera camera;
};

TEST_F(V4l2Streaming, SequenceGapsAreCountedAsDroppedFrames) {
  EXPECT_EQ(cycle(), 0U);
  EXPECT_EQ(cycle(), 1U);
  device.skipFrames(2);  // the sensor made frames 2 and 3, nobody got them
  EXPECT_EQ(cycle(), 4U);
  device.skipFrames(5);
  EXPECT_EQ(cycle(), 10U);
  EXPECT_EQ(camera.counters().frames_dropped, 7U);
  EXPECT_EQ(camera.counters().frames_delivered, 4U);
  EXPECT_EQ(camera.staleFramesSkipped(), 0U);
}

TEST_F(V4l2Streaming, TheThirtyTwoBitDriverSequenceWrapsIntoSixtyFourBits) {
  device.setNextSequence(0xFFFFFFFEU);
  EXPECT_EQ(cycle(), 0xFFFFFFFEULL);
  EXPECT_EQ(cycle(), 0xFFFFFFFFULL);
  EXPECT_EQ(cycle(), 0x100000000ULL);
  device.skipFrames(1);
  EXPECT_EQ(cycle(), 0x100000002ULL);
  EXPECT_EQ(camera.counters().frames_dropped, 1U);
}

TEST_F(V4l2Streaming, TheNewestReadyFrameIsDeliveredAndOlderOnesRequeued) {
  EXPECT_EQ(cycle(), 0U);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(device.produceFrame());  // the cycle was late: 1, 2, 3 are ready
  Frame frame;
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kFrame);
  EXPECT_EQ(frame.sequence, 3U);
  EXPECT_EQ(camera.staleFramesSkipped(), 2U);
  EXPECT_EQ(camera.counters().frames_dropped, 2U);
  EXPECT_EQ(device.queuedBuffers(), 3);  // 4 buffers, one held by the caller
  int mismatches = 0;
  for (int x = 0; x < 64; ++x)
    mismatches += frame.image.u8.at(x, 5) != FakeV4l2Device::pattern(V4L2_PIX_FMT_GREY, 3, x, 5);
  EXPECT_EQ(mismatches, 0);
  camera.release(frame);
  EXPECT_EQ(device.queuedBuffers(), 4);
}

TEST_F(V4l2Streaming, FramesLostInTheKernelForWantOfBuffersShowAsGaps) {
  Frame held;
  produceAndAcquire(device, camera, held);                         // frame 0 held by the "pipeline"
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(device.produceFrame());  // 1, 2, 3 fill the other 3 buffers
  EXPECT_FALSE(device.produceFrame());                             // 4: no buffer queued, lost in the kernel
  EXPECT_FALSE(device.produceFrame());                             // 5: lost too
  camera.release(held);
  EXPECT_EQ(cycle(), 6U);  // 1, 2, 3 skipped as stale, 6 landed in the released buffer
  EXPECT_EQ(camera.counters().frames_dropped, 5U);
}

TEST_F(V4l2Streaming, MonotonicDriverTimestampsAreKept) {
  device.skipFrames(4);
  Frame frame;
  produceAndAcquire(device, camera, frame);
  // Fake: first timestamp 1 s, frame interval 1/5 s (set from fps_hz), frame 4.
  EXPECT_EQ(frame.exposure_time_ns, 1000000000LL + 4 * 200000000LL);
  EXPECT_EQ(camera.timestampFallbacks(), 0U);
  camera.release(frame);
}

class V4l2UnknownClock : public V4l2Streaming {
 protected:
  static FakeV4l2Device::Config config() {
    FakeV4l2Device::Config c;
    c.timestamp_flags = V4L2_BUF_FLAG_TIMESTAMP_COPY;
    return c;
  }
  V4l2UnknownClock() : V4l2Streaming(config()) {}
};

TEST_F(V4l2UnknownClock, ANonMonotonicTimestampIsReplacedByTheDequeueTime) {
  const std::int64_t before = nowNs();
  Frame frame;
  produceAndAcquire(device, camera, frame);
  const std::int64_t after = nowNs();
  EXPECT_GE(frame.exposure_time_ns, before);
  EXPECT_LE(frame.exposure_time_ns, after);
  EXPECT_EQ(camera.timestampFallbacks(), 1U);
  camera.release(frame);
}

TEST_F(V4l2Streaming, NoFrameMeansATimeoutAfterOneBoundedPoll) {
  Frame frame;
  EXPECT_EQ(camera.acquire(25000000, frame), AcquireResult::kTimeout);
  EXPECT_EQ(device.pollCalls(), 1);
  EXPECT_GE(device.lastPollTimeoutMs(), 24);  // the remaining time, rounded up
  EXPECT_LE(device.lastPollTimeoutMs(), 25);
  EXPECT_EQ(camera.counters().timeouts, 1U);
  EXPECT_EQ(camera.acquire(0, frame), AcquireResult::kTimeout);
  EXPECT_EQ(device.lastPollTimeoutMs(), 0);
  EXPECT_EQ(camera.counters().timeouts, 2U);
  EXPECT_EQ(camera.counters().errors, 0U);
}

TEST_F(V4l2Streaming, AnInterruptedPollIsRetried) {
  device.failNextPollWithEintr();
  Frame frame;
  produceAndAcquire(device, camera, frame);
  EXPECT_EQ(device.pollCalls(), 2);
  camera.release(frame);
}

TEST_F(V4l2Streaming, CorruptAndShortFramesAreDroppedAndCounted) {
  EXPECT_EQ(cycle(), 0U);
  device.corruptNextFrame();
  ASSERT_TRUE(device.produceFrame());
  Frame frame;
  EXPECT_EQ(camera.acquire(0, frame), AcquireResult::kError);
  EXPECT_EQ(camera.corruptFrames(), 1U);
  EXPECT_EQ(device.queuedBuffers(), 4);  // handed straight back to the driver
  device.shortNextFrame();
  ASSERT_TRUE(device.produceFrame());
  ASSERT_TRUE(device.produceFrame());  // a good one behind the short one
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kFrame);
  EXPECT_EQ(frame.sequence, 3U);
  EXPECT_EQ(camera.corruptFrames(), 2U);
  EXPECT_EQ(camera.counters().frames_dropped, 2U);
  EXPECT_EQ(camera.counters().errors, 1U);
  camera.release(frame);
}

TEST_F(V4l2Streaming, ContractMisuseIsAnErrorNotACrash) {
  Frame frame;
  produceAndAcquire(device, camera, frame);
  Frame second;
  EXPECT_EQ(camera.acquire(0, second), AcquireResult::kError);  // previous frame not released
  Frame foreign = frame;
  foreign.buffer_index = (frame.buffer_index + 1) % 4;
  camera.release(foreign);
  EXPECT_EQ(camera.counters().errors, 2U);
  camera.release(frame);
  EXPECT_EQ(cycle(), 1U);
  camera.close();
  EXPECT_EQ(camera.acquire(0, frame), AcquireResult::kError);
}

}  // namespace
}  // namespace visnav::test
