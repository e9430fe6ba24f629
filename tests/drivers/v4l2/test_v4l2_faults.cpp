// V4L2 driver against the FAKE device: the faults vivid can inject (issue 13), as the fake imitates them. A
// refused VIDIOC_QBUF keeps its buffer for a retry; a ring that stays short restarts the stream; a loss is
// retried on a back-off capped at 2 s for as long as it lasts; every state change and refused buffer is an
// event; every errno is named. The real vivid runs the same faults in scripts/test-kernel-cameras.sh.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "v4l2_test_util.hpp"
#include "visnav/camera/os_error.hpp"

namespace visnav::test {
namespace {

using camera::AcquireResult;
using camera::CameraEvent;
using camera::CameraEventKind;
using camera::CameraState;
using camera::V4l2Camera;

constexpr std::int64_t kCycleNs = 200'000'000;

class V4l2Faults : public ::testing::Test {
 protected:
  V4l2Faults() : device(FakeV4l2Device::Config{}), camera(fakeCameraParams(), device) {}
  void SetUp() override {
    device.setNowNs(5'000'000'000);
    ASSERT_TRUE(camera.open().ok);
  }
  /// One daemon-like cycle: a frame is produced, acquired, released; a lost camera gets one recover().
  AcquireResult cycle() {
    device.produceFrame();
    Frame frame;
    const AcquireResult result = camera.acquire(0, frame);
    if (result == AcquireResult::kFrame) camera.release(frame);
    if (result == AcquireResult::kDeviceLost) camera.recover();
    device.advanceNs(kCycleNs);
    return result;
  }
  std::vector<CameraEvent> drain() {
    std::vector<CameraEvent> events;
    CameraEvent event;
    while (camera.nextEvent(event)) events.push_back(event);
    return events;
  }
  FakeV4l2Device device;
  V4l2Camera camera;
};

TEST_F(V4l2Faults, ARefusedQbufKeepsTheBufferAndTheNextAcquireRequeuesIt) {
  Frame frame;
  produceAndAcquire(device, camera, frame);
  device.failQbuf(1);  // vivid inject_vidioc_qbuf_error: the next QBUF gives EINVAL
  camera.release(frame);
  EXPECT_EQ(camera.pendingRequeues(), 1);
  EXPECT_EQ(device.queuedBuffers(), 3);
  EXPECT_EQ(camera.counters().errors, 1U);
  EXPECT_STREQ(camera.lastError(), "VIDIOC_QBUF (release): EINVAL (Invalid argument)");
  const std::vector<CameraEvent> events = drain();
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].kind, CameraEventKind::kReleaseError);
  EXPECT_EQ(events[0].pending, 1U);
  EXPECT_NE(std::strstr(events[0].text, "buffer 0 kept for a retry"), nullptr) << events[0].text;
  EXPECT_EQ(cycle(), AcquireResult::kFrame);  // the retry succeeds and the stream goes on
  EXPECT_EQ(camera.pendingRequeues(), 0);
  EXPECT_EQ(device.queuedBuffers(), 4);
  EXPECT_EQ(camera.counters().device_losses, 0U);
}

TEST_F(V4l2Faults, ARefusedRetryIsReportedLikeTheFirstRefusal) {
  // vivid's injection is consumed by whichever QBUF comes next, a parked buffer's retry included: a monitor
  // counting release-error events must see that refusal too (the kernel-camera test waits on it).
  Frame frame;
  produceAndAcquire(device, camera, frame);
  device.failQbuf(1);
  camera.release(frame);
  ASSERT_EQ(drain().size(), 1U);
  device.failQbuf(1);  // the retry in the next acquire() is refused
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  const std::vector<CameraEvent> events = drain();
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].kind, CameraEventKind::kReleaseError);
  EXPECT_NE(std::strstr(events[0].text, "VIDIOC_QBUF (retry): EINVAL"), nullptr) << events[0].text;
  EXPECT_NE(std::strstr(events[0].text, "buffer 0 kept for a retry"), nullptr) << events[0].text;
  EXPECT_EQ(camera.counters().errors, 2U);
  EXPECT_EQ(camera.requeueErrors(), 2U);
  EXPECT_EQ(cycle(), AcquireResult::kFrame);  // the second retry goes through
  EXPECT_EQ(camera.pendingRequeues(), 0);
}

