// What the tracker saw, drawn over the frame like the paper's fig. 3: predicted model edges (blue),
// scanlines (yellow), edge points (green inliers, red outliers, magenta texture hits), fitted lines (orange).
#pragma once

#include <string>

#include "visnav/core/image_view.hpp"
#include "visnav/core/status.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav::replay_tool {

LoadError writeOverlayPng(const std::string& path, const MonoImage& image, const NearRangeTracker& tracker,
                          const NearRangeResult& result);

}  // namespace visnav::replay_tool
