// tools/png, the one PNG writer: what it writes decodes (every CRC checked and the IDAT inflated by zlib, the
// row filters undone by an independent reader) to exactly the pixels given, and a plot is compressed: the
// campaign and closedloop plots, written by their own code, stay far below their raw size (the stored-block
// encoder before wrote 4.8 MB and 6.3 MB).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "png_decode.hpp"
#include "visnav/campaign/report.hpp"
#include "visnav/closedloop/report.hpp"
#include "visnav/core/rng.hpp"
#include "visnav/png/png_writer.hpp"

namespace visnav::png {
namespace {

std::string tempPath(const char* name) { return ::testing::TempDir() + "visnav_png_" + name; }

TEST(PngWriter, PixelsSurviveTheRoundTrip) {
  // 3 x 2; a gradient; and noise deflate cannot shrink (211 x 157 x 3 > 64 KiB, beyond one stored block).
  Pcg32 rng(7U);
  for (const int w : {3, 640, 211}) {
    const int h = w == 3 ? 2 : (w == 640 ? 48 : 157);
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i)
      rgb[i] = w == 211 ? static_cast<std::uint8_t>(rng.next()) : static_cast<std::uint8_t>(i * 7 + i / 1920);
    std::vector<std::uint8_t> file;
    ASSERT_TRUE(encodeRgb(w, h, rgb, file).ok);
    const test::DecodedPng d = test::decodePng(file);
    ASSERT_TRUE(d.ok) << d.error;
    EXPECT_EQ(d.width, static_cast<std::uint32_t>(w));
    EXPECT_EQ(d.height, static_cast<std::uint32_t>(h));
    EXPECT_EQ(d.chunks, 3);  // IHDR, IDAT, IEND
    EXPECT_EQ(d.rgb, rgb) << w << " x " << h;
  }
}

TEST(PngWriter, RefusesSizesThatDoNotMatchAndUnwritablePaths) {
  std::vector<std::uint8_t> file;
  EXPECT_FALSE(encodeRgb(0, 1, {}, file).ok);
  EXPECT_FALSE(encodeRgb(2, 2, std::vector<std::uint8_t>(11), file).ok);
  const LoadError e = writeRgb("/nonexistent-dir/x.png", 1, 1, {1, 2, 3});
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("/nonexistent-dir/x.png"), std::string::npos) << e.message;
}

TEST(PngWriter, ClosedloopPlotDecodesAndIsCompressed) {
  // Two 900 s runs at 5 Hz (4500 frames), closing from 200 m with the mode changes of a real approach.
  closedloop::ScenarioParams params;
  closedloop::RunResult visnav, truth;
  for (int i = 0; i <= 4500; ++i) {
    closedloop::FrameLog f;
    f.t_s = 0.2 * i;
    f.range_m = 5.0 + 195.0 * std::exp(-f.t_s / 150.0);
    f.position_error_m = f.range_m - 5.0 + 0.01 * std::sin(f.t_s);
    f.attitude_error_deg = 20.0 * std::exp(-f.t_s / 100.0);
    f.delta_v_m_s = 0.002 * f.t_s;
    f.mode = f.range_m > 30.0 ? 1 : (f.range_m > 28.0 ? 2 : 3);
    visnav.frames.push_back(f);
    f.mode = -1;
    truth.frames.push_back(f);
  }
  const std::string path = tempPath("closedloop.png");
  ASSERT_TRUE(closedloop::writePlot(path, params, visnav, truth).ok);
  const std::vector<std::uint8_t> file = test::readBinaryFile(path);
  const test::DecodedPng d = test::decodePng(file);
  ASSERT_TRUE(d.ok) << d.error;
  EXPECT_EQ(d.width, 1400U);
  const std::size_t raw_bytes = static_cast<std::size_t>(d.width) * d.height * 3U;
  EXPECT_GT(raw_bytes, 6000000U);
  // Stored blocks were raw + 0.1 %; zlib with filter Up writes ~25 KB of a real run's plot.
  EXPECT_LT(file.size(), 150000U) << "closedloop.png of " << raw_bytes << " raw bytes: " << file.size();
  std::remove(path.c_str());
}

TEST(PngWriter, CampaignPlotDecodesToItsCanvasAndIsCompressed) {
  std::vector<campaign::GroupSummary> groups(3);
  groups[0].name = "overall";
  groups[1].name = "plate";
  groups[1].scenes = 4;
  groups[2].name = "box";
  groups[2].scenes = 4;
  groups[2].wrong = 2;
  groups[2].wrong_scenes = 1;
  const eval::Canvas canvas = campaign::renderCampaignPlot({}, groups, campaign::Gates{});
  const std::string path = tempPath("campaign.png");
  ASSERT_TRUE(canvas.writePng(path).ok);
  const std::vector<std::uint8_t> file = test::readBinaryFile(path);
  const test::DecodedPng d = test::decodePng(file);
  ASSERT_TRUE(d.ok) << d.error;
  ASSERT_EQ(d.width, static_cast<std::uint32_t>(canvas.width()));
  ASSERT_EQ(d.height, static_cast<std::uint32_t>(canvas.height()));
  EXPECT_EQ(d.rgb, canvas.rgb());
  EXPECT_LT(file.size() * 50U, canvas.rgb().size()) << "campaign.png: " << file.size() << " bytes";
  std::remove(path.c_str());
}

}  // namespace
}  // namespace visnav::png
