// The acquisition's view of one frame: a window around the far-range cue, box-averaged by an integer factor
// so that the expected target spans about the same number of working pixels at any distance, with Sobel
// gradients split into four orientation channels |g . n_k| (n_k every 45 deg), saturated, and two spread
// copies of each (tent-weighted max filters), so an edge hypothesis some pixels off still scores (LINE-MOD's
// spreading, Hinterstoisser et al. 2012): a wide one for the coarse search, a narrow one for refinement.
// Buffers are sized in init(); prepare() allocates nothing.
#pragma once

#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/image_view.hpp"
#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"

namespace visnav::acq {

/// Magnitude statistics of the window's gradients (working pixels, brightness per working pixel).
struct GradientStats {
  double median = 0.0;  ///< noise level (most of the window is background), >= 1/4 code step
  double p99 = 0.0;
  double p999 = 0.0;      ///< the target's strongest edges when there is a target
  double edge_snr = 0.0;  ///< p999 / median: ~3 for noise alone (Rayleigh), >> 3 with a target
  /// The same on a copy box-averaged coarse_factor times more (0 when not asked): a dim target's outline
  /// keeps its contrast there while the noise drops by the factor.
  double coarse_edge_snr = 0.0;
  int coarse_factor = 1;
  /// What the no-target test reads: the better of the two scales.
  double detectionSnr() const { return edge_snr > coarse_edge_snr ? edge_snr : coarse_edge_snr; }
  bool has_strong = false;  ///< any pixel above the strong threshold max(0.5 p99, 3 median)
  Vec2 strong_centroid_w =
      Vec2::Zero();  ///< magnitude-weighted centroid of strong pixels, working coordinates
};

/// A pixel of a strong edge (above GradientStats' strong threshold), for the image-to-model check.
struct StrongPixel {
  Vec2 p = Vec2::Zero();         ///< working coordinates of the pixel centre
  Vec2 gradient = Vec2::Zero();  ///< brightness per working pixel
};

/// An edge normal direction as the two orientation channels around it and the interpolation weight.
struct ChannelBlend {
  int k0 = 0;
  int k1 = 1;
  float f = 0.0F;  ///< weight of k1
  /// Normal direction modulo pi, in units of 45 deg.
  static ChannelBlend of(double normal_angle_rad);
};

/// Which copy of the orientation channels evidence is read from.
enum class Evidence : std::uint8_t { kRaw = 0, kFine = 1, kCoarse = 2 };

class WorkingImage {
 public:
  static constexpr int kChannels = 4;
  static constexpr int kLevels = 3;  ///< raw, fine spread, coarse spread
  static constexpr int kMaxSpread = 64;

  /// Allocates for windows up to max_side x max_side working pixels and up to max_strong strong pixels;
  /// no window is wider than max_window_px raw pixels (give twice the image's larger side: a wider one only
  /// adds padding).
  LoadError init(int max_side_px, int max_strong_pixels, int max_window_px);
  /// Places the window: centre and half-size in full-resolution raw pixels, box factor `scale` >= 1. The
  /// factor grows if the window would exceed max_side. The half-size is capped at max_window_px / 2 (a NaN
  /// too) and the asked factor at a sixteenth of the window's side, so prepare() reads at most about
  /// max_window_px^2 raw pixels whatever is asked. Returns the factor used.
  int setWindow(const Vec2& centre_px, double half_size_px, int scale);
  /// prepare() also measures the edge SNR on a copy box-averaged `factor` times more (1: not; bounded so
  /// the copy keeps 8 px a side). Holds until changed.
  void setCoarseSnrFactor(int factor) { m_coarse_snr_factor = factor < 1 ? 1 : factor; }

  /// Reads the window from the frame (outside the frame: nearest frame pixel, so no false edge), computes
  /// gradients and statistics, saturates the channels at cap_multiple x presenceThreshold() and builds the
  /// two spread copies (tent-weighted max filters, radii in working px, at most kMaxSpread).
  void prepare(const MonoImage& image, int fine_spread_px, int coarse_spread_px, double cap_multiple);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int scale() const { return m_scale; }
  /// Full-resolution raw pixel <-> working coordinates (continuous; working pixel (i, j) covers [i, i+1)).
  Vec2 toWorking(const Vec2& full_px) const { return (full_px - m_origin) / static_cast<double>(m_scale); }
  Vec2 toFull(const Vec2& working) const { return m_origin + working * static_cast<double>(m_scale); }

  /// Edge evidence for an edge with unit normal angle `normal_angle_rad` at working point p: the gradient
  /// component along the normal (absolute, either contrast), from the chosen channel copy; 0 outside.
  double evidence(const Vec2& p, double normal_angle_rad, Evidence level) const {
    return evidence(p, ChannelBlend::of(normal_angle_rad), level);
  }
  /// The same with the channel blend computed once per edge (the scoring loop's form).
  double evidence(const Vec2& p, const ChannelBlend& blend, Evidence level) const {
    return evidence(p.x(), p.y(), blend, level);
  }
  double evidence(double x, double y, const ChannelBlend& blend, Evidence level) const;
  const GradientStats& stats() const { return m_stats; }
  /// Strong-edge pixels of the window (evenly thinned to the capacity when there are more).
  const BoundedBuffer<StrongPixel>& strongPixels() const { return m_strong; }
  /// Threshold of "edge present": 3 x the median gradient (~3.5 sigma of noise).
  double presenceThreshold() const { return 3.0 * m_stats.median; }
  /// Saturation level of the evidence (every channel value is in [0, cap]).
  double cap() const { return m_cap; }

 private:
  void computeGradients();
  void spreadChannels(int radius, BoundedBuffer<float>* out);
  void computeStats();
  void computeCoarseSnr();

  int m_max_side = 0;
  int m_max_window = 0;  ///< raw px a side (init)
  int m_width = 0;
  int m_height = 0;
  int m_scale = 1;
  int m_coarse_snr_factor = 1;
  Vec2 m_origin = Vec2::Zero();  ///< full-resolution position of working coordinate (0, 0)
  double m_noise_floor = 0.0;    ///< lower bound of the median gradient (quantisation)
  float m_cap = 1.0F;
  BoundedBuffer<float> m_intensity;
  BoundedBuffer<float> m_magnitude;
  BoundedBuffer<float> m_gx;
  BoundedBuffer<float> m_gy;
  BoundedBuffer<StrongPixel> m_strong;
  BoundedBuffer<float> m_channel[kLevels][kChannels];
  BoundedBuffer<float> m_tmp;
  GradientStats m_stats;
};

}  // namespace visnav::acq
