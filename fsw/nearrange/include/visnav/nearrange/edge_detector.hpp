// Edge point on one scanline (paper sec. II-D): brightness difference (eq. 4) with a sub-pixel refinement,
// or, when the contrast is too weak, the texture split of eq. 5 / Algorithm 1. Pure math, no allocation.
#pragma once

#include <cstdint>

#include "visnav/core/image_view.hpp"
#include "visnav/core/types.hpp"

namespace visnav {

constexpr int kMaxScanlineSamples = 129;  ///< 2 * 64 + 1, the largest scanline_half_length_px allowed

/// Bilinear brightness in [0, 1] at continuous pixel position p (pixel centres at +0.5). False outside.
bool sampleBrightness(const MonoImage& image, const Vec2& p, double& value);

/// Samples 2 * half_length + 1 points centre + k * direction, k = -half_length..half_length (unit spacing
/// when direction is a unit vector). False when any sample falls outside the image.
bool sampleScanline(const MonoImage& image, const Vec2& centre, const Vec2& direction, int half_length,
                    double* samples);

enum class EdgeMethod : std::uint8_t { kNone = 0, kGradient = 1, kTexture = 2 };

struct EdgeSearchParams {
  double contrast_delta = 0.2;  ///< delta of sec. II-D
  int texture_bins = 32;        ///< n_bins of Algorithm 1
  /// A texture split must beat "one texture everywhere" by this log-likelihood margin [nats], else the
  /// scanline has no edge (a uniform patch must not produce a confident edge point).
  double texture_min_log_gain = 1.0;
  bool subpixel = true;
};

struct EdgeHit {
  EdgeMethod method = EdgeMethod::kNone;
  double offset_px = 0.0;  ///< edge position along the scanline relative to its centre sample
  double strength = 0.0;   ///< max(w) - mean(w) for gradient hits, 0 for texture hits
  int polarity = 0;        ///< sign of the brightness step along the scanline direction (+1 dark->bright)
};

/// `expected_polarity`: +1 / -1 searches argmax(+-w) only, 0 searches argmax |w| (unknown polarity).
EdgeHit findEdge(const double* samples, int count, const EdgeSearchParams& params, int expected_polarity);

/// log f(S, x, y) of Algorithm 1 for every prefix: out[n] = log f(S, 0, n + 1), i.e. samples 0..n.
/// Uses s_o = n_bins for the initial total, making f the Dirichlet-multinomial likelihood; see
/// nearrange/README.md for why the printed "#S" and "S(i)" are read as n_bins and S(c).
void textureLogLikelihoodPrefix(const double* samples, int count, int bins, double* out);

/// Eq. 5: split index n maximising f(S, 0, n) * f(S, n + 1, end); returns the edge position in samples
/// (between n and n + 1, i.e. n + 0.5). At least 2 samples on each side. `log_gain` (optional) receives
/// log f(split) - log f(S, 0, end): how much better two textures explain the samples than one. Invalid input
/// (count outside 4..kMaxScanlineSamples, bins outside 2..256) returns the centre with a zero gain.
double textureSplit(const double* samples, int count, int bins, double* log_gain = nullptr);

}  // namespace visnav
