// The rest of visnav_core: Status and PixelFormat names, ImageView strides, MonoImage dispatch.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <set>
#include <string>

#include "visnav/core/frame.hpp"
#include "visnav/core/image_view.hpp"
#include "visnav/core/status.hpp"

namespace visnav {
namespace {

TEST(Status, EveryValueHasADistinctName) {
  const Status all[] = {
      Status::kOk,           Status::kInvalidArgument, Status::kCapacityExceeded, Status::kNotEnoughData,
      Status::kNotConverged, Status::kGaveUp,          Status::kDegenerate,       Status::kOutOfImage};
  std::set<std::string> names;
  for (const Status status : all) {
    const std::string name = toString(status);
    EXPECT_NE(name, "unknown");
    EXPECT_FALSE(name.empty());
    names.insert(name);
  }
  EXPECT_EQ(names.size(), sizeof(all) / sizeof(all[0]));
  EXPECT_STREQ(toString(Status::kOk), "ok");
  EXPECT_STREQ(toString(Status::kNotConverged), "not converged");
  EXPECT_STREQ(toString(Status::kGaveUp), "gave up");
  EXPECT_STREQ(toString(static_cast<Status>(250)), "unknown");
}

TEST(LoadError, SuccessAndFailure) {
  const LoadError ok = LoadError::success();
  EXPECT_TRUE(ok.ok);
  EXPECT_TRUE(ok.message.empty());
  const LoadError bad = LoadError::failure("camera.toml:3: fx must be > 0");
  EXPECT_FALSE(bad.ok);
  EXPECT_EQ(bad.message, "camera.toml:3: fx must be > 0");
}

TEST(PixelFormat, Names) {
  EXPECT_STREQ(toString(PixelFormat::kGrey8), "GREY");
  EXPECT_STREQ(toString(PixelFormat::kY10), "Y10");
  EXPECT_STREQ(toString(PixelFormat::kY12), "Y12");
  EXPECT_STREQ(toString(PixelFormat::kY16), "Y16");
  EXPECT_STREQ(toString(PixelFormat::kYuyv), "YUYV");
  EXPECT_STREQ(toString(static_cast<PixelFormat>(99)), "unknown");
}

TEST(ImageView, DefaultIsEmpty) {
  const ImageView8 view;
  EXPECT_TRUE(view.empty());
  EXPECT_EQ(view.width(), 0);
  EXPECT_EQ(view.height(), 0);
  EXPECT_EQ(view.data(), nullptr);
  EXPECT_FALSE(view.contains(0, 0));
}

TEST(ImageView, PackedRowsUseWidthTimesPixelSize) {
  std::array<std::uint16_t, 12> pixels{};
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint16_t>(1000 + i);
  const ImageView16 view(pixels.data(), 4, 3);
  EXPECT_FALSE(view.empty());
  EXPECT_EQ(view.strideBytes(), 8);
  EXPECT_EQ(view.row(2), pixels.data() + 8);
  EXPECT_EQ(view.at(3, 1), 1007);
  EXPECT_EQ(view.at(0, 2), 1008);
}

TEST(ImageView, PaddedStrideSkipsThePadding) {
  // 3 x 2 pixels, 5-byte rows: two padding bytes (0xEE) per row are never read as pixels.
  const std::array<std::uint8_t, 10> bytes = {1, 2, 3, 0xEE, 0xEE, 4, 5, 6, 0xEE, 0xEE};
  const ImageView8 view(bytes.data(), 3, 2, 5);
  EXPECT_EQ(view.strideBytes(), 5);
  EXPECT_EQ(view.at(0, 1), 4);
  EXPECT_EQ(view.at(2, 1), 6);
  int sum = 0;
  for (int y = 0; y < view.height(); ++y)
    for (int x = 0; x < view.width(); ++x) sum += view.at(x, y);
  EXPECT_EQ(sum, 21);
}

TEST(ImageView, SixteenBitStrideIsInBytes) {
  // 2 x 2 words with a 6-byte stride (one padding word per row).
  const std::array<std::uint16_t, 6> words = {10, 11, 0xFFFF, 20, 21, 0xFFFF};
  const ImageView16 view(words.data(), 2, 2, 6);
  EXPECT_EQ(view.at(1, 0), 11);
  EXPECT_EQ(view.at(0, 1), 20);
  EXPECT_EQ(view.at(1, 1), 21);
}

TEST(ImageView, ContainsChecksBothAxes) {
  const std::array<std::uint8_t, 6> bytes{};
  const ImageView8 view(bytes.data(), 3, 2);
  EXPECT_TRUE(view.contains(0, 0));
  EXPECT_TRUE(view.contains(2, 1));
  EXPECT_FALSE(view.contains(3, 0));
  EXPECT_FALSE(view.contains(0, 2));
  EXPECT_FALSE(view.contains(-1, 0));
  EXPECT_FALSE(view.contains(0, -1));
  EXPECT_TRUE(ImageView8(bytes.data(), 0, 2).empty());
  EXPECT_TRUE(ImageView8(bytes.data(), 3, 0).empty());
}

TEST(MonoImage, DispatchesOnTheDepth) {
  const std::array<std::uint8_t, 6> bytes{};
  const std::array<std::uint16_t, 20> words{};
  const MonoImage eight = MonoImage::from8(ImageView8(bytes.data(), 3, 2));
  EXPECT_EQ(eight.depth, MonoImage::Depth::kU8);
  EXPECT_EQ(eight.width(), 3);
  EXPECT_EQ(eight.height(), 2);
  EXPECT_EQ(eight.max_code, 255);
  EXPECT_FALSE(eight.empty());
  const MonoImage sixteen = MonoImage::from16(ImageView16(words.data(), 5, 4), 1023);
  EXPECT_EQ(sixteen.depth, MonoImage::Depth::kU16);
  EXPECT_EQ(sixteen.width(), 5);
  EXPECT_EQ(sixteen.height(), 4);
  EXPECT_EQ(sixteen.max_code, 1023);
  EXPECT_FALSE(sixteen.empty());
  EXPECT_TRUE(MonoImage{}.empty());
}

}  // namespace
}  // namespace visnav
