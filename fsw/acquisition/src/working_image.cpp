#include "visnav/acquisition/working_image.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>

namespace visnav::acq {

namespace {

constexpr int kHistogramBins = 256;

double pixel(const MonoImage& image, int x, int y) {
  return image.depth == MonoImage::Depth::kU8 ? image.u8.at(x, y) : image.u16.at(x, y);
}

struct Quantiles {
  double median = 0.0;
  double p99 = 0.0;
  double p999 = 0.0;
};

/// Median, 99th and 99.9th percentiles of n values in [0, max_value] (max_value > 0), from a histogram.
Quantiles quantilesOf(const float* values, std::size_t n, float max_value) {
  int histogram[kHistogramBins] = {};
  const double to_bin = (kHistogramBins - 1) / static_cast<double>(max_value);
  for (std::size_t i = 0; i < n; ++i) ++histogram[static_cast<int>(values[i] * to_bin)];
  auto quantile = [&](double q) {
    const double target = q * static_cast<double>(n);
    double cumulative = 0.0;
    for (int b = 0; b < kHistogramBins; ++b) {
      cumulative += histogram[b];
      if (cumulative >= target) return (b + 0.5) / to_bin;
    }
    return static_cast<double>(max_value);
  };
  return {quantile(0.5), quantile(0.99), quantile(0.999)};
}

/// Sobel / 8 at interior pixel (x, y) of a w-wide row-major image: brightness per pixel.
void sobel(const float* image, int w, int x, int y, float& gx, float& gy) {
  const float* r0 = image + (y - 1) * w + x;
  const float* r1 = r0 + w;
  const float* r2 = r1 + w;
  gx = ((r0[1] - r0[-1]) + 2.0F * (r1[1] - r1[-1]) + (r2[1] - r2[-1])) * 0.125F;
  gy = ((r2[-1] - r0[-1]) + 2.0F * (r2[0] - r0[0]) + (r2[1] - r0[1])) * 0.125F;
}

}  // namespace

LoadError WorkingImage::init(int max_side_px, int max_strong_pixels, int max_window_px) {
  if (max_side_px < 16) return LoadError::failure("acquisition: working image side below 16 px");
  if (max_window_px < 16) return LoadError::failure("acquisition: window side below 16 px");
  if (max_strong_pixels < 16) return LoadError::failure("acquisition: fewer than 16 strong pixels");
  m_strong.reserve(static_cast<std::size_t>(max_strong_pixels));
  m_max_side = max_side_px;
  m_max_window = max_window_px;
  const auto n = static_cast<std::size_t>(max_side_px) * static_cast<std::size_t>(max_side_px);
  m_intensity.reserve(n);
  m_magnitude.reserve(n);
  m_gx.reserve(n);
  m_gy.reserve(n);
  m_tmp.reserve(n);
  for (auto& level : m_channel)
    for (auto& channel : level) channel.reserve(n);
  return LoadError::success();
}

int WorkingImage::setWindow(const Vec2& centre_px, double half_size_px, int scale) {
  // Bounded work whatever is asked: a search whose prediction had coasted past the camera (depth near zero,
  // the target at 24 m) asked for a window many times wider than the image, averaged in blocks as wide, and
  // prepare() ran for an hour (campaign plate/26 with the search's rates fading). A window wider than twice
  // the image only adds padding.
  const double max_half = 0.5 * m_max_window;
  const double half = half_size_px <= max_half ? std::max(half_size_px, 8.0) : max_half;
  const double side_full = 2.0 * half;
  m_scale = std::clamp(scale, 1, std::max(1, static_cast<int>(side_full / 16.0)));
  const int needed = static_cast<int>(std::ceil(side_full / m_max_side));
  m_scale = std::max(m_scale, needed);
  const int side = std::min(m_max_side, static_cast<int>(std::ceil(side_full / m_scale)));
  m_width = side;
  m_height = side;
  // Nor further off the image than a window's width (only padding there): prepare() indexes from the
  // origin in int (a coasted line of sight through a strong distortion, k3 ~ 0.1 at 85 deg off axis, projects
  // past int by the audit's arithmetic).
  const double reach = static_cast<double>(m_max_window);
  Vec2 centre = centre_px;
  for (int k = 0; k < 2; ++k) {
    if (!(centre[k] >= -reach)) centre[k] = -reach;  // NaN too
    if (centre[k] > 2.0 * reach) centre[k] = 2.0 * reach;
  }
  m_origin = centre - Vec2::Constant(0.5 * side * m_scale);
  m_origin = m_origin.array().floor();
  return m_scale;
}

void WorkingImage::prepare(const MonoImage& image, int fine_spread_px, int coarse_spread_px,
                           double cap_multiple) {
  const auto n = static_cast<std::size_t>(m_width) * static_cast<std::size_t>(m_height);
  m_intensity.clear();
  const double norm = 1.0 / (static_cast<double>(image.max_code) * m_scale * m_scale);
  m_noise_floor = 0.25 / image.max_code;
  const int x0 = static_cast<int>(m_origin.x());
  const int y0 = static_cast<int>(m_origin.y());
  const int w_max = image.width() - 1;
  const int h_max = image.height() - 1;
  for (int j = 0; j < m_height; ++j) {
    for (int i = 0; i < m_width; ++i) {
      // Box average of the s x s block; outside the frame the nearest frame pixel (flat: no false edge).
      double sum = 0.0;
      for (int dy = 0; dy < m_scale; ++dy) {
        const int y = std::clamp(y0 + j * m_scale + dy, 0, h_max);
        for (int dx = 0; dx < m_scale; ++dx)
          sum += pixel(image, std::clamp(x0 + i * m_scale + dx, 0, w_max), y);
      }
      m_intensity.push(static_cast<float>(sum * norm));
    }
  }
  for (auto& level : m_channel) {
    for (auto& channel : level) {
      channel.clear();
      for (std::size_t i = 0; i < n; ++i) channel.push(0.0F);
    }
  }
  m_magnitude.clear();
  m_gx.clear();
  m_gy.clear();
  for (std::size_t i = 0; i < n; ++i) {
    m_magnitude.push(0.0F);
    m_gx.push(0.0F);
    m_gy.push(0.0F);
  }
  computeGradients();
  computeStats();
  // Saturate the evidence before spreading: every supported place counts, the strongest edges do not
  // dominate a hypothesis' mean, and the spread copies keep their slope towards the edge.
  m_cap = static_cast<float>(cap_multiple * presenceThreshold());
  for (auto& channel : m_channel[static_cast<int>(Evidence::kRaw)])
    for (float& v : channel) v = std::min(v, m_cap);
  spreadChannels(fine_spread_px, m_channel[static_cast<int>(Evidence::kFine)]);
  spreadChannels(coarse_spread_px, m_channel[static_cast<int>(Evidence::kCoarse)]);
}

void WorkingImage::computeGradients() {
  // Sobel / 8: brightness per working pixel. Channel k: |gx cos(k 45 deg) + gy sin(k 45 deg)|.
  constexpr float kC = 0.70710678F;
  const int w = m_width;
  for (int y = 1; y + 1 < m_height; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      float gx = 0.0F;
      float gy = 0.0F;
      sobel(m_intensity.data(), w, x, y, gx, gy);
      const int i = y * w + x;
      m_magnitude[i] = std::sqrt(gx * gx + gy * gy);
      m_gx[i] = gx;
      m_gy[i] = gy;
      BoundedBuffer<float>* raw = m_channel[static_cast<int>(Evidence::kRaw)];
      raw[0][i] = std::fabs(gx);
      raw[1][i] = std::fabs(kC * (gx + gy));
      raw[2][i] = std::fabs(gy);
      raw[3][i] = std::fabs(kC * (gy - gx));
    }
  }
}

