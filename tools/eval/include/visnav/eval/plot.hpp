// Paper fig. 6 style plot: six panels (x, y, z, yaw, pitch, roll) of error vs. distance (truth t_c_m.z),
// errors as dots, worst-case envelopes as +- curves, lost frames as grey ticks on the bottom axis; below them
// the far-range direction/distance errors vs. distance and the mode timeline when the replay has them.
#pragma once

#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/eval/canvas.hpp"
#include "visnav/eval/evaluation.hpp"

namespace visnav::eval {

struct PlotOptions {
  int panel_width_px = 620;
  int panel_height_px = 400;
  std::string title = "pose error vs distance";
};

/// Height of the mode timeline strip [px].
constexpr int kTimelineHeightPx = 240;

/// The frames the pose panels show, nearest first: every frame that has a pose or was not in far range or
/// standby (a far-range frame without a pose would only stretch the distance axis). Replays without a mode
/// column, and replays that never left far range, show every frame.
std::vector<std::size_t> posePanelFrames(const Evaluation& evaluation);

/// Renders into a new canvas: a legend strip, 3 x 2 pose panels, then (only when the replay has them) a row
/// of two far-range panels of panel height and the mode timeline strip, each 3 panels wide.
Canvas renderErrorPlot(const Evaluation& evaluation, const PlotOptions& options = {});
LoadError writeErrorPlot(const std::string& path, const Evaluation& evaluation,
                         const PlotOptions& options = {});

/// The mode timeline strip alone (`--timeline`), `width_px` wide.
Canvas renderModeTimeline(const Evaluation& evaluation, int width_px = 1860);
LoadError writeModeTimeline(const std::string& path, const Evaluation& evaluation, int width_px = 1860);

/// Tick positions at 1, 2 or 5 x 10^k covering [lo, hi] with about `target` intervals; `decimals` receives
/// the number of decimals that label them exactly.
std::vector<double> niceTicks(double lo, double hi, int target, int& decimals);

}  // namespace visnav::eval
