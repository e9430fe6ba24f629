// The far-range error panels and the mode timeline of visnav-eval's plot (plot_parts.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "plot_parts.hpp"
#include "visnav/eval/plot.hpp"

namespace visnav::eval {
namespace plot_parts {
namespace {

// Indexed by ReplayMode: standby grey, far range blue, acquisition orange, near range green.
constexpr Rgb kModeColours[kReplayModeCount] = {{150, 150, 150}, {30, 90, 200}, {240, 150, 0}, {0, 150, 60}};

// Upper end of an axis over |values|: 1.15 x their 99th percentile, so one outlier cannot flatten the rest.
double bulkRange(std::vector<double> values) {
  for (double& v : values) v = std::fabs(v);
  std::sort(values.begin(), values.end());
  const double r = 1.15 * percentileSorted(values, 0.99);
  return r > 0.0 && std::isfinite(r) ? r : 1.0;
}

// One far-range panel: dots at (truth distance, value) in the frame's mode colour, magenta when clipped.
void drawFarPanel(Canvas& c, const Evaluation& ev, const PlotArea& f, bool distance_error) {
  c.setClip(f.left, f.top, f.right, f.bottom);
  for (const FrameRecord& r : ev.frames) {
    if (!r.far_scored) continue;
    const double value = distance_error ? r.far_error.distance_pct : r.far_error.direction_deg;
    const double shown = std::clamp(value, f.y_lo, f.y_hi);
    c.dot(f.px(r.distance_m), f.py(shown), 1, shown == value ? modeColour(r.mode) : kClipped);
  }
  c.resetClip();
  c.rect(f.left - 1, f.top - 1, f.right + 1, f.bottom + 1, kBlack);
}

// Truth distance of the frame nearest to `frame` (frames in any order).
double distanceAtFrame(const Evaluation& ev, double frame) {
  double best = 0.0, best_gap = -1.0;
  for (const FrameRecord& r : ev.frames) {
    const double gap = std::fabs(static_cast<double>(r.frame) - frame);
    if (best_gap < 0.0 || gap < best_gap) {
      best_gap = gap;
      best = r.distance_m;
    }
  }
  return best;
}

}  // namespace

Rgb modeColour(ReplayMode mode) {
  const auto i = static_cast<std::size_t>(mode);
  return i < static_cast<std::size_t>(kReplayModeCount) ? kModeColours[i] : kError;
}

bool hasFarRange(const Evaluation& ev) {
  return std::any_of(ev.frames.begin(), ev.frames.end(), [](const FrameRecord& r) { return r.far_scored; });
}

bool hasModes(const Evaluation& ev) {
  return std::any_of(ev.frames.begin(), ev.frames.end(),
                     [](const FrameRecord& r) { return r.mode != ReplayMode::kUnknown; });
}

void drawFarRangePanels(Canvas& c, const Evaluation& ev, int x0, int y0, int width, int height) {
  double x_lo = 0.0, x_hi = 0.0;
  bool first = true;
  std::vector<double> direction, distance;
  for (const FrameRecord& r : ev.frames) {
    if (!r.far_scored) continue;
    x_lo = first ? r.distance_m : std::min(x_lo, r.distance_m);
    x_hi = first ? r.distance_m : std::max(x_hi, r.distance_m);
    first = false;
    direction.push_back(r.far_error.direction_deg);
    distance.push_back(r.far_error.distance_pct);
  }
  if (!(x_hi > x_lo)) {
    x_lo -= 0.5;
    x_hi += 0.5;
  }
  const int w = width / 2;
  const PlotArea dir{x0 + 100, y0 + 34, x0 + w - 32, y0 + height - 52, x_lo, x_hi, 0.0, bulkRange(direction)};
  drawAxes(c, dir, "far-range direction error [deg] (colour: mode)", y0 + 10, "distance [m]");
  drawFarPanel(c, ev, dir, false);
  const double half = bulkRange(distance);
  const PlotArea dist{x0 + w + 100, y0 + 34, x0 + width - 32, y0 + height - 52, x_lo, x_hi, -half, half};
  drawAxes(c, dist, "far-range distance error [%] (colour: mode)", y0 + 10, "distance [m]");
  drawFarPanel(c, ev, dist, true);
}

void drawModeTimeline(Canvas& c, const Evaluation& ev, int x0, int y0, int width, int height) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < ev.frames.size(); ++i) {
    const auto frame = static_cast<double>(ev.frames[i].frame);
    lo = i == 0 ? frame : std::min(lo, frame);
    hi = i == 0 ? frame : std::max(hi, frame);
  }
  // Each frame fills [frame - 0.5, frame + 0.5); lanes are 0 (standby) at the bottom to 3 (near range).
  const PlotArea f{x0 + 170,
                   y0 + 34,
                   x0 + width - 32,
                   y0 + height - 74,
                   lo - 0.5,
                   hi + 0.5,
                   0.0,
                   static_cast<double>(kReplayModeCount)};
  const std::string title = "mode timeline";
  c.text(f.left + (f.right - f.left - Canvas::textWidth(title, kText)) / 2, y0 + 10, title, kBlack, kText);
  for (int m = 0; m < kReplayModeCount; ++m) {
    const auto mode = static_cast<ReplayMode>(m);
    const std::string name = toString(mode);
    const int lane_top = static_cast<int>(f.py(m + 1.0));
    const int lane_bottom = static_cast<int>(f.py(static_cast<double>(m)));
    c.text(f.left - 10 - Canvas::textWidth(name, kText), (lane_top + lane_bottom) / 2 - 7, name,
           modeColour(mode), kText);
    if (m > 0) c.line(f.left, lane_bottom, f.right - 1, lane_bottom, kGrid);
  }
  int decimals = 0;
  for (double t : niceTicks(lo, hi, 8, decimals)) {
    if (t != std::floor(t)) continue;  // frame numbers only
    const double x = f.px(t);
    c.line(x, f.top, x, f.bottom - 1, kGrid);
    c.line(x, f.bottom, x, f.bottom + 5, kBlack);
    const std::string label = formatTick(t, 0);
    c.text(static_cast<int>(x) - Canvas::textWidth(label, kText) / 2, f.bottom + 9, label, kBlack, kText);
    const double d = distanceAtFrame(ev, t);
    const std::string metres = formatTick(d, d < 10.0 ? 1 : 0) + " m";
    c.text(static_cast<int>(x) - Canvas::textWidth(metres, kText) / 2, f.bottom + 30, metres, kZero, kText);
  }
  const std::string xlabel = "frame (grey: truth distance)";
  c.text(f.left + (f.right - f.left - Canvas::textWidth(xlabel, kText)) / 2, f.bottom + 52, xlabel, kBlack,
         kText);

