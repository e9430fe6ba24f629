#include "visnav/eval/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numeric>

#include "plot_parts.hpp"

namespace visnav::eval {

namespace plot_parts {

std::string formatTick(double v, int decimals) {
  char buf[32];
  if (std::fabs(v) < 1e-12) v = 0.0;  // no "-0.00"
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

void drawAxes(Canvas& c, const PlotArea& f, const std::string& title, int title_y,
              const std::string& xlabel) {
  c.text(f.left + (f.right - f.left - Canvas::textWidth(title, kText)) / 2, title_y, title, kBlack, kText);
  int decimals = 0;
  for (double t : niceTicks(f.y_lo, f.y_hi, 6, decimals)) {
    const double y = f.py(t);
    c.line(f.left, y, f.right - 1, y, std::fabs(t) < 1e-15 ? kZero : kGrid);
    const std::string label = formatTick(t, decimals);
    c.text(f.left - 8 - Canvas::textWidth(label, kText), static_cast<int>(y) - 7, label, kBlack, kText);
  }
  for (double t : niceTicks(f.x_lo, f.x_hi, 6, decimals)) {
    const double x = f.px(t);
    c.line(x, f.top, x, f.bottom - 1, kGrid);
    c.line(x, f.bottom, x, f.bottom + 5, kBlack);
    const std::string label = formatTick(t, decimals);
    c.text(static_cast<int>(x) - Canvas::textWidth(label, kText) / 2, f.bottom + 9, label, kBlack, kText);
  }
  c.text(f.left + (f.right - f.left - Canvas::textWidth(xlabel, kText)) / 2, f.bottom + 30, xlabel, kBlack,
         kText);
}

}  // namespace plot_parts

using namespace plot_parts;

namespace {

constexpr Rgb kEnvelope[] = {{220, 30, 30}, {240, 150, 0}, {0, 150, 60}, {140, 60, 180}};

Rgb envelopeColour(std::size_t d) { return kEnvelope[d % (sizeof(kEnvelope) / sizeof(kEnvelope[0]))]; }

// Shown in the pose panels (posePanelFrames): 750 m of far-range envelope would flatten a 25 m track.
bool inPosePanels(const FrameRecord& f) {
  return f.scored || (f.mode != ReplayMode::kFarRange && f.mode != ReplayMode::kStandby);
}

// Symmetric y half-range: envelopes and the bulk (p99) of the errors, so one outlier cannot flatten the rest.
double yHalfRange(const Evaluation& ev, int axis, const std::vector<std::size_t>& shown) {
  double env = 0.0;
  std::vector<double> errs;
  for (std::size_t i : shown) {
    const FrameRecord& f = ev.frames[i];
    for (const FrameEnvelope& e : f.envelopes)
      if (e.valid) env = std::max(env, e.max_abs[axis]);
    if (f.scored) errs.push_back(std::fabs(f.error[axis]));
  }
  std::sort(errs.begin(), errs.end());
  const double bulk = percentileSorted(errs, 0.99);
  const double r = 1.15 * std::max(env, bulk);
  return r > 0.0 && std::isfinite(r) ? r : 1.0;
}

void drawPanel(Canvas& c, const Evaluation& ev, int axis, int x0, int y0, int w, int h, double x_lo,
               double x_hi, const std::vector<std::size_t>& by_distance) {
  const double half = yHalfRange(ev, axis, by_distance);
  const PlotArea f{x0 + 100, y0 + 34, x0 + w - 32, y0 + h - 52, x_lo, x_hi, -half, half};
  drawAxes(c, f, std::string(axisName(axis)) + " error [" + axisUnit(axis) + "]", y0 + 10, "distance [m]");

  c.setClip(f.left, f.top, f.right, f.bottom);
  for (std::size_t i : by_distance) {  // lost / missing frames: grey ticks at the bottom
    const FrameRecord& r = ev.frames[i];
    if (r.status == TrackStatus::kLost || r.status == TrackStatus::kMissing)
      c.line(f.px(r.distance_m), f.bottom - 10, f.px(r.distance_m), f.bottom - 1, kLost);
  }
  for (std::size_t d = 0; d < ev.envelope_px.size(); ++d) {
    for (int sign = -1; sign <= 1; sign += 2) {
      bool have_prev = false;
      double px_prev = 0.0, py_prev = 0.0;
      for (std::size_t i : by_distance) {
        const FrameEnvelope& e = ev.frames[i].envelopes[d];
        if (!e.valid) continue;
        const double px = f.px(ev.frames[i].distance_m);
        const double py = f.py(sign * e.max_abs[axis]);
        if (have_prev) c.line(px_prev, py_prev, px, py, envelopeColour(d), 2);
        px_prev = px;
        py_prev = py;
        have_prev = true;
      }
    }
  }
  for (std::size_t i : by_distance) {
    const FrameRecord& r = ev.frames[i];
    if (!r.scored) continue;
    const double v = std::clamp(r.error[axis], -half, half);
    c.dot(f.px(r.distance_m), f.py(v), 1, v == r.error[axis] ? kError : kClipped);
  }
  c.resetClip();
  c.rect(f.left - 1, f.top - 1, f.right + 1, f.bottom + 1, kBlack);
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int target, int& decimals) {
  decimals = 0;
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || target < 1) return ticks;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  const double first = std::ceil(lo / step - 1e-9);
  for (int k = 0; k < 100; ++k) {
    const double t = (first + k) * step;
    if (t > hi + 1e-9 * step) break;
    ticks.push_back(t);
  }
  return ticks;
}

std::vector<std::size_t> posePanelFrames(const Evaluation& ev) {
  std::vector<std::size_t> by_distance(ev.frames.size());
  std::iota(by_distance.begin(), by_distance.end(), std::size_t{0});
  std::stable_sort(by_distance.begin(), by_distance.end(), [&ev](std::size_t a, std::size_t b) {
    return ev.frames[a].distance_m < ev.frames[b].distance_m;
  });
  std::vector<std::size_t> shown;
  std::copy_if(by_distance.begin(), by_distance.end(), std::back_inserter(shown),
               [&ev](std::size_t i) { return inPosePanels(ev.frames[i]); });
  return shown.empty() ? by_distance : shown;
}

Canvas renderErrorPlot(const Evaluation& ev, const PlotOptions& options) {
  const int w = options.panel_width_px;
  const int h = options.panel_height_px;
  const int legend_h = 44;
  // Below the six pose panels: the far-range panels (when a row had far_valid = 1), then the mode timeline
  // (when the replay has a mode column). An old replay CSV gives the plot it always gave.
  const int far_h = hasFarRange(ev) ? h : 0;
  const int timeline_h = hasModes(ev) ? kTimelineHeightPx : 0;
  Canvas c(3 * w, legend_h + 2 * h + far_h + timeline_h, kWhite);

  // Legend strip: title, then one swatch per series.
  int x = 16;
  c.text(x, 14, options.title, kBlack, kText);
  x += Canvas::textWidth(options.title, kText) + 40;
  auto swatch = [&](Rgb colour, const std::string& label) {
    c.fillRect(x, 14, x + 24, 28, colour);
    c.text(x + 32, 14, label, kBlack, kText);
    x += 32 + Canvas::textWidth(label, kText) + 30;
  };
  swatch(kError, "error");
  for (std::size_t d = 0; d < ev.envelope_px.size(); ++d) {
    char buf[48];
    std::snprintf(buf, sizeof(buf), "+-envelope %g px", ev.envelope_px[d]);
    swatch(envelopeColour(d), buf);
  }
  swatch(kClipped, "clipped");
  swatch(kLost, "lost");

  const std::vector<std::size_t> by_distance = posePanelFrames(ev);
  double x_lo = 0.0, x_hi = 1.0;
  if (!by_distance.empty()) {
    x_lo = ev.frames[by_distance.front()].distance_m;
    x_hi = ev.frames[by_distance.back()].distance_m;
  }
  if (!(x_hi > x_lo)) {
    x_lo -= 0.5;
    x_hi += 0.5;
  }
  for (int axis = 0; axis < kAxisCount; ++axis)
    drawPanel(c, ev, axis, (axis % 3) * w, legend_h + (axis / 3) * h, w, h, x_lo, x_hi, by_distance);
  if (far_h > 0) drawFarRangePanels(c, ev, 0, legend_h + 2 * h, 3 * w, far_h);
  if (timeline_h > 0) drawModeTimeline(c, ev, 0, legend_h + 2 * h + far_h, 3 * w, timeline_h);
  return c;
}

LoadError writeErrorPlot(const std::string& path, const Evaluation& ev, const PlotOptions& options) {
  return renderErrorPlot(ev, options).writePng(path);
}

}  // namespace visnav::eval
