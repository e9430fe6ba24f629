// FarRangeResult -> FarRangeSolution, the stage interface far range hands to acquisition and navigation
// (visnav/core/stage_interfaces.hpp). Header-only; includes far range and core only (navigation uses the
// estimators, not the reverse).
#pragma once

#include "visnav/core/stage_interfaces.hpp"
#include "visnav/farrange/far_range_estimator.hpp"

namespace visnav::far {

inline FarRangeSolution toFarRangeSolution(const FarRangeResult& r) {
  FarRangeSolution s;
  s.valid = r.valid;
  s.direction_c = r.direction_c;
  s.azimuth_rad = r.azimuth_rad;
  s.elevation_rad = r.elevation_rad;
  s.distance_m = r.distance_m;
  s.cluster_pixels = r.cluster_pixels;
  s.circularity = r.circularity;
  s.cluster_count = r.cluster_count;
  s.quality = r.valid ? r.quality : 0.0;
  s.outline = r.valid && (r.flags & kFlagExtended) != 0U;
  return s;
}

}  // namespace visnav::far