  c.setClip(f.left, f.top, f.right, f.bottom);
  for (const FrameRecord& r : ev.frames) {
    const auto frame = static_cast<double>(r.frame);
    if (r.status == TrackStatus::kLost || r.status == TrackStatus::kMissing)
      c.line(f.px(frame), f.bottom - 8, f.px(frame), f.bottom - 1, kLost);
    if (r.mode == ReplayMode::kUnknown) continue;
    const auto m = static_cast<double>(r.mode);
    const int left = static_cast<int>(std::floor(f.px(frame - 0.5)));
    const int right = std::max(static_cast<int>(std::floor(f.px(frame + 0.5))), left + 1);
    c.fillRect(left, static_cast<int>(f.py(m + 1.0)) + 4, right, static_cast<int>(f.py(m)) - 3,
               modeColour(r.mode));
  }
  c.resetClip();
  c.rect(f.left - 1, f.top - 1, f.right + 1, f.bottom + 1, kBlack);
}

}  // namespace plot_parts

Canvas renderModeTimeline(const Evaluation& ev, int width_px) {
  Canvas c(width_px, kTimelineHeightPx, plot_parts::kWhite);
  plot_parts::drawModeTimeline(c, ev, 0, 0, width_px, kTimelineHeightPx);
  return c;
}

LoadError writeModeTimeline(const std::string& path, const Evaluation& ev, int width_px) {
  return renderModeTimeline(ev, width_px).writePng(path);
}

}  // namespace visnav::eval
