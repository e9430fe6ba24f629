#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "visnav/eval/canvas.hpp"
#include "visnav/eval/plot.hpp"
#include "visnav/eval/png_writer.hpp"

namespace visnav::eval {
namespace {

std::uint32_t readU32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24U) | (std::uint32_t{b[at + 1]} << 16U) |
         (std::uint32_t{b[at + 2]} << 8U) | b[at + 3];
}

// Walks the chunks, checks every CRC with zlib's crc32, returns IHDR fields and the inflated IDAT payload.
void decodePng(const std::vector<std::uint8_t>& png, std::uint32_t& width, std::uint32_t& height,
               std::vector<std::uint8_t>& raw) {
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  ASSERT_GE(png.size(), 8U);
  ASSERT_TRUE(std::equal(signature, signature + 8, png.begin()));
  std::size_t at = 8;
  std::vector<std::uint8_t> idat;
  bool end = false;
  while (at + 12 <= png.size() && !end) {
    const std::uint32_t len = readU32(png, at);
    ASSERT_LE(at + 12 + len, png.size());
    const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                           png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    const uLong crc = ::crc32(0L, png.data() + at + 4, static_cast<uInt>(len + 4));
    EXPECT_EQ(crc, readU32(png, at + 8 + len)) << type;
    if (type == "IHDR") {
      ASSERT_EQ(len, 13U);
      width = readU32(png, at + 8);
      height = readU32(png, at + 12);
      EXPECT_EQ(png[at + 16], 8);  // bit depth
      EXPECT_EQ(png[at + 17], 2);  // RGB
    } else if (type == "IDAT") {
      idat.insert(idat.end(), png.begin() + static_cast<std::ptrdiff_t>(at + 8),
                  png.begin() + static_cast<std::ptrdiff_t>(at + 8 + len));
    }
    end = type == "IEND";
    at += 12 + len;
  }
  EXPECT_TRUE(end);
  EXPECT_EQ(at, png.size());
  raw.assign((width * 3U + 1U) * height, 0);
  uLongf raw_len = static_cast<uLongf>(raw.size());
  ASSERT_EQ(uncompress(raw.data(), &raw_len, idat.data(), static_cast<uLong>(idat.size())), Z_OK);
  EXPECT_EQ(raw_len, raw.size());
}

TEST(Png, ChecksumsMatchZlib) {
  const std::string s = "123456789";
  const auto* d = reinterpret_cast<const std::uint8_t*>(s.data());
  EXPECT_EQ(crc32(d, s.size()), 0xCBF43926U);  // the CRC-32 check value
  EXPECT_EQ(adler32(d, s.size()), ::adler32(1L, d, static_cast<uInt>(s.size())));
}

TEST(Png, SmallAndMultiBlockImagesDecode) {
  for (const int w : {3, 211}) {
    const int h = w == 3 ? 2 : 157;  // 211 x 157 x 3 > 65535: several stored blocks
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>(i * 7 + 3);
    const std::vector<std::uint8_t> png = encodePngRgb(w, h, rgb);
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> raw;
    decodePng(png, width, height, raw);
    ASSERT_EQ(width, static_cast<std::uint32_t>(w));
    ASSERT_EQ(height, static_cast<std::uint32_t>(h));
    for (int y = 0; y < h; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * (w * 3 + 1);
      ASSERT_EQ(raw[row], 0);  // filter type none
      ASSERT_TRUE(std::equal(rgb.begin() + y * w * 3, rgb.begin() + (y + 1) * w * 3, raw.begin() + row + 1));
    }
  }
}

TEST(Canvas, TextLinesAndClipping) {
  Canvas c(60, 20, {255, 255, 255});
  c.text(1, 1, "-0.5", {0, 0, 0});
  // '-' is the middle row of the first glyph.
  EXPECT_EQ(c.pixel(1, 4).r, 0);
  EXPECT_EQ(c.pixel(1, 1).r, 255);
  EXPECT_EQ(Canvas::textWidth("-0.5"), 24);
  c.setClip(0, 0, 30, 20);
  c.line(0, 15, 59, 15, {255, 0, 0});
  c.resetClip();
  EXPECT_EQ(c.pixel(10, 15).g, 0);
  EXPECT_EQ(c.pixel(40, 15).g, 255);     // clipped away
  c.line(-1e9, 0, 1e9, 0, {0, 0, 255});  // far outside: bounded, no crash
  EXPECT_EQ(c.pixel(30, 0).b, 255);
  EXPECT_EQ(c.pixel(30, 0).r, 0);
}

TEST(Plot, NiceTicks) {
  int decimals = -1;
  const std::vector<double> t = niceTicks(-0.023, 0.023, 6, decimals);
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(decimals, 2);
  EXPECT_NEAR(t.front(), -0.02, 1e-12);
  EXPECT_NEAR(t.back(), 0.02, 1e-12);
  const std::vector<double> d = niceTicks(5.0, 25.0, 6, decimals);
  EXPECT_EQ(decimals, 0);
  EXPECT_EQ(d.size(), 5U);  // 5 10 15 20 25
}