TEST_F(V4l2Faults, FourRefusedQbufsInARowNoLongerEmptyTheRing) {
  // The run: 4 injected errors emptied a 4-buffer ring for good. Now each is retried.
  for (int i = 0; i < 4; ++i) {
    device.failQbuf(1);
    EXPECT_EQ(cycle(), AcquireResult::kFrame) << i << ": " << camera.lastError();
  }
  for (int i = 0; i < 20; ++i) EXPECT_EQ(cycle(), AcquireResult::kFrame) << camera.lastError();
  EXPECT_EQ(camera.requeueErrors(), 4U);
  EXPECT_EQ(camera.streamRestarts(), 0U);
  EXPECT_EQ(camera.counters().frames_delivered, 24U);
  EXPECT_EQ(device.queuedBuffers(), 4);
}

TEST_F(V4l2Faults, ABufferRefusedOverAndOverRestartsTheStreamWhenTheRingRunsLow) {
  device.failQbuf(1000);  // the driver refuses every QBUF
  AcquireResult result = AcquireResult::kFrame;
  int cycles = 0;
  while (result != AcquireResult::kDeviceLost && cycles < 10) {
    result = cycle();
    ++cycles;
  }
  ASSERT_EQ(result, AcquireResult::kDeviceLost);
  EXPECT_EQ(cycles, 4);  // 4 buffers: 3 frames parked one by one, then only 1 left with the driver
  EXPECT_EQ(camera.streamRestarts(), 1U);
  bool lost = false;
  std::string restart;
  for (const CameraEvent& event : drain()) {
    if (event.kind == CameraEventKind::kStreamRestart) restart = event.text;
    lost = lost || (event.kind == CameraEventKind::kStateChange && event.to == CameraState::kLost);
  }
  EXPECT_NE(restart.find("EINVAL (Invalid argument); 3 of 4 buffers refused"), std::string::npos) << restart;
  EXPECT_NE(restart.find("restarting the stream"), std::string::npos) << restart;
  EXPECT_TRUE(lost);
  device.failQbuf(0);  // the driver recovers; the restart gets a fresh ring
  for (int i = 0; i < 5; ++i) cycle();
  EXPECT_EQ(camera.state(), CameraState::kStreaming);
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  EXPECT_EQ(camera.counters().recoveries, 1U);
  EXPECT_EQ(device.queuedBuffers(), 4);
}

TEST_F(V4l2Faults, ALongLossGoesLostRetryingStreamingWithEveryChangeReported) {
  device.unplug();
  EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);
  // 15 s away: longer than the 5 quick attempts (1 s), and than the old retry budget.
  int opens_while_away = device.openCalls();
  for (int i = 0; i < 75; ++i) EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);
  opens_while_away = device.openCalls() - opens_while_away;
  // Quick attempts, then 0.25, 0.5, 1, 2, 2, ... s apart: bounded, but never stopped.
  EXPECT_GE(opens_while_away, 8);
  EXPECT_LE(opens_while_away, 16);
  EXPECT_EQ(camera.state(), CameraState::kRetrying);
  device.replug();
  int cycles = 0;
  while (cycle() != AcquireResult::kFrame && cycles < 50) ++cycles;
  EXPECT_LE(cycles * kCycleNs, camera::RetryBackoff::kMaxIntervalNs + kCycleNs);
  const std::vector<CameraEvent> events = drain();
  ASSERT_EQ(events.size(), 3U);
  EXPECT_EQ(events[0].from, CameraState::kStreaming);
  EXPECT_EQ(events[0].to, CameraState::kLost);
  EXPECT_NE(std::strstr(events[0].text, "ENODEV (No such device)"), nullptr) << events[0].text;
  EXPECT_EQ(events[1].from, CameraState::kLost);
  EXPECT_EQ(events[1].to, CameraState::kRetrying);
  EXPECT_EQ(events[1].attempts, 5U);
  EXPECT_NE(std::strstr(events[1].text, "ENOENT (No such file or directory)"), nullptr) << events[1].text;
  EXPECT_EQ(events[2].from, CameraState::kRetrying);
  EXPECT_EQ(events[2].to, CameraState::kStreaming);
  EXPECT_GT(events[2].down_ns, 15'000'000'000);
  EXPECT_LE(events[2].retry_interval_ns, camera::RetryBackoff::kMaxIntervalNs);
  char line[256];
  camera::formatEvent(events[2], line, sizeof(line));
  EXPECT_NE(std::strstr(line, "from=retrying to=streaming attempts="), nullptr) << line;
}

