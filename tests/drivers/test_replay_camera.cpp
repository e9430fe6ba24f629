// ReplayCamera over sequences written here with known pixel content: every frame, its recorded timestamp and
// frame number, end of stream, pacing and timeouts on the real clock, looping, 16-bit frames, ring misuse,
// unreadable files, and zero allocations per acquire() after open().
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../support/alloc_counter.hpp"
#include "visnav/replay/replay_camera.hpp"

namespace visnav::replay {
namespace {
namespace fs = std::filesystem;
using camera::AcquireResult;
using camera::Pacing;

constexpr int kW = 64;
constexpr int kH = 48;
constexpr std::int64_t kFirstNs = 5000;
constexpr std::int64_t kIntervalNs = 20000000;  // 50 Hz

std::uint16_t pixelValue(std::int64_t frame, int x, int y, std::uint16_t max_code) {
  return static_cast<std::uint16_t>((frame * 37 + x * 3 + y * 5) % (max_code + 1));
}

// A sequence of `count` frames numbered 10, 12, 14 ... (a strided recording) at 50 Hz.
class SequenceDir {
 public:
  SequenceDir(const std::string& tag, int count, int bit_depth = 8, std::uint16_t max_code = 255) {
    m_path = fs::temp_directory_path() / ("visnav_test_replaycam_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(m_path);
    CameraIntrinsics k;
    k.width_px = kW;
    k.height_px = kH;
    k.fx_px = k.fy_px = 80.0;
    k.cx_px = 32.0;
    k.cy_px = 24.0;
    SequenceWriter writer;
    EXPECT_TRUE(
        writer.open(m_path.string(), tag, k, makeRectanglePlate(1.0, 1.0), bit_depth, max_code, 50.0).ok);
    std::vector<std::uint16_t> img(kW * kH);
    std::vector<std::uint8_t> img8(kW * kH);
    for (int i = 0; i < count; ++i) {
      const std::int64_t frame = 10 + 2 * i;
      for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
          img[y * kW + x] = pixelValue(frame, x, y, max_code);
          img8[y * kW + x] = static_cast<std::uint8_t>(img[y * kW + x]);
        }
      }
      const LoadError e =
          bit_depth == 8 ? writePgm8(writer.framePath(frame), ImageView8(img8.data(), kW, kH))
                         : writePgm16(writer.framePath(frame), ImageView16(img.data(), kW, kH), max_code);
      EXPECT_TRUE(e.ok) << e.message;
      writer.addFrame(frame, kFirstNs + i * kIntervalNs, nullptr);
    }
    EXPECT_TRUE(writer.close().ok);
  }
  ~SequenceDir() { fs::remove_all(m_path); }
  std::string str() const { return m_path.string(); }
  std::string framePath(std::int64_t frame) const {
    char name[32];
    std::snprintf(name, sizeof name, "frames/%06lld.pgm", static_cast<long long>(frame));
    return (m_path / name).string();
  }

 private:
  fs::path m_path;
};

bool frameMatches(const Frame& f, std::int64_t frame, std::uint16_t max_code) {
  if (f.image.width() != kW || f.image.height() != kH) return false;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const std::uint16_t v =
          f.image.depth == MonoImage::Depth::kU8 ? f.image.u8.at(x, y) : f.image.u16.at(x, y);
      if (v != pixelValue(frame, x, y, max_code)) return false;
    }
  }
  return true;
}

TEST(ReplayCamera, DeliversEveryFrameThenEndOfStream) {
  SequenceDir dir("all", 6);
  ReplayCamera cam({dir.str(), Pacing::kAsFastAsPossible, false, 2});
  ASSERT_TRUE(cam.open().ok);
  EXPECT_EQ(cam.sequence().frames.size(), 6U);
  for (int i = 0; i < 6; ++i) {
    Frame f;
    ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame) << cam.lastError();
    EXPECT_TRUE(frameMatches(f, 10 + 2 * i, 255)) << "frame " << i;
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(10 + 2 * i));  // the recorded frame numbers
    EXPECT_EQ(f.exposure_time_ns, kFirstNs + i * kIntervalNs);      // the recorded timestamps
    EXPECT_EQ(f.source_format, PixelFormat::kGrey8);
    cam.release(f);
  }
  Frame f;
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kEndOfStream);
  EXPECT_EQ(cam.acquire(1000000, f), AcquireResult::kEndOfStream);
  EXPECT_EQ(cam.counters().frames_delivered, 6U);
  EXPECT_EQ(cam.counters().errors, 0U);
  EXPECT_EQ(cam.counters().frames_dropped, 0U);
}