void WorkingImage::spreadChannels(int radius, BoundedBuffer<float>* out) {
  // Tent-weighted max filter: out(p) = max_d in(p + d) (1 - |dx| / (r + 1)) (1 - |dy| / (r + 1)). Separable
  // (the weights are a product of non-negative factors): rows into m_tmp, then columns. Unlike a flat max the
  // result still peaks on the edge, so the refinement has a slope to climb.
  const int w = m_width;
  const int h = m_height;
  float tent[2 * kMaxSpread + 1] = {};
  const int r = std::min(radius, kMaxSpread);
  for (int d = -r; d <= r; ++d)
    tent[d + r] = 1.0F - static_cast<float>(std::abs(d)) / static_cast<float>(r + 1);
  for (int k = 0; k < kChannels; ++k) {
    const float* src = m_channel[static_cast<int>(Evidence::kRaw)][k].data();
    m_tmp.clear();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        float best = 0.0F;
        for (int d = std::max(-r, -x); d <= std::min(r, w - 1 - x); ++d)
          best = std::max(best, src[y * w + x + d] * tent[d + r]);
        m_tmp.push(best);
      }
    }
    float* dst = out[k].data();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        float best = 0.0F;
        for (int d = std::max(-r, -y); d <= std::min(r, h - 1 - y); ++d)
          best = std::max(best, m_tmp[static_cast<std::size_t>(y + d) * static_cast<std::size_t>(w) +
                                      static_cast<std::size_t>(x)] *
                                    tent[d + r]);
        dst[y * w + x] = best;
      }
    }
  }
}