TEST_F(V4l2Faults, AShortLossIsLostThenStreamingWithoutRetrying) {
  device.unplug();
  EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);
  device.replug();
  EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);  // this cycle's recover() reopens
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  const std::vector<CameraEvent> events = drain();
  ASSERT_EQ(events.size(), 2U);
  EXPECT_EQ(events[1].from, CameraState::kLost);
  EXPECT_EQ(events[1].to, CameraState::kStreaming);
}

TEST_F(V4l2Faults, AFatalStreamingErrorIsALossNamedWithItsErrno) {
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  device.fatalStreamingError();  // vivid inject_fatal_streaming_error: vb2 answers EIO
  EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);
  EXPECT_EQ(camera.counters().device_losses, 1U);
  EXPECT_EQ(camera.state(), CameraState::kStreaming);  // the cycle's recover() reopened at once
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  const std::vector<CameraEvent> events = drain();
  ASSERT_GE(events.size(), 1U);
  EXPECT_STREQ(events[0].text, "VIDIOC_DQBUF: EIO (Input/output error)");
}

TEST_F(V4l2Faults, AFreshBufferRefusedAtOpenIsParkedNotFatal) {
  camera.close();
  device.failQbuf(1);  // a QBUF error injected before the daemon starts
  ASSERT_TRUE(camera.open().ok) << camera.lastError();
  EXPECT_EQ(camera.pendingRequeues(), 1);
  EXPECT_EQ(camera.counters().errors, 1U);
  EXPECT_EQ(cycle(), AcquireResult::kFrame);
  EXPECT_EQ(camera.pendingRequeues(), 0);
  EXPECT_EQ(device.queuedBuffers(), 4);
  camera.close();
  device.failQbuf(3);  // only one of four left with the driver: refused, with the errno
  const LoadError error = camera.open();
  ASSERT_FALSE(error.ok);
  EXPECT_NE(error.message.find("VIDIOC_QBUF refused the fresh buffers"), std::string::npos) << error.message;
  EXPECT_EQ(device.openFds(), 0);
}

TEST_F(V4l2Faults, StreamonAndReqbufsErrorsDuringAReopenAreRetried) {
  for (const unsigned long request :
       {static_cast<unsigned long>(VIDIOC_STREAMON), static_cast<unsigned long>(VIDIOC_REQBUFS)}) {
    device.unplug();
    EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);
    device.replug();
    device.failNextIoctl(request, EINVAL);
    EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);  // the reopen fails on the injected error
    EXPECT_NE(std::strstr(camera.lastError(), ": EINVAL (Invalid argument)"), nullptr) << camera.lastError();
    EXPECT_EQ(device.openFds(), 0);
    EXPECT_EQ(cycle(), AcquireResult::kDeviceLost);  // the next one succeeds
    EXPECT_EQ(cycle(), AcquireResult::kFrame) << camera.lastError();
  }
  EXPECT_EQ(camera.counters().recoveries, 2U);
}

TEST_F(V4l2Faults, TheBackoffIsOnTheInjectedClockNotOnCalls) {
  device.unplug();
  Frame frame;
  ASSERT_EQ(camera.acquire(0, frame), AcquireResult::kDeviceLost);
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(camera.recover());  // quick attempts: one per call
  const int opens = device.openCalls();
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(camera.recover());  // a runaway caller costs nothing
  EXPECT_EQ(device.openCalls(), opens);
  device.advanceNs(camera::RetryBackoff::kFirstIntervalNs);
  EXPECT_FALSE(camera.recover());
  EXPECT_EQ(device.openCalls(), opens + 1);
}

TEST(V4l2Errno, EveryNameAndTextIsSpelledOut) {
  char text[96];
  EXPECT_STREQ(camera::formatOsError(text, sizeof(text), "VIDIOC_DQBUF", EIO),
               "VIDIOC_DQBUF: EIO (Input/output error)");
  EXPECT_STREQ(camera::formatOsError(text, sizeof(text), "VIDIOC_QBUF", 0), "VIDIOC_QBUF");
  EXPECT_STREQ(camera::formatNegativeError(text, sizeof(text), "queueRequest", -ENODEV),
               "queueRequest: ENODEV (No such device)");
  EXPECT_STREQ(camera::errnoName(99999), "E?");
  char small[8];
  camera::formatOsError(small, sizeof(small), "VIDIOC_STREAMON", EINVAL);
  EXPECT_EQ(std::strlen(small), 7U);  // truncated, terminated
}

}  // namespace
}  // namespace visnav::test
