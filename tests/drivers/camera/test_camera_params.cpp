// [camera] settings through the real config loader (fsw/io), and the buffer-to-view rules of mono_view.hpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "visnav/camera/camera_params.hpp"
#include "visnav/camera/mono_view.hpp"
#include "visnav/io/config_io.hpp"

namespace visnav::camera {
namespace {

/// Writes `text` to a fresh temporary TOML file and loads [camera] from it.
LoadError load(const std::string& text, CameraParams& params) {
  const std::string path = ::testing::TempDir() + "camera_params_" + std::to_string(::getpid()) + ".toml";
  std::ofstream(path) << text;
  io::ConfigFile config;
  LoadError error = config.open(path);
  if (error.ok) error = config.apply(params);
  if (error.ok) error = config.checkNoUnknownKeys();
  std::remove(path.c_str());
  return error;
}

TEST(CameraParams, DefaultsNeedNoHardware) {
  const CameraParams params;
  EXPECT_EQ(params.driverKind(), CameraDriver::kSynthetic);
  EXPECT_EQ(params.crossCheck(), nullptr);
  EXPECT_EQ(params.acquireTimeoutNs(), 100000000);
}

TEST(CameraParams, EveryKeyLoads) {
  CameraParams params;
  const LoadError error = load(
      "[camera]\ndriver = \"v4l2\"\ndevice = \"/dev/video2\"\nwidth_px = 1280\nheight_px = 720\n"
      "pixel_format = \"y10\"\nfps_hz = 7.5\nbuffer_count = 6\nacquire_timeout_ms = 50\nrecovery_attempts = "
      "3\n"
      "libcamera_role = \"raw\"\n",
      params);
  ASSERT_TRUE(error.ok) << error.message;
  EXPECT_EQ(params.driverKind(), CameraDriver::kV4l2);
  EXPECT_EQ(params.device, "/dev/video2");
  EXPECT_EQ(params.width_px, 1280);
  EXPECT_EQ(params.height_px, 720);
  EXPECT_EQ(params.format(), RequestedFormat::kY10);
  EXPECT_DOUBLE_EQ(params.fps_hz, 7.5);
  EXPECT_EQ(params.buffer_count, 6);
  EXPECT_EQ(params.acquireTimeoutNs(), 50000000);
  EXPECT_EQ(params.recovery_attempts, 3);
  EXPECT_EQ(params.libcamera_role, static_cast<int>(LibcameraRole::kRaw));
}

TEST(CameraParams, ErrorsNameLineKeyAndProblem) {
  CameraParams params;
  LoadError error = load("[camera]\ndriver = \"v4l2\"\ndevice = 3\n", params);
  ASSERT_FALSE(error.ok);
  EXPECT_NE(error.message.find(":3: [camera] device must be a string"), std::string::npos) << error.message;
  error = load("[camera]\npixel_format = \"rgb\"\n", params);
  EXPECT_NE(error.message.find("'rgb' is not one of: grey|y10|y12|y16|yuyv"), std::string::npos)
      << error.message;
  error = load("[camera]\nbuffer_count = 64\n", params);
  EXPECT_NE(error.message.find("buffer_count = 64 is outside [2, 32]"), std::string::npos) << error.message;
  error = load("[camera]\ndevise = \"/dev/video0\"\n", params);
  EXPECT_NE(error.message.find("unknown key [camera] devise"), std::string::npos) << error.message;
  error = load("[camera]\ndriver = \"v4l2\"\n", params);
  EXPECT_NE(error.message.find("device must name the V4L2 node"), std::string::npos) << error.message;
  error = load("[camera]\ndriver = \"libcamera\"\npixel_format = \"y16\"\n", params);
  EXPECT_NE(error.message.find("no libcamera 0.0.3 equivalent"), std::string::npos) << error.message;
  EXPECT_EQ(params.driverKind(), CameraDriver::kSynthetic);  // a failed load leaves the struct untouched
}

TEST(MonoView, YuyvLumaIgnoresChromaAndRowPadding) {
  // 3 x 2 pixels, rows of 8 bytes (6 used + 2 padding): Y0 U Y1 V Y2 U | pad pad
  const std::array<std::uint8_t, 16> yuyv = {10, 200, 11, 201, 12, 202, 99, 99,
                                             20, 210, 21, 211, 22, 212, 99, 99};
  std::array<std::uint8_t, 6> luma{};
  const MonoImage image = extractLumaYuyv(yuyv.data(), 3, 2, 8, luma.data());
  EXPECT_EQ(image.depth, MonoImage::Depth::kU8);
  EXPECT_EQ(image.u8.strideBytes(), 3);
  EXPECT_EQ(luma, (std::array<std::uint8_t, 6>{10, 11, 12, 20, 21, 22}));
}

TEST(MonoView, SixteenBitViewsReadLittleEndianWordsWithTheStride) {
  alignas(2) const std::array<std::uint8_t, 12> y10 = {0xFF, 0x03, 0x01, 0x00, 0xAA, 0xAA,   // 1023, 1, pad
                                                       0x00, 0x02, 0x10, 0x00, 0xAA, 0xAA};  // 512, 16, pad
  const MonoImage image = viewInPlace(PixelFormat::kY10, y10.data(), 2, 2, 6);
  ASSERT_EQ(image.depth, MonoImage::Depth::kU16);
  EXPECT_EQ(image.max_code, 1023);
  EXPECT_EQ(image.u16.at(0, 0), 1023);
  EXPECT_EQ(image.u16.at(1, 0), 1);
  EXPECT_EQ(image.u16.at(0, 1), 512);
  EXPECT_EQ(image.u16.at(1, 1), 16);
  EXPECT_TRUE(viewInPlace(PixelFormat::kYuyv, y10.data(), 2, 2, 6).empty());
}

TEST(MonoView, RgbLumaUsesIntegerBt601WeightsInEveryByteOrder) {
  // 2 x 1 pixels: pure red, then a grey (90, 90, 90); rows of 8 bytes (6 used + padding).
  const std::array<std::uint8_t, 8> rgb = {255, 0, 0, 90, 90, 90, 7, 7};   // R, G, B in memory (BGR888)
  const std::array<std::uint8_t, 8> bgr = {0, 0, 255, 90, 90, 90, 7, 7};   // B, G, R in memory (RGB888)
  const std::array<std::uint8_t, 8> xrgb = {0, 0, 255, 0, 90, 90, 90, 0};  // B, G, R, X (XRGB8888)
  std::array<std::uint8_t, 2> luma{};
  const std::uint8_t red = (77 * 255 + 128) >> 8;  // 77
  extractLumaRgb(rgb.data(), 2, 1, 8, PackedRgbLayout{3, 0, 1, 2}, luma.data());
  EXPECT_EQ(luma, (std::array<std::uint8_t, 2>{red, 90}));
  extractLumaRgb(bgr.data(), 2, 1, 8, PackedRgbLayout{3, 2, 1, 0}, luma.data());
  EXPECT_EQ(luma, (std::array<std::uint8_t, 2>{red, 90}));
  const MonoImage image = extractLumaRgb(xrgb.data(), 2, 1, 8, PackedRgbLayout{4, 2, 1, 0}, luma.data());
  EXPECT_EQ(luma, (std::array<std::uint8_t, 2>{red, 90}));
  EXPECT_EQ(image.u8.strideBytes(), 2);
  // White stays 255 and every grey stays itself: the weights sum to 256.
  for (int v = 0; v < 256; ++v) {
    const std::array<std::uint8_t, 3> grey = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v),
                                              static_cast<std::uint8_t>(v)};
    extractLumaRgb(grey.data(), 1, 1, 3, PackedRgbLayout{}, luma.data());
    ASSERT_EQ(luma[0], v);
  }
}

TEST(MonoView, BufferSizeRules) {
  EXPECT_EQ(minimumBufferBytes(PixelFormat::kGrey8, 640, 480, 640), 640U * 480U);
  EXPECT_EQ(minimumBufferBytes(PixelFormat::kY16, 640, 480, 1300), 1300U * 479U + 1280U);
  EXPECT_EQ(minimumBufferBytes(PixelFormat::kYuyv, 4, 1, 8), 8U);
  EXPECT_EQ(maxCode(PixelFormat::kY12), 4095);
  EXPECT_FALSE(isZeroCopy(PixelFormat::kYuyv));
  EXPECT_TRUE(isZeroCopy(PixelFormat::kY16));
}

}  // namespace
}  // namespace visnav::camera