TEST(Plot, WritesAValidPng) {
  Evaluation ev;
  ev.envelope_px = {1.0};
  for (int i = 0; i < 50; ++i) {
    FrameRecord f;
    f.frame = i;
    f.distance_m = 5.0 + 0.4 * i;
    f.status = i == 10 ? TrackStatus::kLost : TrackStatus::kTracking;
    f.scored = i != 10;
    for (int a = 0; a < kAxisCount; ++a) f.error[a] = 0.001 * f.distance_m * ((i % 3) - 1);
    FrameEnvelope e;
    e.valid = true;
    for (int a = 0; a < kAxisCount; ++a) e.max_abs[a] = 0.002 * f.distance_m;
    f.envelopes = {e};
    f.inside = {1};
    ev.frames.push_back(f);
  }
  const std::string path = ::testing::TempDir() + "visnav_eval_plot.png";
  ASSERT_TRUE(writeErrorPlot(path, ev).ok);
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> raw;
  decodePng(png, width, height, raw);
  EXPECT_EQ(width, 3U * PlotOptions{}.panel_width_px);
  std::remove(path.c_str());
}

// Frames 0..7: standby, 3 far range (far errors), acquisition, 3 near range (frame 6 lost).
Evaluation modeTimelineFixture() {
  Evaluation ev;
  const ReplayMode modes[8] = {ReplayMode::kStandby,   ReplayMode::kFarRange,    ReplayMode::kFarRange,
                               ReplayMode::kFarRange,  ReplayMode::kAcquisition, ReplayMode::kNearRange,
                               ReplayMode::kNearRange, ReplayMode::kNearRange};
  for (int i = 0; i < 8; ++i) {
    FrameRecord f;
    f.frame = i;
    f.distance_m = 100.0 - 10.0 * i;
    f.mode = modes[i];
    f.status = i == 6 ? TrackStatus::kLost : (i >= 5 ? TrackStatus::kTracking : TrackStatus::kInit);
    f.far_scored = f.mode == ReplayMode::kFarRange;
    f.far_error = {0.01 * i, 2.0 * i - 5.0};
    ev.frames.push_back(f);
  }
  return ev;
}

TEST(Plot, ModeTimelineLanes) {
  const Evaluation ev = modeTimelineFixture();
  const int width = 1000;
  const Canvas c = renderModeTimeline(ev, width);
  ASSERT_EQ(c.height(), kTimelineHeightPx);
  // Plot area x [170, width - 32), y [34, 240 - 74); frame k spans k +- 0.5 of [-0.5, 7.5]; lane m (0 standby
  // ... 3 near range) spans y values [m, m + 1] of [0, 4], y = 165 - v / 4 * 131. Probes sit 0.3 frame off
  // the centres, where the grid lines of the frame ticks are.
  const auto x = [&](double frame) {
    return static_cast<int>(170 + (frame + 0.8) / 8.0 * (width - 32 - 170 - 1));
  };
  const auto y = [](double lane_centre) { return static_cast<int>(165 - lane_centre / 4.0 * 131); };
  const auto is = [](Rgb p, Rgb q) { return p.r == q.r && p.g == q.g && p.b == q.b; };
  const Rgb grey{150, 150, 150}, blue{30, 90, 200}, orange{240, 150, 0}, green{0, 150, 60},
      white{255, 255, 255};
  EXPECT_TRUE(is(c.pixel(x(0), y(0.5)), grey));
  EXPECT_TRUE(is(c.pixel(x(0), y(1.5)), white));
  EXPECT_TRUE(is(c.pixel(x(2), y(1.5)), blue));
  EXPECT_TRUE(is(c.pixel(x(4), y(2.5)), orange));
  EXPECT_TRUE(is(c.pixel(x(4), y(3.5)), white));
  EXPECT_TRUE(is(c.pixel(x(7), y(3.5)), green));
  EXPECT_TRUE(is(c.pixel(x(7), y(0.5)), white));
  const int lost_x = static_cast<int>(std::lround(170 + 6.5 / 8.0 * (width - 32 - 170 - 1)));
  EXPECT_TRUE(is(c.pixel(lost_x, 163), Rgb{120, 120, 120}));  // frame 6 lost: grey tick on the bottom axis
}

TEST(Plot, PosePanelsLeaveOutFarRangeFramesWithoutAPose) {
  Evaluation ev = modeTimelineFixture();
  // Acquisition and near range (frames 4..7, 70 m down to 40 m), nearest first; frame 6 is lost but shown.
  EXPECT_EQ(posePanelFrames(ev), (std::vector<std::size_t>{7, 6, 5, 4}));
  ev.frames[2].scored = true;  // a far-range frame that carries a pose is scored, so shown
  EXPECT_EQ(posePanelFrames(ev), (std::vector<std::size_t>{7, 6, 5, 4, 2}));
  for (FrameRecord& f : ev.frames) f.mode = ReplayMode::kUnknown;  // no mode column: every frame
  EXPECT_EQ(posePanelFrames(ev), (std::vector<std::size_t>{7, 6, 5, 4, 3, 2, 1, 0}));
  for (FrameRecord& f : ev.frames) {
    f.mode = ReplayMode::kFarRange;  // never left far range: every frame rather than none
    f.scored = false;
  }
  EXPECT_EQ(posePanelFrames(ev).size(), 8U);
}

TEST(Plot, FarRangeAndTimelineRowsOnlyWhenPresent) {
  Evaluation ev = modeTimelineFixture();
  const PlotOptions o;
  EXPECT_EQ(renderErrorPlot(ev, o).height(), 44 + 3 * o.panel_height_px + kTimelineHeightPx);
  for (FrameRecord& f : ev.frames) f.far_scored = false;
  EXPECT_EQ(renderErrorPlot(ev, o).height(), 44 + 2 * o.panel_height_px + kTimelineHeightPx);
  for (FrameRecord& f : ev.frames) f.mode = ReplayMode::kUnknown;
  EXPECT_EQ(renderErrorPlot(ev, o).height(), 44 + 2 * o.panel_height_px);  // an old replay: the old plot
}

}  // namespace
}  // namespace visnav::eval
