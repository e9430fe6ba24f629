#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../png/png_decode.hpp"
#include "visnav/eval/canvas.hpp"
#include "visnav/eval/plot.hpp"

namespace visnav::eval {
namespace {

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
  const test::DecodedPng png = test::decodePng(test::readBinaryFile(path));  // CRCs, inflate, unfilter
  ASSERT_TRUE(png.ok) << png.error;
  EXPECT_EQ(png.width, 3U * PlotOptions{}.panel_width_px);
  EXPECT_EQ(png.rgb, renderErrorPlot(ev).rgb());
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