/// A simulated monotonic clock for the pacer: time moves only when the pacer sleeps (or the test says so).
struct SimulatedPacerClock {
  std::int64_t now_ns = 1'000'000'000'000LL;
  int sleeps = 0;
  camera::PacerClock clock() {
    camera::PacerClock c;
    c.now_ns = [](void* self) { return static_cast<SimulatedPacerClock*>(self)->now_ns; };
    c.sleep_until_ns = [](void* self, std::int64_t deadline_ns) {
      auto* s = static_cast<SimulatedPacerClock*>(self);
      if (deadline_ns > s->now_ns) s->now_ns = deadline_ns;
      ++s->sleeps;
    };
    c.context = this;
    return c;
  }
};

TEST(ReplayCamera, RecordedRatePacingOnTheMonotonicClock) {
  // On a simulated clock: the result is the same however slowly the machine runs the test.
  SequenceDir dir("paced", 4);
  SimulatedPacerClock time;
  ReplayCamera cam({dir.str(), Pacing::kRecordedRate, false, 2});
  cam.setPacerClock(time.clock());
  ASSERT_TRUE(cam.open().ok);
  Frame f;
  ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);  // the first frame is due at once
  const std::int64_t origin = f.exposure_time_ns;
  EXPECT_EQ(origin, time.now_ns);
  cam.release(f);
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kTimeout);  // frame 1 is 20 ms away
  EXPECT_EQ(cam.counters().timeouts, 1U);
  EXPECT_EQ(cam.acquire(kIntervalNs / 2, f), AcquireResult::kTimeout);  // waits 10 ms of its 20, no more
  EXPECT_EQ(time.now_ns, origin + kIntervalNs / 2);
  for (int i = 1; i < 4; ++i) {
    ASSERT_EQ(cam.acquire(1000000000, f), AcquireResult::kFrame);
    EXPECT_EQ(f.exposure_time_ns, origin + i * kIntervalNs);  // recorded spacing on the pacer's clock
    EXPECT_EQ(time.now_ns, f.exposure_time_ns);               // delivered when due, not before
    EXPECT_TRUE(frameMatches(f, 10 + 2 * i, 255));
    cam.release(f);
  }
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kEndOfStream);
}

TEST(ReplayCamera, LoopKeepsTimeAndSequenceIncreasing) {
  SequenceDir dir("loop", 3);
  ReplayCamera cam({dir.str(), Pacing::kAsFastAsPossible, true, 2});
  ASSERT_TRUE(cam.open().ok);
  // Span of one pass: 40 ms + one 20 ms interval; frame numbers 10..14 repeat shifted by 14 - 10 + 1 = 5.
  for (int n = 0; n < 8; ++n) {
    Frame f;
    ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
    const int i = n % 3;
    const int pass = n / 3;
    EXPECT_TRUE(frameMatches(f, 10 + 2 * i, 255));
    EXPECT_EQ(f.exposure_time_ns, kFirstNs + i * kIntervalNs + pass * 3 * kIntervalNs);
    EXPECT_EQ(f.sequence, static_cast<std::uint64_t>(10 + 2 * i + 5 * pass));
    cam.release(f);
  }
}

TEST(ReplayCamera, SixteenBitFramesAreHostOrderY10Views) {
  SequenceDir dir("y10", 2, 16, 1023);
  ReplayCamera cam({dir.str(), Pacing::kAsFastAsPossible, false, 2});
  ASSERT_TRUE(cam.open().ok);
  Frame f;
  ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);
  EXPECT_EQ(f.image.depth, MonoImage::Depth::kU16);
  EXPECT_EQ(f.image.max_code, 1023);
  EXPECT_EQ(f.source_format, PixelFormat::kY10);
  EXPECT_TRUE(frameMatches(f, 10, 1023));
}

