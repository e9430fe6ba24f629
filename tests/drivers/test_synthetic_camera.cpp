// SyntheticCamera / ScenarioCamera: frames bit-identical to what visnav-synth writes for the same scenario
// (the tool is run here), 16-bit frames identical to an independent renderer, trajectory timestamps and
// end of stream, looping, pacing, and zero allocations per acquire() after open().
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "../support/alloc_counter.hpp"
#include "visnav/replay/sequence.hpp"
#include "visnav/synthetic/scenario_camera.hpp"

namespace visnav::synthetic {
namespace {
namespace fs = std::filesystem;
using camera::AcquireResult;
using camera::Pacing;

const std::string kScenario = std::string(VISNAV_SOURCE_DIR) + "/config/scenarios/approach_ci.toml";

// A short straight approach at 10 Hz.
class LineTrajectory final : public PoseTrajectory {
 public:
  explicit LineTrajectory(int frames) : m_frames(frames) {}
  int frameCount() const override { return m_frames; }
  Pose pose(int frame) const override {
    return Pose::fromYpr({0.01 * frame, 0.02, kPi}, Vec3(0.01 * frame, 0.0, 6.0 - 0.05 * frame));
  }
  std::int64_t timestampNs(int frame) const override { return 1000 + frame * 100000000LL; }

 private:
  int m_frames;
};

SyntheticCameraConfig smallConfig(const PoseTrajectory& trajectory, int bit_depth, Pacing pacing, bool loop) {
  SyntheticCameraConfig c;
  c.camera.width_px = 160;
  c.camera.height_px = 120;
  c.camera.fx_px = c.camera.fy_px = 200.0;
  c.camera.cx_px = 80.0;
  c.camera.cy_px = 60.0;
  c.model = makeRectanglePlate(2.3, 1.8);
  c.trajectory = &trajectory;
  c.seed = 99;
  c.bit_depth = bit_depth;
  c.max_code = bit_depth == 16 ? 4095 : 255;
  c.pacing = pacing;
  c.loop = loop;
  return c;
}

TEST(ScenarioCamera, FramesAreBitIdenticalToVisnavSynthOutput) {
  const fs::path out = fs::temp_directory_path() / ("visnav_test_synthcam_" + std::to_string(::getpid()));
  fs::remove_all(out);
  const std::string command = std::string(VISNAV_SYNTH_EXE) + " --scenario " + kScenario + " --out " +
                              out.string() + " --frames 3 > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  replay::Sequence written;
  ASSERT_TRUE(replay::loadSequence(out.string(), written).ok);
  ASSERT_EQ(written.frames.size(), 3U);

  ScenarioCamera cam({kScenario, Pacing::kAsFastAsPossible, false, 2});
  const LoadError e = cam.open();
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(cam.scenario().name, "approach_ci");
  const int w = cam.config().camera.width_px;
  const int h = cam.config().camera.height_px;
  std::vector<std::uint8_t> expected(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (std::size_t i = 0; i < 3; ++i) {
    int pw = 0;
    int ph = 0;
    int maxval = 0;
    ASSERT_TRUE(replay::readPgm(written.frames[i].file, expected.data(), expected.size(), pw, ph, maxval).ok);
    Frame f;
    ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame) << cam.lastError();
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(written.frames[i].frame));
    EXPECT_EQ(f.exposure_time_ns, written.frames[i].timestamp_ns);
    ASSERT_EQ(f.image.depth, MonoImage::Depth::kU8);
    int differing = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        differing += f.image.u8.at(x, y) != expected[static_cast<std::size_t>(y * w + x)];
    EXPECT_EQ(differing, 0) << "frame " << i;
    cam.release(f);
  }
  fs::remove_all(out);
}

TEST(SyntheticCamera, SixteenBitFramesMatchAnIndependentRendererAndEndOfStream) {
  const LineTrajectory trajectory(4);
  SyntheticCamera cam;
  const SyntheticCameraConfig config = smallConfig(trajectory, 16, Pacing::kAsFastAsPossible, false);
  cam.configure(config);
  ASSERT_TRUE(cam.open().ok);
  Renderer reference;
  ASSERT_TRUE(reference.init(PinholeCamera(config.camera), config.model, config.render).ok);
  std::vector<std::uint16_t> expected(160 * 120);
  for (int i = 0; i < 4; ++i) {
    reference.setFrameIndex(i);
    reference.render(trajectory.pose(i), Renderer::frameSeed(99, static_cast<std::uint64_t>(i)),
                     expected.data(), 2 * 160, 4095);
    Frame f;
    ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
    EXPECT_EQ(f.image.depth, MonoImage::Depth::kU16);
    EXPECT_EQ(f.image.max_code, 4095);
    EXPECT_EQ(f.source_format, PixelFormat::kY12);
    EXPECT_EQ(f.exposure_time_ns, trajectory.timestampNs(i));
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(i));
    int differing = 0;
    int bright = 0;
    for (int y = 0; y < 120; ++y) {
      for (int x = 0; x < 160; ++x) {
        differing += f.image.u16.at(x, y) != expected[static_cast<std::size_t>(y * 160 + x)];
        bright += f.image.u16.at(x, y) > 2000;
      }
    }
    EXPECT_EQ(differing, 0) << "frame " << i;
    EXPECT_GT(bright, 500);  // the plate is really in the picture
    cam.release(f);
  }
  Frame f;
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kEndOfStream);
  EXPECT_EQ(cam.counters().frames_delivered, 4U);
}

