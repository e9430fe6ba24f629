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

TEST(LibcameraFormats, RequestedFirstThenMonoThenYPlaneThenYuyvThenRgb) {
  const FormatCandidates y10 = formatCandidates(RequestedFormat::kY10);
  ASSERT_EQ(y10.count, kLibcameraFormatCount);
  const char* expected[] = {"R10",  "R8",   "R12",      "NV12",     "NV21",   "YUV420", "YVU420",
                            "NV16", "YUYV", "XRGB8888", "XBGR8888", "RGB888", "BGR888"};
  for (int i = 0; i < y10.count; ++i)
    EXPECT_STREQ(formatInfo(y10.formats[static_cast<std::size_t>(i)]).name, expected[i]) << i;
  const FormatCandidates yuyv = formatCandidates(RequestedFormat::kYuyv);
  ASSERT_EQ(yuyv.count, kLibcameraFormatCount);
  EXPECT_EQ(yuyv.formats[0], LibcameraFormat::kYuyv);
  EXPECT_EQ(yuyv.formats[1], LibcameraFormat::kR8);
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
  EXPECT_FALSE(pixelFormatFromLibcameraName("NV12", format));  // no visnav format of its own: luma only
  for (int i = 0; i < kLibcameraFormatCount; ++i) {
    LibcameraFormat back = LibcameraFormat::kR8;
    ASSERT_TRUE(libcameraFormatFromName(formatInfo(static_cast<LibcameraFormat>(i)).name, back));
    EXPECT_EQ(static_cast<int>(back), i);
  }
  LibcameraFormat unknown = LibcameraFormat::kR8;
  EXPECT_FALSE(libcameraFormatFromName("SRGGB10", unknown));  // Bayer: not demosaiced
}

TEST(LibcameraFormats, HowEachFormatBecomesLuma) {
  // YUV: the first plane is Y, viewed in place; RGB: converted with DRM byte order (RGB888 is B, G, R).
  EXPECT_EQ(formatInfo(LibcameraFormat::kNv12).source, LumaSource::kInPlace8);
  EXPECT_EQ(formatInfo(LibcameraFormat::kNv16).delivered, PixelFormat::kGrey8);
  EXPECT_EQ(formatInfo(LibcameraFormat::kR12).source, LumaSource::kInPlace16);
  const LibcameraFormatInfo& rgb888 = formatInfo(LibcameraFormat::kRgb888);
  EXPECT_EQ(rgb888.source, LumaSource::kPackedRgb);
  EXPECT_EQ(rgb888.bytes_per_pixel, 3);
  EXPECT_EQ(rgb888.blue, 0);
  EXPECT_EQ(rgb888.red, 2);
  const LibcameraFormatInfo& bgr888 = formatInfo(LibcameraFormat::kBgr888);
  EXPECT_EQ(bgr888.red, 0);
  EXPECT_EQ(bgr888.blue, 2);
  EXPECT_EQ(formatInfo(LibcameraFormat::kXbgr8888).bytes_per_pixel, 4);
  EXPECT_EQ(firstPlaneBytes(LibcameraFormat::kRgb888, 640, 480, 1920), 1920U * 480U);
  EXPECT_EQ(firstPlaneBytes(LibcameraFormat::kNv12, 640, 480, 640), 640U * 480U);
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

/// The ids libcamera lists, read from the refusal of an id that cannot exist ("none" when it sees none).
std::string availableIds() {
  LibcameraCamera probe(libcameraParams("/base/visnav/no-such-sensor@10"));
  const std::string message = probe.open().message;
  const std::size_t at = message.find("; available: ");
  return at == std::string::npos ? message : message.substr(at + 13);
}

// The claim: with an empty id the driver takes the first camera libcamera lists, and says which; with none
// listed it says "none". It holds whether or not a camera is present, usable or not.
TEST(LibcameraCamera, AnEmptyIdTakesTheFirstCameraOrSaysThereIsNone) {
  const std::string available = availableIds();
  LibcameraCamera camera(libcameraParams(""));
  const LoadError error = camera.open();
  if (available.rfind("none", 0) == 0) {
    ASSERT_FALSE(error.ok);
    EXPECT_NE(
        error.message.find("libcamera: no camera found; available: none (libcamera v0.0.3 sees no camera"),
        std::string::npos)
        << error.message;
    return;
  }
  // A camera is listed: the first one ('id', ...) is the one opened, or named in the refusal.
  ASSERT_EQ(available.front(), '\'') << available;
  const std::string first = available.substr(0, available.find('\'', 1) + 1);
  const std::string said = error.ok ? camera.description() : error.message;
  EXPECT_NE(said.find("camera " + first), std::string::npos) << "first listed " << first << ": " << said;
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
  // A pipeline with size steps (vimc: widths in steps of 12) needs a size it offers:
  // VISNAV_LIBCAMERA_SIZE=WxH.
  if (const char* size = std::getenv("VISNAV_LIBCAMERA_SIZE"))
    std::sscanf(size, "%dx%d", &params.width_px, &params.height_px);
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