TEST(ReplayCamera, RingMisuseAndBadFilesAreErrorsNotCrashes) {
  SequenceDir dir("misuse", 4);
  ReplayCamera cam({dir.str(), Pacing::kAsFastAsPossible, false, 1});
  ASSERT_TRUE(cam.open().ok);
  Frame held;
  ASSERT_EQ(cam.acquire(0, held), AcquireResult::kFrame);
  Frame f;
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kError);  // the one slot is still held
  EXPECT_NE(std::string(cam.lastError()).find("release"), std::string::npos) << cam.lastError();
  cam.release(held);
  cam.release(held);  // double release
  EXPECT_EQ(cam.counters().errors, 2U);
  fs::remove(dir.framePath(12));  // frame 12 vanished after open
  EXPECT_EQ(cam.acquire(0, f), AcquireResult::kError);
  EXPECT_NE(std::string(cam.lastError()).find("000012.pgm"), std::string::npos) << cam.lastError();
  ASSERT_EQ(cam.acquire(0, f), AcquireResult::kFrame);  // the bad frame is skipped, not retried forever
  EXPECT_TRUE(frameMatches(f, 14, 255));
  cam.release(f);
}

TEST(ReplayCamera, OpenErrorsNameTheProblem) {
  ReplayCamera missing({"/nonexistent/visnav/sequence", Pacing::kAsFastAsPossible, false, 2});
  const LoadError e = missing.open();
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("/nonexistent/visnav/sequence"), std::string::npos) << e.message;
  Frame f;
  EXPECT_EQ(missing.acquire(0, f), AcquireResult::kError);
  SequenceDir dir("ring", 1);
  ReplayCamera bad_ring({dir.str(), Pacing::kAsFastAsPossible, false, 0});
  EXPECT_FALSE(bad_ring.open().ok);
}

TEST(ReplayCamera, LongPgmHeaderCommentsCrossTheReadBuffer) {
  SequenceDir dir("hdr", 1);
  const std::string path = dir.str() + "/long_header.pgm";
  std::string raster(kW * kH, '\0');
  for (int i = 0; i < kW * kH; ++i) raster[i] = static_cast<char>(i % 251);
  std::ofstream(path, std::ios::binary) << "P5\n# " << std::string(700, 'c') << "\n"
                                        << kW << " " << kH << "\n# " << std::string(300, 'd') << "\n255\n"
                                        << raster;
  std::vector<std::uint8_t> buffer(kW * kH);
  int w = 0;
  int h = 0;
  int maxval = 0;
  const LoadError e = readPgm(path, buffer.data(), buffer.size(), w, h, maxval);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(w, kW);
  EXPECT_EQ(h, kH);
  EXPECT_EQ(maxval, 255);
  for (int i = 0; i < kW * kH; ++i) ASSERT_EQ(buffer[i], i % 251) << i;
}

TEST(ReplayCamera, NoAllocationPerAcquireAfterOpen) {
  SequenceDir dir("noalloc", 5, 16, 4095);
  ReplayCamera cam({dir.str(), Pacing::kAsFastAsPossible, true, 2});
  ASSERT_TRUE(cam.open().ok);
  std::uint64_t checksum = 0;
  const std::uint64_t before = test::allocationCount();
  for (int n = 0; n < 300; ++n) {
    Frame f;
    if (cam.acquire(0, f) != AcquireResult::kFrame) break;
    checksum += f.image.u16.at(n % kW, n % kH);
    cam.release(f);
  }
  const std::uint64_t after = test::allocationCount();
  EXPECT_EQ(after - before, 0U) << "allocations in 300 acquire/release (malloc counted: "
                                << test::countsMalloc() << ")";
  EXPECT_EQ(cam.counters().frames_delivered, 300U);
  EXPECT_GT(checksum, 0U);
}

}  // namespace
}  // namespace visnav::replay
