// libcamera driver: what runs on this machine, which has no camera (libcamera 0.0.3 starts and sees none).
// libcamera is NOT faked: the protocol with a real camera is tested on a testbed or in the vimc VM (set
// VISNAV_LIBCAMERA_ID to a camera id, or leave it empty to use the first camera, to run the streaming test).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "visnav/libcamera/libcamera_camera.hpp"
#include "visnav/libcamera/libcamera_formats.hpp"

namespace visnav::camera {
namespace {

CameraParams libcameraParams(const std::string& id) {
  ::setenv("LIBCAMERA_LOG_LEVELS", "*:ERROR", 0);  // keep libcamera's INFO/WARN lines out of the test log
  CameraParams params;
  params.driver = static_cast<int>(CameraDriver::kLibcamera);
  params.device = id;
  return params;
}

TEST(LibcameraFormats, RequestedFirstThenMonoFallbacks) {
  const FormatCandidates y10 = formatCandidates(RequestedFormat::kY10);
  ASSERT_EQ(y10.count, 4);
  EXPECT_EQ(y10.formats[0], PixelFormat::kY10);
  EXPECT_EQ(y10.formats[1], PixelFormat::kGrey8);
  EXPECT_EQ(y10.formats[2], PixelFormat::kY12);
  EXPECT_EQ(y10.formats[3], PixelFormat::kYuyv);
  const FormatCandidates yuyv = formatCandidates(RequestedFormat::kYuyv);
  ASSERT_EQ(yuyv.count, 4);
  EXPECT_EQ(yuyv.formats[0], PixelFormat::kYuyv);
  EXPECT_EQ(yuyv.formats[1], PixelFormat::kGrey8);
  EXPECT_EQ(formatCandidates(RequestedFormat::kY16).count, 0);
}

TEST(LibcameraFormats, NamesRoundTrip) {
  EXPECT_STREQ(libcameraFormatName(PixelFormat::kGrey8), "R8");
  EXPECT_STREQ(libcameraFormatName(PixelFormat::kY12), "R12");
  EXPECT_EQ(libcameraFormatName(PixelFormat::kY16), nullptr);
  PixelFormat format = PixelFormat::kGrey8;
  EXPECT_TRUE(pixelFormatFromLibcameraName("R10", format));
  EXPECT_EQ(format, PixelFormat::kY10);
  EXPECT_TRUE(pixelFormatFromLibcameraName("YUYV", format));
  EXPECT_EQ(format, PixelFormat::kYuyv);
  EXPECT_FALSE(pixelFormatFromLibcameraName("NV12", format));
}

TEST(LibcameraCamera, AnUnknownIdIsNamedWithTheAvailableOnes) {
  LibcameraCamera camera(libcameraParams("/base/visnav/no-such-sensor@10"));
  const LoadError error = camera.open();
  ASSERT_FALSE(error.ok);
  EXPECT_NE(
      error.message.find("libcamera: no camera with id '/base/visnav/no-such-sensor@10' ([camera] device)"),
      std::string::npos)
      << error.message;
  EXPECT_NE(error.message.find("; available: "), std::string::npos) << error.message;
  // A failed open leaves the object reusable: the CameraManager was stopped and destroyed (libcamera allows
  // one per process, so a leak would abort the next one).
  const LoadError again = camera.open();
  EXPECT_FALSE(again.ok);
  EXPECT_EQ(again.message, error.message);
}

TEST(LibcameraCamera, WithoutACameraTheListIsNone) {
  LibcameraCamera camera(libcameraParams(""));
  const LoadError error = camera.open();
  if (error.ok) GTEST_SKIP() << "a camera is present: " << camera.description();
  EXPECT_NE(
      error.message.find("libcamera: no camera found; available: none (libcamera v0.0.3 sees no camera"),
      std::string::npos)
      << error.message;
}

TEST(LibcameraCamera, ConfigErrorsComeBeforeLibcamera) {
  CameraParams y16 = libcameraParams("any");
  y16.pixel_format = static_cast<int>(RequestedFormat::kY16);
  LoadError error = LibcameraCamera(y16).open();
  EXPECT_NE(error.message.find("y16 has no libcamera 0.0.3 equivalent"), std::string::npos) << error.message;
  CameraParams ring = libcameraParams("any");
  ring.buffer_count = 40;
  error = LibcameraCamera(ring).open();
  EXPECT_NE(error.message.find("buffer_count must be in [2, 32]"), std::string::npos) << error.message;
}

TEST(LibcameraCamera, UnopenedCameraRefusesWork) {
  LibcameraCamera camera(libcameraParams("any"));
  Frame frame;
  EXPECT_EQ(camera.acquire(1000000, frame), AcquireResult::kError);
  EXPECT_FALSE(camera.recover());
  EXPECT_EQ(camera.counters().errors, 1U);
  camera.release(frame);  // nothing held: counted, harmless
  EXPECT_EQ(camera.counters().errors, 2U);
}

TEST(LibcameraCamera, StreamsFromACameraWhenOneIsGiven) {
  const char* id = std::getenv("VISNAV_LIBCAMERA_ID");
  if (id == nullptr) GTEST_SKIP() << "no camera here; set VISNAV_LIBCAMERA_ID (empty: first camera) to run";
  CameraParams params = libcameraParams(id);
  params.fps_hz = 10.0;
  LibcameraCamera camera(params);
  const LoadError error = camera.open();
  ASSERT_TRUE(error.ok) << error.message;
  std::uint64_t last_sequence = 0;
  for (int i = 0; i < 5; ++i) {
    Frame frame;
    ASSERT_EQ(camera.acquire(2000000000, frame), AcquireResult::kFrame) << camera.lastError();
    EXPECT_EQ(frame.image.width(), params.width_px);
    if (i > 0) {
      EXPECT_GT(frame.sequence, last_sequence);
    }
    last_sequence = frame.sequence;
    camera.release(frame);
  }
  std::printf("%s\n", camera.description().c_str());
}

}  // namespace
}  // namespace visnav::camera
