#include "visnav/nearrange/edge_detector.hpp"

#include <algorithm>
#include <cmath>

namespace visnav {

namespace {

// Bilinear brightness at p in [0, 1] without a bounds check: the caller has checked that the four pixels
// around p exist (sampleBrightness per sample, bandInside once per band), so both paths give the same bits.
template <typename PixelT>
inline double sampleInside(const ImageView<PixelT>& view, double max_code, const Vec2& p) {
  const double xs = p.x() - 0.5;
  const double ys = p.y() - 0.5;
  // xs, ys >= 0 here, so truncation is floor (std::floor is a library call without SSE4.1).
  const int x0 = static_cast<int>(xs);
  const int y0 = static_cast<int>(ys);
  const double ax = xs - static_cast<double>(x0);
  const double ay = ys - static_cast<double>(y0);
  const PixelT* r0 = view.row(y0) + x0;
  const PixelT* r1 = view.row(y0 + 1) + x0;
  const double v00 = r0[0];
  const double v10 = r0[1];
  const double v01 = r1[0];
  const double v11 = r1[1];
  const double top = v00 + ax * (v10 - v00);
  const double bottom = v01 + ax * (v11 - v01);
  return (top + ay * (bottom - top)) / max_code;
}

template <typename PixelT>
void sampleBandInside(const ImageView<PixelT>& view, double max_code, const Vec2& centre,
                      const Vec2& direction, const Vec2& along, int half_length, int band_half_width,
                      double* samples) {
  const double scale = 1.0 / (2 * band_half_width + 1);
  for (int k = -half_length; k <= half_length; ++k) {
    const Vec2 p = centre + static_cast<double>(k) * direction;
    double sum = 0.0;
    for (int j = -band_half_width; j <= band_half_width; ++j)
      sum += sampleInside(view, max_code, p + static_cast<double>(j) * along);
    samples[k + half_length] = sum * scale;
  }
}

/// Every bilinear sample of the band is inside when its four corners are, with a margin far above rounding:
/// the set of valid sample points is convex (sampleBrightness).
bool bandInside(const MonoImage& image, const Vec2& centre, const Vec2& direction, const Vec2& along,
                int half_length, int band_half_width) {
  // sampleBrightness needs 0 <= x - 0.5 < width - 1 (and the same in y).
  constexpr double kMargin = 1e-6;
  const double x_low = 0.5 + kMargin;
  const double y_low = 0.5 + kMargin;
  const double x_high = image.width() - 0.5 - kMargin;
  const double y_high = image.height() - 0.5 - kMargin;
  for (const int k : {-half_length, half_length}) {
    for (const int j : {-band_half_width, band_half_width}) {
      const Vec2 p = centre + static_cast<double>(k) * direction + static_cast<double>(j) * along;
      if (!(p.x() >= x_low && p.y() >= y_low && p.x() <= x_high && p.y() <= y_high)) return false;
    }
  }
  return true;
}

}  // namespace

bool sampleBrightness(const MonoImage& image, const Vec2& p, double& value) {
  // Continuous coordinates have pixel centres at +0.5 (CONVENTIONS.md). The four pixels around p exist
  // when 0 <= p - 0.5 < size - 1 (checked in this form, NaN fails it).
  const double xs = p.x() - 0.5;
  const double ys = p.y() - 0.5;
  if (!(xs >= 0.0 && ys >= 0.0 && xs < image.width() - 1.0 && ys < image.height() - 1.0)) return false;
  const double max_code = static_cast<double>(image.max_code);
  value = image.depth == MonoImage::Depth::kU8 ? sampleInside(image.u8, max_code, p)
                                               : sampleInside(image.u16, max_code, p);
  return true;
}

bool sampleScanline(const MonoImage& image, const Vec2& centre, const Vec2& direction, int half_length,
                    double* samples) {
  for (int k = -half_length; k <= half_length; ++k) {
    if (!sampleBrightness(image, centre + static_cast<double>(k) * direction, samples[k + half_length]))
      return false;
  }
  return true;
}

bool sampleScanlineBand(const MonoImage& image, const Vec2& centre, const Vec2& direction, int half_length,
                        int band_half_width, double* samples) {
  if (band_half_width <= 0) return sampleScanline(image, centre, direction, half_length, samples);
  const Vec2 along(-direction.y(), direction.x());
  // The fast path: one bounds check for the whole band (a scanline costs 5 x 21 samples by default).
  if (bandInside(image, centre, direction, along, half_length, band_half_width)) {
    const double max_code = static_cast<double>(image.max_code);
    if (image.depth == MonoImage::Depth::kU8)
      sampleBandInside(image.u8, max_code, centre, direction, along, half_length, band_half_width, samples);
    else
      sampleBandInside(image.u16, max_code, centre, direction, along, half_length, band_half_width, samples);
    return true;
  }
  const double scale = 1.0 / (2 * band_half_width + 1);
  for (int k = -half_length; k <= half_length; ++k) {
    const Vec2 p = centre + static_cast<double>(k) * direction;
    double sum = 0.0;
    for (int j = -band_half_width; j <= band_half_width; ++j) {
      double v = 0.0;
      if (!sampleBrightness(image, p + static_cast<double>(j) * along, v)) return false;
      sum += v;
    }
    samples[k + half_length] = sum * scale;
  }
  return true;
}

double scanlineNoiseSigma(const double* samples, int count, double floor) {
  if (count < 2 || count > kMaxScanlineSamples) return floor;
  double diffs[kMaxScanlineSamples];
  const int m = count - 1;
  for (int k = 0; k < m; ++k) diffs[k] = std::fabs(samples[k + 1] - samples[k]);
  std::nth_element(diffs, diffs + m / 2, diffs + m);
  // For Gaussian noise sigma, |difference| has median 0.6745 * sqrt(2) * sigma.
  return std::max(diffs[m / 2] / (0.6744897501960817 * 1.4142135623730951), floor);
}

namespace {

/// Sub-pixel peak of three equally spaced samples: Gaussian (log-parabola) fit when all are positive, the
/// shape a blurred step's derivative has; plain parabola otherwise. Offset in (-0.5, 0.5).
double peakOffset(double left, double centre, double right) {
  double offset = 0.0;
  if (left > 0.0 && centre > 0.0 && right > 0.0) {
    const double ll = std::log(left), lc = std::log(centre), lr = std::log(right);
    const double den = ll - 2.0 * lc + lr;
    if (den < -1e-12) offset = 0.5 * (ll - lr) / den;
  } else {
    const double den = left - 2.0 * centre + right;
    if (den < -1e-12) offset = 0.5 * (left - right) / den;
  }
  if (offset > 0.5) offset = 0.5;
  if (offset < -0.5) offset = -0.5;
  return offset;
}

}  // namespace

void textureLogLikelihoodPrefix(const double* samples, int count, int bins, double* out) {
  int counts[256];
  for (int b = 0; b < bins; ++b) counts[b] = 1;  // o <- {1 ... 1}
  double total = bins;                           // s_o (see header)
  double log_p = 0.0;                            // p <- 1
  for (int c = 0; c < count; ++c) {
    double s = samples[c];
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    const int bin = static_cast<int>(std::floor(s * (bins - 1)));
    log_p += std::log(counts[bin] / total);  // p <- p * o(bin) / s_o, in logs: no underflow
    counts[bin] += 1;
    total += 1.0;
    out[c] = log_p;
  }
}

double textureSplit(const double* samples, int count, int bins, double* log_gain) {
  if (log_gain != nullptr) *log_gain = 0.0;
  if (count < 4 || count > kMaxScanlineSamples || bins < 2 || bins > 256) return 0.5 * (count - 1);
  double prefix[kMaxScanlineSamples] = {};
  double suffix[kMaxScanlineSamples] = {};
  double reversed[kMaxScanlineSamples] = {};
  textureLogLikelihoodPrefix(samples, count, bins, prefix);
  for (int i = 0; i < count; ++i) reversed[i] = samples[count - 1 - i];
  textureLogLikelihoodPrefix(reversed, count, bins, suffix);  // suffix[k] = log f of the last k+1 samples
  int best_n = count / 2 - 1;
  double best = -1e300;
  for (int n = 1; n <= count - 3; ++n) {
    // Left: samples 0..n (n + 1 of them); right: n + 1..count - 1 (count - n - 1 of them).
    const double score = prefix[n] + suffix[count - n - 2];
    if (score > best) {
      best = score;
      best_n = n;
    }
  }
  if (log_gain != nullptr) *log_gain = best - prefix[count - 1];
  return best_n + 0.5;
}

namespace {

/// Sub-pixel position of the step around difference index `best` (between samples best and best + 1):
/// peak of the polarity-signed first differences smoothed by [1 2 1] / 4 (a blurred step's derivative is
/// bell-shaped; smoothing keeps one noisy difference from deciding), refined by the Gaussian fit.
double locateStep(const double* samples, int count, int best, int polarity, bool subpixel) {
  const int nw = count - 1;
  const auto diff = [&](int x) {
    const int c = x < 0 ? 0 : (x >= nw ? nw - 1 : x);
    return polarity * (samples[c + 1] - samples[c]);
  };
  const auto smooth = [&](int x) { return 0.25 * diff(x - 1) + 0.5 * diff(x) + 0.25 * diff(x + 1); };
  int peak = best;
  double peak_value = smooth(best);
  for (int x = best - 1; x <= best + 1; x += 2) {
    if (x < 0 || x >= nw) continue;
    const double v = smooth(x);
    if (v > peak_value) {
      peak_value = v;
      peak = x;
    }
  }
  double offset = 0.0;
  if (subpixel && peak > 0 && peak < nw - 1)
    offset = peakOffset(smooth(peak - 1), peak_value, smooth(peak + 1));
  return peak + 0.5 + offset;
}

}  // namespace

EdgeHit findEdge(const double* samples, int count, const EdgeSearchParams& params, int expected_polarity) {
  EdgeHit hit;
  const int w = params.step_window;
  if (count < 5 || count > kMaxScanlineSamples || w < 1 || 2 * w > count) return hit;
  // Eq. 4 generalised: the step between samples x and x + 1 is the difference of the w-sample means on
  // either side. w = 1 is the paper's w(x); w > 1 keeps the whole step of a blurred edge and averages the
  // noise down by sqrt(w / 2) relative to one difference.
  double left = 0.0, right = 0.0;
  for (int i = 0; i < w; ++i) {
    left += samples[i];
    right += samples[w + i];
  }
  // Pass 1: the step at every position (x between samples x and x + 1) and the strongest one.
  double steps[kMaxScanlineSamples] = {};
  const auto signedValue = [&](double step) {
    return expected_polarity > 0 ? step : (expected_polarity < 0 ? -step : std::fabs(step));
  };
  double max_value = 0.0;
  for (int x = w - 1; x + w < count; ++x) {
    if (x > w - 1) {  // slide both windows one sample
      left += samples[x] - samples[x - w];
      right += samples[x + w] - samples[x];
    }
    steps[x] = (right - left) / w;
    max_value = std::max(max_value, signedValue(steps[x]));
  }
  const double centre_index = 0.5 * (count - 1);
  const double step_sigma = scanlineNoiseSigma(samples, count, params.noise_floor) * std::sqrt(2.0 / w);
  const double threshold = std::max(params.step_min_z * step_sigma, params.candidate_min_share * max_value);
  // Pass 2: among the local maxima (over +-w, one per blurred step) that pass both the noise test and the
  // share of the strongest, the one nearest the prediction (the scanline centre). A short scanline across a
  // small target also crosses neighbouring edges (a panel 6 px from the body); the strongest of them is
  // often not the one predicted, while the prediction is good to a pixel or two while tracking.
  int best = -1;
  double best_value = 0.0;
  double best_distance = 1e300;
  for (int x = w - 1; x + w < count; ++x) {
    const double value = signedValue(steps[x]);
    if (value <= 0.0 || value < threshold) continue;
    bool local_max = true;
    for (int j = std::max(w - 1, x - w); j <= std::min(count - w - 1, x + w) && local_max; ++j)
      local_max = j == x || signedValue(steps[j]) < value || (signedValue(steps[j]) == value && j > x);
    if (!local_max) continue;
    const double distance = std::fabs(x + 0.5 - centre_index);
    if (distance < best_distance) {
      best_distance = distance;
      best_value = value;
      best = x;
    }
  }
  if (best >= 0) {
    const double best_step = steps[best];
    hit.method = best_value >= params.contrast_delta ? EdgeMethod::kGradient : EdgeMethod::kStep;
    hit.polarity = best_step >= 0.0 ? 1 : -1;
    hit.strength = best_value;
    hit.z = best_value / step_sigma;
    hit.offset_px = locateStep(samples, count, best, hit.polarity, params.subpixel) - centre_index;
    return hit;
  }
  // No significant step: texture segmentation (eq. 5, Algorithm 1).
  double gain = 0.0;
  const double split = textureSplit(samples, count, params.texture_bins, &gain);
  if (gain < params.texture_min_log_gain) return hit;  // no edge on this scanline
  hit.method = EdgeMethod::kTexture;
  hit.strength = 0.0;
  const int n = static_cast<int>(split);
  double left_sum = 0.0, right_sum = 0.0, left_sq = 0.0, right_sq = 0.0;
  for (int i = 0; i <= n; ++i) {
    left_sum += samples[i];
    left_sq += samples[i] * samples[i];
  }
  for (int i = n + 1; i < count; ++i) {
    right_sum += samples[i];
    right_sq += samples[i] * samples[i];
  }
  const double left_mean = left_sum / (n + 1), right_mean = right_sum / (count - n - 1);
  const double floor2 = params.noise_floor * params.noise_floor;
  const double left_var = std::max(left_sq / (n + 1) - left_mean * left_mean, floor2);
  const double right_var = std::max(right_sq / (count - n - 1) - right_mean * right_mean, floor2);
  if (std::max(left_var, right_var) < params.texture_min_variance_ratio * std::min(left_var, right_var)) {
    hit.method = EdgeMethod::kNone;  // same spread on both sides and no significant step: noise
    return hit;
  }
  hit.polarity = right_mean >= left_mean ? 1 : -1;
  hit.offset_px = split - centre_index;
  if (!params.subpixel) return hit;
  // The split is pixel-level and biased: blurred samples straddling the edge look unlikely under the class
  // with the narrower histogram and go to the other one (measured ~0.35 px towards the uniform target).
  // Localise within one sample of the split by the eq. 4 difference signed by the split's polarity.
  const int nw = count - 1;
  int peak = -1;
  double peak_value = 0.0;
  for (int x = n - 1; x <= n + 1; ++x) {
    if (x < 0 || x >= nw) continue;
    const double d = hit.polarity * (samples[x + 1] - samples[x]);
    if (d > peak_value) {
      peak_value = d;
      peak = x;
    }
  }
  if (peak < 0) return hit;
  double offset = 0.0;
  if (peak > 0 && peak < nw - 1)
    offset = peakOffset(hit.polarity * (samples[peak] - samples[peak - 1]), peak_value,
                        hit.polarity * (samples[peak + 2] - samples[peak + 1]));
  hit.offset_px = peak + 0.5 + offset - centre_index;
  return hit;
}

}  // namespace visnav
