// Edge point on one scanline (paper sec. II-D): a noise-scaled step test (eq. 4 generalised to a w-sample
// difference of means) with a sub-pixel refinement, or, when no step is significant, the texture split of
// eq. 5 / Algorithm 1. Pure math, no allocation.
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

/// As sampleScanline, each sample the mean of 2 * band_half_width + 1 samples spaced 1 px along the edge
/// (perpendicular to `direction`, a unit vector): an oriented mask like ViSP's moving edges, which lowers
/// the noise by sqrt(2 b + 1) while a straight edge stays sharp. band_half_width 0 is sampleScanline.
bool sampleScanlineBand(const MonoImage& image, const Vec2& centre, const Vec2& direction, int half_length,
                        int band_half_width, double* samples);

/// kGradient: a significant step of at least delta (the paper's strong edge, eq. 4); kStep: a significant
/// step weaker than delta (the paper's "weak contrast"); kTexture: Algorithm 1's split.
enum class EdgeMethod : std::uint8_t { kNone = 0, kGradient = 1, kTexture = 2, kStep = 3 };

struct EdgeSearchParams {
  double contrast_delta = 0.2;  ///< delta of sec. II-D: a step at least this large is a strong edge
  int step_window = 4;          ///< w: samples averaged on each side of a candidate step
  /// A step must exceed this many standard deviations of the w-sample difference of means, the noise
  /// measured on the scanline itself (median absolute first difference).
  double step_min_z = 5.0;
  /// Of the significant steps at least this share of the scanline's strongest, the one nearest the
  /// prediction is the edge point (1: always the strongest, the paper's argmax; 0: the nearest significant).
  double candidate_min_share = 0.5;
  /// Lower bound of that noise estimate (brightness 0..1): quantisation, so an 8-bit flat patch whose
  /// differences are mostly zero does not make every 1-code wiggle "significant".
  double noise_floor = 1.0 / (255.0 * 3.4641016151377544);
  int texture_bins = 32;  ///< n_bins of Algorithm 1
  /// A texture split must beat "one texture everywhere" by this log-likelihood margin [nats], else the
  /// scanline has no edge (a uniform patch must not produce a confident edge point).
  double texture_min_log_gain = 1.0;
  /// ... and the two sides' variances must differ by at least this factor. Histograms ignore order, so a
  /// noisy ramp that crosses a bin boundary scores like a clean step (gain <= 2.65 nats on 21 samples for
  /// either); what a texture boundary with no step has that noise lacks is a change of spread.
  double texture_min_variance_ratio = 10.0;
  bool subpixel = true;
};

struct EdgeHit {
  EdgeMethod method = EdgeMethod::kNone;
  double offset_px = 0.0;  ///< edge position along the scanline relative to its centre sample
  double strength = 0.0;   ///< |step| (difference of the w-sample means) for step hits, 0 for texture hits
  double z = 0.0;          ///< strength over its noise standard deviation (step hits)
  int polarity = 0;        ///< sign of the brightness step along the scanline direction (+1 dark->bright)
};

/// Robust noise standard deviation of a scanline: median |s(k+1) - s(k)| / (0.6745 sqrt 2), at least
/// `floor`. One edge changes a few differences only, so the median still measures the noise.
double scanlineNoiseSigma(const double* samples, int count, double floor);

/// `expected_polarity`: +1 / -1 accepts only steps of that sign, 0 either (unknown polarity).
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
