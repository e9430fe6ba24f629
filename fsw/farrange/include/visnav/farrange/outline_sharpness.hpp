// How sharp a cluster's outline is (ours, not the paper's): a body in the camera's field has an outline
// blurred by the optics over a pixel or two, a glow or a diffuse blob (a cloud, a wide Gaussian spot) a
// ramp over tens of pixels. Sec. III's filters do not tell them apart: a blob is as rare in the histogram
// (eq. 11-12) as a body, and eq. 10's percentile normalisation makes its gentle gradient look like an edge.
#pragma once

#include "visnav/core/image_view.hpp"
#include "visnav/core/types.hpp"

namespace visnav::far {

/// Rays cast from the centre, and the scales of the steps compared on each.
struct OutlineSharpnessSettings {
  static constexpr int kRays = 32;
  /// The fine scale h (px): the radius over this, at least kMinScalePx. Steps are between means of 2 h + 1
  /// samples: fine q(r + h) - q(r - h), coarse q(r + kCoarseScales h) - q(r - kCoarseScales h). At h = 1
  /// the 3-sample mean spreads a body's 1-px edge over the fine baseline (fine / coarse 0.53 against a
  /// blob's 0.32-0.39); at 2 it spans it.
  static constexpr double kRadiusPerScale = 16.0;
  static constexpr int kMinScalePx = 2;
  static constexpr int kCoarseScales = 4;
  /// Radii below this are not measured: the outline is looked for beyond the coarse baseline (5 h).
  static constexpr double kMinRadiusPx = 10.0;
  /// Longest ray, px: bounds the cost (kRays x 3 samples x this) whatever the cluster's size.
  static constexpr int kMaxRayPx = 512;
  /// A ray counts only where its coarse step is this many times its noise (1-sigma of q).
  static constexpr double kMinStepNoise = 5.0;
};

struct OutlineSharpness {
  bool measured = false;  ///< false: too small, or under half the rays inside the image with a clear step
  double ratio =
      0.0;       ///< sum of fine steps over sum of coarse steps: near 1 at a body's edge, ~0.25 on a ramp
  int rays = 0;  ///< rays that reached past the outline inside the image
};

/// Casts kRays rays from `centre_px` (raw pixel coordinates) out to 1.5 `radius_px` and a coarse baseline.
/// Along each, the profile p(r) is the mean of three pixels across the ray, q(r) its mean over 2 h + 1
/// samples; the outline is where q's 4 h step is largest, and there its 2 h step (fine) is compared with
/// its 8 h step (coarse), signed by the latter. Rays whose coarse step is not kMinStepNoise times their
/// noise are left out; the rest are summed, so noise averages out instead of biasing one ray. No
/// allocation; at most kRays x 3 x kMaxRayPx pixel reads.
OutlineSharpness measureOutlineSharpness(const MonoImage& image, const Vec2& centre_px, double radius_px);

}  // namespace visnav::far
