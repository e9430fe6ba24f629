// RANSAC line fit on the edge points of one edge (paper sec. II-E, Fischler & Bolles [3]), then a total
// least-squares refit on the largest consensus set. Deterministic: the caller seeds the generator.
#pragma once

#include <cstdint>

#include "visnav/core/rng.hpp"
#include "visnav/geometry/line2d.hpp"

namespace visnav {

struct RansacParams {
  double threshold_px = 0.9;  ///< alpha
  int iterations = 100;       ///< n
};

struct RansacResult {
  bool ok = false;
  Line2d line;
  int inliers = 0;
  double rms_px = 0.0;  ///< of the inliers about the refitted line
};

/// `inlier` (size count) receives the consensus flags of the final line; `scratch` (size count) is work
/// space owned by the caller. No allocation.
RansacResult fitLineRansac(const Vec2* points, int count, const RansacParams& params, Pcg32& rng,
                           std::uint8_t* inlier, Vec2* scratch);

/// The variance of a zero-mean normal point scatter whose part within +-threshold_px has the variance
/// `inlier_variance_px2`. The consensus set keeps only the points within the threshold, so its scatter
/// understates the points' own once that is not small against the threshold: a normal cut at 1.5 sigma
/// keeps 55 % of its variance. Returned unchanged below a quarter of the threshold (sigma), capped at
/// (2 * threshold_px)^2, where the cut scatter is within 4 % of a uniform band's and says no more. Bounded
/// bisection, no allocation.
double uncutScatterVariance(double inlier_variance_px2, double threshold_px);

}  // namespace visnav
