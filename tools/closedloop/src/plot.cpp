// closedloop.png: range (log), distance to the hold point (log) with the 10 cm gate, attitude error with the
// 2 deg gate, delta-v of both runs, and visnav's mode timeline, all against time.
#include "visnav/eval/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "visnav/closedloop/report.hpp"
#include "visnav/eval/canvas.hpp"

namespace visnav::closedloop {
namespace {

using eval::Canvas;
using eval::Rgb;

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrid{225, 225, 225};
constexpr Rgb kVisnav{30, 90, 200};
constexpr Rgb kTruth{230, 120, 0};
constexpr Rgb kGate{200, 30, 30};
constexpr Rgb kModes[4] = {{160, 160, 160}, {90, 160, 230}, {240, 190, 40}, {60, 170, 80}};
constexpr int kText = 2;
constexpr int kWidth = 1400;
constexpr int kPanelH = 300;
constexpr int kLeft = 130;
constexpr int kRight = kWidth - 40;

struct Panel {
  int top, bottom;
  double t_max, y_lo, y_hi;
  bool log;
  double px(double t) const { return kLeft + t / t_max * (kRight - kLeft - 1); }
  double py(double y) const {
    const double v = log ? std::log10(std::max(y, 1e-12)) : y;
    const double c = std::clamp(v, y_lo, y_hi);
    return bottom - 1 - (c - y_lo) / (y_hi - y_lo) * (bottom - top - 1);
  }
};

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof(b), f, v);
  return b;
}

Panel frame(Canvas& c, int top, const std::string& title, double t_max, double lo, double hi, bool log) {
  const Panel p{top + 30, top + kPanelH - 10, t_max, lo, hi, log};
  c.text(kLeft, top + 6, title, kBlack, kText);
  int decimals = 0;
  for (double v : eval::niceTicks(lo, hi, 5, decimals)) {
    if (log && std::fabs(v - std::round(v)) > 1e-9) continue;
    const double y = p.bottom - 1 - (v - lo) / (hi - lo) * (p.bottom - p.top - 1);
    c.line(kLeft, y, kRight - 1, y, kGrid);
    const std::string label =
        log ? fmt("%g", std::pow(10.0, v)) : fmt(("%." + std::to_string(decimals) + "f").c_str(), v);
    c.text(kLeft - 8 - Canvas::textWidth(label, kText), static_cast<int>(y) - 7, label, kBlack, kText);
  }
  for (double t : eval::niceTicks(0.0, t_max, 10, decimals)) {
    c.line(p.px(t), p.top, p.px(t), p.bottom - 1, kGrid);
    const std::string label = fmt("%.0f", t);
    c.text(static_cast<int>(p.px(t)) - Canvas::textWidth(label, kText) / 2, p.bottom + 4, label, kBlack,
           kText);
  }
  c.rect(kLeft, p.top, kRight, p.bottom, kBlack);
  return p;
}

template <typename Get>
void curve(Canvas& c, const Panel& p, const RunResult& r, Get get, Rgb colour) {
  c.setClip(kLeft + 1, p.top + 1, kRight - 1, p.bottom - 1);
  for (std::size_t i = 1; i < r.frames.size(); ++i)
    c.line(p.px(r.frames[i - 1].t_s), p.py(get(r.frames[i - 1])), p.px(r.frames[i].t_s),
           p.py(get(r.frames[i])), colour, 2);
  c.resetClip();
}

}  // namespace

LoadError writePlot(const std::string& path, const ScenarioParams& params, const RunResult& v,
                    const RunResult& t) {
  const int panels = 4;
  Canvas c(kWidth, 60 + panels * (kPanelH + 30) + 110, kWhite);
  const double t_max = std::max(v.frames.back().t_s, t.frames.back().t_s) + 1.0;
  c.text(kLeft, 10,
         "visnav-closedloop " + params.name + ", from " + fmt("%.0f", params.start_range_m) +
             " m. blue: visnav in the loop, orange: the same guidance fed the truth",
         kBlack, kText);
  int top = 40;
  const double r_hi = std::ceil(std::log10(params.start_range_m * 1.2));
  Panel p = frame(c, top, "range to the target centre [m]", t_max, 0.0, r_hi, true);
  curve(
      c, p, v, [](const FrameLog& f) { return f.range_m; }, kVisnav);
  curve(
      c, p, t, [](const FrameLog& f) { return f.range_m; }, kTruth);
  top += kPanelH + 30;
  p = frame(c, top, "distance to the hold point [m], gate 0.1 m", t_max, -3.0, r_hi, true);
  c.line(kLeft, p.py(params.gate_position_m), kRight - 1, p.py(params.gate_position_m), kGate);
  curve(
      c, p, v, [](const FrameLog& f) { return f.position_error_m; }, kVisnav);
  curve(
      c, p, t, [](const FrameLog& f) { return f.position_error_m; }, kTruth);
  top += kPanelH + 30;
  p = frame(c, top, "attitude error to the hold attitude [deg] (modulo the plate symmetry), gate 2 deg",
            t_max, 0.0, 30.0, false);
  c.line(kLeft, p.py(params.gate_attitude_deg), kRight - 1, p.py(params.gate_attitude_deg), kGate);
  curve(
      c, p, v, [](const FrameLog& f) { return f.attitude_error_deg; }, kVisnav);
  curve(
      c, p, t, [](const FrameLog& f) { return f.attitude_error_deg; }, kTruth);
  top += kPanelH + 30;
  double dv_max = 0.1;
  for (const RunResult* r : {&v, &t}) dv_max = std::max(dv_max, r->frames.back().delta_v_m_s);
  p = frame(c, top, "delta-v spent [m/s]", t_max, 0.0, dv_max * 1.1, false);
  curve(
      c, p, v, [](const FrameLog& f) { return f.delta_v_m_s; }, kVisnav);
  curve(
      c, p, t, [](const FrameLog& f) { return f.delta_v_m_s; }, kTruth);
  top += kPanelH + 30;
  // Mode timeline of the visnav run.
  c.text(kLeft, top, "visnav mode: grey standby, blue far range, yellow acquisition, green near range",
         kBlack, kText);
  const int y0 = top + 25, y1 = top + 65;
  for (std::size_t i = 0; i + 1 < v.frames.size(); ++i) {
    const int m = v.frames[i].mode;
    if (m < 0 || m > 3) continue;
    c.fillRect(static_cast<int>(p.px(v.frames[i].t_s)), y0, static_cast<int>(p.px(v.frames[i + 1].t_s)) + 1,
               y1, kModes[m]);
  }
  c.rect(kLeft, y0, kRight, y1, kBlack);
  c.text(kLeft, y1 + 10, "time [s]", kBlack, kText);
  return c.writePng(path);
}

}  // namespace visnav::closedloop
