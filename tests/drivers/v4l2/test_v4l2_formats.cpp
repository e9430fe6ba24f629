// V4L2 driver against the FAKE device: format negotiation, zero-copy views, conversions, open() errors.
#include <gtest/gtest.h>

#include <string>

#include "v4l2_test_util.hpp"

namespace visnav::test {
namespace {

using camera::AcquireResult;
using camera::RequestedFormat;
using camera::V4l2Camera;

FakeV4l2Device::Config paddedConfig() {
  FakeV4l2Device::Config config;
  config.row_padding_bytes = 24;  // a stride that is not width * bytes per pixel
  return config;
}

TEST(V4l2Formats, GreyIsAnInPlaceViewWithTheDriverStride) {
  FakeV4l2Device device(paddedConfig());
  V4l2Camera camera(fakeCameraParams(RequestedFormat::kGrey), device);
  ASSERT_TRUE(camera.open().ok);
  EXPECT_EQ(device.format().bytesperline, 64U + 24U);
  EXPECT_EQ(camera.streamInfo().bytes_per_line, 88U);
  EXPECT_EQ(std::string(camera.streamInfo().driver), "fake-v4l2");
  device.skipFrames(3);
  Frame frame;
  produceAndAcquire(device, camera, frame);
  ASSERT_EQ(frame.image.depth, MonoImage::Depth::kU8);
  EXPECT_EQ(frame.image.max_code, 255);
  EXPECT_EQ(frame.image.width(), 64);
  EXPECT_EQ(frame.image.height(), 48);
  EXPECT_EQ(frame.image.u8.strideBytes(), 88);  // the mmap buffer's own rows: no copy was made
  EXPECT_EQ(frame.source_format, PixelFormat::kGrey8);
  EXPECT_EQ(frame.sequence, 3U);
  int mismatches = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      mismatches += frame.image.u8.at(x, y) != FakeV4l2Device::pattern(V4L2_PIX_FMT_GREY, 3, x, y) ? 1 : 0;
  EXPECT_EQ(mismatches, 0);
  // The view points into mapped driver memory: the row after the last pixel is padding (0xEE), not image.
  EXPECT_EQ(frame.image.u8.row(0)[64], 0xEE);
  camera.release(frame);
}

struct Wide {
  RequestedFormat format;
  std::uint32_t fourcc;
  std::uint16_t max_code;
  PixelFormat pixel_format;
};

class V4l2SixteenBit : public ::testing::TestWithParam<Wide> {};

TEST_P(V4l2SixteenBit, LittleEndianWordsAreAnInPlaceSixteenBitView) {
  const Wide wide = GetParam();
  FakeV4l2Device device(paddedConfig());
  V4l2Camera camera(fakeCameraParams(wide.format), device);
  ASSERT_TRUE(camera.open().ok) << camera.lastError();
  Frame frame;
  device.skipFrames(17);
  produceAndAcquire(device, camera, frame);
  ASSERT_EQ(frame.image.depth, MonoImage::Depth::kU16);
  EXPECT_EQ(frame.image.max_code, wide.max_code);
  EXPECT_EQ(frame.source_format, wide.pixel_format);
  EXPECT_EQ(frame.image.u16.strideBytes(), 64 * 2 + 24);
  int mismatches = 0;
  std::uint16_t largest = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const std::uint16_t got = frame.image.u16.at(x, y);
      mismatches += got != FakeV4l2Device::pattern(wide.fourcc, 17, x, y) ? 1 : 0;
      largest = got > largest ? got : largest;
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_LE(largest, wide.max_code);
  EXPECT_GT(largest, 255);  // really more than 8 bits came through
  camera.release(frame);
}

INSTANTIATE_TEST_SUITE_P(
    Formats, V4l2SixteenBit,
    ::testing::Values(Wide{RequestedFormat::kY10, V4L2_PIX_FMT_Y10, 1023, PixelFormat::kY10},
                      Wide{RequestedFormat::kY12, V4L2_PIX_FMT_Y12, 4095, PixelFormat::kY12},
                      Wide{RequestedFormat::kY16, V4L2_PIX_FMT_Y16, 65535, PixelFormat::kY16}),
    [](const ::testing::TestParamInfo<Wide>& param_info) {
      return std::string(toString(param_info.param.pixel_format));
    });

TEST(V4l2Formats, YuyvDeliversItsYPlaneCopiedIntoPackedStorage) {
  FakeV4l2Device device(paddedConfig());
  V4l2Camera camera(fakeCameraParams(RequestedFormat::kYuyv), device);
  ASSERT_TRUE(camera.open().ok);
  for (std::uint32_t sequence = 0; sequence < 3; ++sequence) {
    Frame frame;
    produceAndAcquire(device, camera, frame);
    ASSERT_EQ(frame.image.depth, MonoImage::Depth::kU8);
    EXPECT_EQ(frame.image.u8.strideBytes(), 64);  // packed: the copy, not the 2 * 64 + 24 device rows
    EXPECT_EQ(frame.source_format, PixelFormat::kYuyv);
    int mismatches = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        mismatches +=
            frame.image.u8.at(x, y) != FakeV4l2Device::pattern(V4L2_PIX_FMT_YUYV, sequence, x, y) ? 1 : 0;
    EXPECT_EQ(mismatches, 0) << "frame " << sequence;
    camera.release(frame);
  }
}

TEST(V4l2Formats, FrameIntervalAndRingAreSetFromTheConfig) {
  FakeV4l2Device::Config config;
  config.min_buffers = 3;
  FakeV4l2Device device(config);
  camera::CameraParams params = fakeCameraParams();
  params.fps_hz = 7.5;
  params.buffer_count = 2;  // below the driver's minimum: it grants 3
  V4l2Camera camera(params, device);
  ASSERT_TRUE(camera.open().ok);
  EXPECT_EQ(device.frameInterval().numerator, 1000U);
  EXPECT_EQ(device.frameInterval().denominator, 7500U);
  EXPECT_TRUE(camera.streamInfo().frame_interval_set);
  EXPECT_EQ(camera.streamInfo().buffer_count, 3);
  EXPECT_EQ(device.grantedBuffers(), 3U);
  EXPECT_EQ(device.mappedBuffers(), 3);
  EXPECT_EQ(device.queuedBuffers(), 3);
  EXPECT_TRUE(device.streaming());
  camera.close();
  EXPECT_EQ(device.mappedBuffers(), 0);
  EXPECT_EQ(device.openFds(), 0);
  EXPECT_FALSE(device.streaming());
}

TEST(V4l2Formats, WholeFrameRateIsAnExactFraction) {
  FakeV4l2Device device(FakeV4l2Device::Config{});
  V4l2Camera camera(fakeCameraParams(), device);
  ASSERT_TRUE(camera.open().ok);
  EXPECT_EQ(device.frameInterval().numerator, 1U);
  EXPECT_EQ(device.frameInterval().denominator, 5U);
}

TEST(V4l2Formats, AFixedRateDeviceStillStreams) {
  FakeV4l2Device::Config config;
  config.frame_interval_settable = false;  // VIDIOC_S_PARM -> ENOTTY
  FakeV4l2Device device(config);
  V4l2Camera camera(fakeCameraParams(), device);
  ASSERT_TRUE(camera.open().ok);
  EXPECT_FALSE(camera.streamInfo().frame_interval_set);
  Frame frame;
  produceAndAcquire(device, camera, frame);
}

std::string openError(const FakeV4l2Device::Config& config, const camera::CameraParams& params) {
  FakeV4l2Device device(config);
  V4l2Camera camera(params, device);
  const LoadError error = camera.open();
  EXPECT_FALSE(error.ok);
  EXPECT_EQ(device.openFds(), 0) << "a failed open must close what it opened";
  EXPECT_EQ(device.mappedBuffers(), 0);
  return error.message;
}

TEST(V4l2Formats, AnAdjustedFormatIsRefusedNamingBoth) {
  FakeV4l2Device::Config config;
  config.formats = {V4L2_PIX_FMT_YUYV};
  config.format_count = 1;
  const std::string message = openError(config, fakeCameraParams(RequestedFormat::kGrey));
  EXPECT_NE(message.find("/dev/fake-video0"), std::string::npos) << message;
  EXPECT_NE(message.find("asked for GREY 64x48, the device offers YUYV 64x48"), std::string::npos) << message;
  EXPECT_NE(message.find("v4l2-ctl -d /dev/fake-video0 --list-formats-ext"), std::string::npos) << message;
}

TEST(V4l2Formats, AClampedSizeIsRefused) {
  camera::CameraParams params = fakeCameraParams(RequestedFormat::kY16);
  params.width_px = 640;
  params.height_px = 480;
  const std::string message = openError(FakeV4l2Device::Config{}, params);
  EXPECT_NE(message.find("asked for Y16  640x480, the device offers Y16  320x240"), std::string::npos)
      << message;
}

TEST(V4l2Formats, NonCaptureDevicesAreRefusedWithTheReason) {
  FakeV4l2Device::Config output;
  output.device_caps = V4L2_CAP_VIDEO_OUTPUT | V4L2_CAP_STREAMING;
  EXPECT_NE(openError(output, fakeCameraParams()).find("not a video capture device"), std::string::npos);
  FakeV4l2Device::Config multiplanar;
  multiplanar.device_caps = V4L2_CAP_VIDEO_CAPTURE_MPLANE | V4L2_CAP_STREAMING;
  EXPECT_NE(openError(multiplanar, fakeCameraParams()).find("multi-planar"), std::string::npos);
  FakeV4l2Device::Config read_only;
  read_only.device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_READWRITE;
  EXPECT_NE(openError(read_only, fakeCameraParams()).find("V4L2_CAP_STREAMING"), std::string::npos);
}

TEST(V4l2Formats, AMissingNodeNamesPathAndErrno) {
  camera::CameraParams params = fakeCameraParams();
  params.device = "/dev/fake-video7";
  const std::string message = openError(FakeV4l2Device::Config{}, params);
  EXPECT_NE(message.find("v4l2 /dev/fake-video7: cannot open the device node"), std::string::npos) << message;
  EXPECT_NE(message.find(": ENOENT (No such file or directory)"), std::string::npos) << message;
}

}  // namespace
}  // namespace visnav::test