void WorkingImage::computeStats() {
  m_stats = GradientStats{};
  m_strong.clear();
  const std::size_t n = m_magnitude.size();
  float max_magnitude = 0.0F;
  for (std::size_t i = 0; i < n; ++i) max_magnitude = std::max(max_magnitude, m_magnitude[i]);
  if (!(max_magnitude > 0.0F)) {
    m_stats.median = m_noise_floor;
    return;
  }
  const Quantiles q = quantilesOf(m_magnitude.data(), n, max_magnitude);
  // Floor: a quarter of a code step, so a noise-free frame does not divide by zero.
  m_stats.median = std::max(q.median, m_noise_floor);
  m_stats.p99 = q.p99;
  m_stats.p999 = q.p999;
  m_stats.edge_snr = m_stats.median > 0.0 ? m_stats.p999 / m_stats.median : 0.0;
  computeCoarseSnr();
  // Strong: above most of the target's edges' level and above the noise (3 median ~ 3.5 sigma of Rayleigh).
  const double strong = std::max(0.5 * m_stats.p99, 3.0 * m_stats.median);
  double weight = 0.0;
  Vec2 sum = Vec2::Zero();
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) count += m_magnitude[i] > strong ? 1U : 0U;
  const std::size_t stride = count / m_strong.capacity() + 1U;  // thin evenly to the capacity
  m_strong.clear();
  std::size_t seen = 0;
  for (int y = 0; y < m_height; ++y) {
    for (int x = 0; x < m_width; ++x) {
      const std::size_t i =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x);
      const double excess = m_magnitude[i] - strong;
      if (excess <= 0.0) continue;
      weight += excess;
      sum += excess * Vec2(x + 0.5, y + 0.5);
      if (seen++ % stride == 0U) m_strong.push({Vec2(x + 0.5, y + 0.5), Vec2(m_gx[i], m_gy[i])});
    }
  }
  m_stats.has_strong = weight > 0.0;
  if (m_stats.has_strong) m_stats.strong_centroid_w = sum / weight;
}

void WorkingImage::computeCoarseSnr() {
  // The window box-averaged f times more into m_tmp (free until the channels are spread), then its Sobel
  // magnitudes after it. A dim outline under noise 0.1 (campaign cao/58, octagon/40: window edge SNR 3.2-4.5
  // at working_radius_px) keeps its step while the noise's gradient drops by f.
  int f = m_coarse_snr_factor;
  while (f > 1 && (m_width / f < 8 || m_height / f < 8)) --f;
  m_stats.coarse_factor = f;
  if (f <= 1) return;
  const int cw = m_width / f;
  const int ch = m_height / f;
  const float norm = 1.0F / static_cast<float>(f * f);
  m_tmp.clear();
  for (int j = 0; j < ch; ++j) {
    for (int i = 0; i < cw; ++i) {
      float sum = 0.0F;
      for (int dy = 0; dy < f; ++dy) {
        const float* row = m_intensity.data() + static_cast<std::ptrdiff_t>(j * f + dy) * m_width + i * f;
        for (int dx = 0; dx < f; ++dx) sum += row[dx];
      }
      m_tmp.push(sum * norm);
    }
  }
  float max_magnitude = 0.0F;
  for (int y = 1; y + 1 < ch; ++y) {
    for (int x = 1; x + 1 < cw; ++x) {
      float gx = 0.0F;
      float gy = 0.0F;
      sobel(m_tmp.data(), cw, x, y, gx, gy);
      const float magnitude = std::sqrt(gx * gx + gy * gy);
      max_magnitude = std::max(max_magnitude, magnitude);
      m_tmp.push(magnitude);
    }
  }
  if (!(max_magnitude > 0.0F)) return;
  const auto count = static_cast<std::size_t>(cw - 2) * static_cast<std::size_t>(ch - 2);
  const Quantiles q = quantilesOf(m_tmp.data() + static_cast<std::size_t>(cw) * static_cast<std::size_t>(ch),
                                  count, max_magnitude);
  const double median = std::max(q.median, m_noise_floor);
  m_stats.coarse_edge_snr = q.p999 / median;
}

ChannelBlend ChannelBlend::of(double normal_angle_rad) {
  double a = normal_angle_rad * (4.0 / kPi);
  a -= 4.0 * std::floor(a / 4.0);
  ChannelBlend blend;
  blend.k0 = static_cast<int>(a) & 3;
  blend.k1 = (blend.k0 + 1) & 3;
  blend.f = static_cast<float>(a - std::floor(a));
  return blend;
}

double WorkingImage::evidence(double px, double py, const ChannelBlend& blend, Evidence level) const {
  // In double first: a point projected far off the window must not reach the int casts (NaN fails too).
  if (!(px >= 0.0 && py >= 0.0 && px < m_width && py < m_height)) return 0.0;
  const int x = static_cast<int>(px);
  const int y = static_cast<int>(py);
  const BoundedBuffer<float>* channels = m_channel[static_cast<int>(level)];
  const std::size_t i =
      static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x);
  return (1.0F - blend.f) * channels[blend.k0][i] + blend.f * channels[blend.k1][i];
}

}  // namespace visnav::acq
