// Internals shared by the plot sources (plot.cpp: the six pose panels; plot_modes.cpp: far-range panels and
// the mode timeline): colours, the data-to-pixel mapping of one panel, and its axes.
#pragma once

#include <string>

#include "visnav/eval/canvas.hpp"
#include "visnav/eval/evaluation.hpp"

namespace visnav::eval::plot_parts {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrid{225, 225, 225};
constexpr Rgb kZero{150, 150, 150};
constexpr Rgb kError{30, 90, 200};
constexpr Rgb kClipped{200, 0, 200};
constexpr Rgb kLost{120, 120, 120};
constexpr int kText = 2;  // font scale: 10x14 px characters

/// Plot area [left, right) x [top, bottom) in pixels and the data ranges it shows.
struct PlotArea {
  int left, top, right, bottom;
  double x_lo, x_hi, y_lo, y_hi;
  double px(double x) const { return left + (x - x_lo) / (x_hi - x_lo) * (right - left - 1); }
  double py(double y) const { return bottom - 1 - (y - y_lo) / (y_hi - y_lo) * (bottom - top - 1); }
};

std::string formatTick(double v, int decimals);

/// Title centred at `title_y`, grid and labelled ticks on both axes (y = 0 darker), x label below.
void drawAxes(Canvas& c, const PlotArea& f, const std::string& title, int title_y, const std::string& xlabel);

/// Colour of a mode in the timeline and the far-range panels (kError for kUnknown).
Rgb modeColour(ReplayMode mode);

/// Some frame has far-range errors / a known mode.
bool hasFarRange(const Evaluation& ev);
bool hasModes(const Evaluation& ev);

/// Far-range direction error [deg] and distance error [%] against distance, two panels side by side in
/// [x0, x0 + width) x [y0, y0 + height); dots coloured by mode.
void drawFarRangePanels(Canvas& c, const Evaluation& ev, int x0, int y0, int width, int height);
/// Mode timeline strip in [x0, x0 + width) x [y0, y0 + height): one lane per mode against the frame number,
/// the truth distance under the frame ticks, lost and missing frames as grey ticks.
void drawModeTimeline(Canvas& c, const Evaluation& ev, int x0, int y0, int width, int height);

}  // namespace visnav::eval::plot_parts