TEST(SyntheticCamera, LoopRepeatsTheTrajectoryWithIncreasingTimeAndSequence) {
  const LineTrajectory trajectory(2);
  SyntheticCamera cam;
  cam.configure(smallConfig(trajectory, 8, Pacing::kAsFastAsPossible, true));
  ASSERT_TRUE(cam.open().ok);
  std::vector<std::uint8_t> first(160 * 120);
  for (int n = 0; n < 5; ++n) {
    Frame f;
    ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(n));
    EXPECT_EQ(cam.trajectoryFrame(f.sequence), n % 2);
    EXPECT_EQ(f.exposure_time_ns, 1000 + n * 100000000LL);  // span of one pass: 2 frames of 100 ms
    if (n == 0) std::copy(f.image.u8.data(), f.image.u8.data() + first.size(), first.begin());
    if (n == 2) {
      EXPECT_TRUE(std::equal(first.begin(), first.end(), f.image.u8.data()));  // the same frame again
    }
    cam.release(f);
  }
}

TEST(SyntheticCamera, RecordedRatePacingAndTimeout) {
  const LineTrajectory trajectory(3);  // 100 ms apart
  SyntheticCamera cam;
  cam.configure(smallConfig(trajectory, 8, Pacing::kRecordedRate, false));
  ASSERT_TRUE(cam.open().ok);
  Frame f;
  ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
  const std::int64_t origin = f.exposure_time_ns;
  cam.release(f);
  EXPECT_EQ(cam.acquire(1000000, f), AcquireResult::kTimeout);  // 1 ms is not enough for 100 ms
  EXPECT_EQ(cam.counters().timeouts, 1U);
  ASSERT_EQ(cam.acquire(1000000000, f), AcquireResult::kFrame);
  EXPECT_EQ(f.exposure_time_ns - origin, 100000000);
  cam.release(f);
}

TEST(SyntheticCamera, OpenRejectsBadConfigurations) {
  SyntheticCamera cam;
  EXPECT_FALSE(cam.open().ok);  // no trajectory
  const LineTrajectory trajectory(2);
  SyntheticCameraConfig c = smallConfig(trajectory, 12, Pacing::kAsFastAsPossible, false);
  cam.configure(c);
  EXPECT_FALSE(cam.open().ok);
  ScenarioCamera missing({"/nonexistent/scenario.toml", Pacing::kAsFastAsPossible, false, 2});
  const LoadError e = missing.open();
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("/nonexistent/scenario.toml"), std::string::npos) << e.message;
}

TEST(SyntheticCamera, NoAllocationPerAcquireAfterOpen) {
  const LineTrajectory trajectory(10);
  for (const int bit_depth : {8, 16}) {
    SyntheticCamera cam;
    cam.configure(smallConfig(trajectory, bit_depth, Pacing::kAsFastAsPossible, true));
    ASSERT_TRUE(cam.open().ok);
    const std::uint64_t before = test::allocationCount();
    for (int n = 0; n < 50; ++n) {
      Frame f;
      ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
      cam.release(f);
    }
    const std::uint64_t after = test::allocationCount();
    EXPECT_EQ(after - before, 0U) << bit_depth << "-bit: allocations in 50 acquire/release (malloc counted: "
                                  << test::countsMalloc() << ")";
  }
}

}  // namespace
}  // namespace visnav::synthetic
