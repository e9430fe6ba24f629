// Edge alignment of a projected polygon model with an image's gradient: the truth-free score of
// tools/realimages (README.md there, "The metric"). Used for every tracker's poses alike (visnav-replay's
// CSV, ViSP's vpMbEdgeTracker CSV), so the numbers compare. Ground tool, not flight code: allocates freely.
#pragma once

#include <cstdint>
#include <vector>

#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::realimages {

struct EdgeScoreOptions {
  double sample_step_px = 2.0;  ///< spacing of the samples along a projected edge [px]
  int search_half_px = 10;      ///< the gradient maximum is searched +-this along the edge normal [px]
  double end_margin_px = 4.0;   ///< no sample closer than this to a projected vertex [px]
  double min_gradient = 10.0;   ///< a maximum below this (Sobel / 8, grey levels per px) is "no edge"
  double within_px = 1.0;       ///< the "aligned" radius [px]
};

/// One frame's samples: offsets of the gradient maximum from the projected edge, signed along the normal.
struct FrameEdgeScore {
  int samples = 0;                  ///< sample points whose whole search segment lies inside the image
  int with_edge = 0;                ///< of them, maximum >= min_gradient
  int within = 0;                   ///< of those, |offset| <= within_px
  std::vector<double> abs_offsets;  ///< |offset| [px] of the samples with an edge
  double median_abs_offset_px() const;
  double withinFraction() const { return samples > 0 ? static_cast<double>(within) / samples : 0.0; }
};

/// Sobel gradient of an 8-bit image (gx, gy divided by 8: grey levels per pixel; 0 on the 1-px border).
struct Gradient {
  int width = 0;
  int height = 0;
  std::vector<float> gx, gy;
  void compute(const std::uint8_t* pixels, int width, int height, std::ptrdiff_t stride_bytes);
};

/// The visible model edges at `pose` (an edge of at least one front face, CONVENTIONS.md "Surface
/// visibility"; no occlusion test beyond that, exact for convex bodies) sampled every sample_step_px in raw
/// (distorted) pixels; at each sample, |d I / d n| (bilinear in the Sobel gradient projected on the edge
/// normal) is searched over integer offsets -N..N along the normal, the maximum refined by a parabola.
FrameEdgeScore scoreFrame(const Gradient& gradient, const PinholeCamera& camera, const PolygonModel& model,
                          const Pose& pose, const EdgeScoreOptions& options);

}  // namespace visnav::realimages
