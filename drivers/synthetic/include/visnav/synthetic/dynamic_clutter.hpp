// Clutter that changes from frame to frame, drawn into the background before the target (so the target
// occludes it): a bright elongated object crossing the view (the robot platform of paper sec. IV-B) and
// small specular glints. Frame windows and motion are in trajectory frame indices
// (Renderer::setFrameIndex); outside its window an object is not drawn.
#pragma once

#include <cstdint>

#include "visnav/core/types.hpp"

namespace visnav::synthetic {

/// A flat-brightness rectangle in image space, drawn with exact area coverage. Its centre moves linearly
/// from start_px (first_frame) to end_px (last_frame); its brightness ramps linearly the same way.
struct MovingBar {
  std::int64_t first_frame = 0;
  std::int64_t last_frame = 0;
  Vec2 start_px = Vec2::Zero();
  Vec2 end_px = Vec2::Zero();
  double length_px = 100.0;
  double width_px = 10.0;
  double angle_deg = 0.0;  ///< long axis from image x towards image y
  double brightness_start = 0.9;
  double brightness_end = 0.9;
};

/// A Gaussian spot added to the background: peak * exp(-r^2 / (2 sigma^2)), centre moving linearly.
struct Glint {
  std::int64_t first_frame = 0;
  std::int64_t last_frame = 0;
  Vec2 start_px = Vec2::Zero();
  Vec2 end_px = Vec2::Zero();
  double sigma_px = 0.7;
  double peak = 1.0;
};

/// Position of an object at `frame` (linear between its window's ends); false outside the window.
bool clutterAt(std::int64_t first_frame, std::int64_t last_frame, std::int64_t frame, double& fraction);

}  // namespace visnav::synthetic
