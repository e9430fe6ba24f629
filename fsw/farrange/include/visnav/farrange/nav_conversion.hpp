// FarRangeResult -> the pipeline's FarRangeSolution (fsw/navigation nav_solution.hpp). Header-only, so
// visnav_farrange does not link visnav_navigation (navigation uses the estimators, not the reverse); include
// it where both are linked.
#pragma once

#include "visnav/farrange/far_range_estimator.hpp"
#include "visnav/navigation/nav_solution.hpp"

namespace visnav::far {

inline nav::FarRangeSolution toFarRangeSolution(const FarRangeResult& r) {
  nav::FarRangeSolution s;
  s.valid = r.valid;
  s.direction_c = r.direction_c;
  s.azimuth_rad = r.azimuth_rad;
  s.elevation_rad = r.elevation_rad;
  s.distance_m = r.distance_m;
  s.cluster_pixels = r.cluster_pixels;
  s.circularity = r.circularity;
  s.cluster_count = r.cluster_count;
  s.quality = r.valid ? r.quality : 0.0;
  return s;
}

}  // namespace visnav::far
