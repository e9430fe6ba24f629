// Scanline edge study: how often the edge detector puts a point within 1 px of a true edge, how often it
// puts one elsewhere, and how often it answers on a scanline with no edge, over a grid of noise (0.02-0.12),
// blur (0.3-1.2 px), contrast (0.1-0.5) and background ramps, 8-bit quantised. It compares the paper's rule
// (eq. 4's one-pixel difference against delta 0.2, else Algorithm 1 with a 1-nat gain, one scanline) with
// the detector as configured (band of 5 lines, w-sample step test, texture split gated by spread).
// The last row adds the noise before the blur, as the campaign's renderer does (drivers/synthetic): blurred
// noise is correlated from pixel to pixel, which the scanline's noise estimate (first differences) does not
// see. Seeded: the printout is the same on every run. Usage: edge_study [trials per cell, default 2000]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "visnav/core/rng.hpp"
#include "visnav/nearrange/edge_detector.hpp"

namespace {

using visnav::EdgeHit;
using visnav::EdgeMethod;
using visnav::EdgeSearchParams;
using visnav::Pcg32;

constexpr int kCount = 21;  // scanline_half_length_px = 10

double gaussian(Pcg32& rng) {
  const double u1 = std::max(rng.uniform(), 1e-12);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * rng.uniform());
}

/// The paper's rule as published (sec. II-D): argmax of w(x) = s(x+1) - s(x), an edge when max(w) - mean(w)
/// >= delta; otherwise the texture split of Algorithm 1 when it gains at least 1 nat.
EdgeHit paperRule(const double* s) {
  EdgeHit hit;
  double w[kCount];
  double sum = 0.0, best_value = -1e300;
  int best = 0;
  for (int x = 0; x + 1 < kCount; ++x) {
    w[x] = std::fabs(s[x + 1] - s[x]);
    sum += w[x];
    if (w[x] > best_value) {
      best_value = w[x];
      best = x;
    }
  }
  if (best_value - sum / (kCount - 1) >= 0.2) {
    hit.method = EdgeMethod::kGradient;
    hit.offset_px = best + 0.5 - 0.5 * (kCount - 1);
    return hit;
  }
  double gain = 0.0;
  const double split = visnav::textureSplit(s, kCount, 32, &gain);
  if (gain < 1.0) return hit;
  hit.method = EdgeMethod::kTexture;
  hit.offset_px = split - 0.5 * (kCount - 1);
  return hit;
}

constexpr int kMaxBand = 5;
constexpr int kTaps = 7;
constexpr int kPad = kTaps / 2;

/// band x kCount samples of white noise (sigma) blurred by a normalised Gaussian of `blur` px, 7 taps in
/// x and y: the renderer's order (noise, then blur).
void blurredNoise(Pcg32& rng, double sigma, double blur, int band, double (&out)[kMaxBand][kCount]) {
  double kernel[kTaps];
  double total = 0.0;
  for (int i = 0; i < kTaps; ++i) {
    kernel[i] = std::exp(-0.5 * (i - kPad) * (i - kPad) / (blur * blur));
    total += kernel[i];
  }
  for (double& k : kernel) k /= total;
  double field[kMaxBand + 2 * kPad][kCount + 2 * kPad];
  for (auto& row : field)
    for (double& v : row) v = sigma * gaussian(rng);
  double rows[kMaxBand + 2 * kPad][kCount] = {};
  for (int y = 0; y < band + 2 * kPad; ++y)
    for (int x = 0; x < kCount; ++x)
      for (int i = 0; i < kTaps; ++i) rows[y][x] += kernel[i] * field[y][x + i];
  for (int y = 0; y < band; ++y)
    for (int x = 0; x < kCount; ++x) {
      out[y][x] = 0.0;
      for (int i = 0; i < kTaps; ++i) out[y][x] += kernel[i] * rows[y + i][x];
    }
}

struct Tally {
  double good = 0.0, bad = 0.0, false_alarm = 0.0, abs_error = 0.0;
  int edge_cells = 0, empty_cells = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const int trials = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2000;
  struct Variant {
    const char* name;
    int band_lines;
    bool paper;
    bool noise_blurred;
  } variants[] = {{"paper eq. 4 + Algorithm 1, one line", 1, true, false},
                  {"visnav detector, one line", 1, false, false},
                  {"visnav detector, band of 5 (default)", 5, false, false},
                  {"the same, noise blurred with the image", 5, false, true}};
  std::printf("%-40s %8s %8s %8s %8s\n", "detector", "good", "bad", "empty", "mae_px");
  for (const Variant& v : variants) {
    Pcg32 rng(2026);
    Tally t;
    EdgeSearchParams params;
    params.noise_floor /= std::sqrt(static_cast<double>(v.band_lines));
    for (double sigma : {0.02, 0.05, 0.08, 0.12}) {
      for (double blur : {0.3, 0.8, 1.2}) {
        for (double contrast : {0.0, 0.1, 0.2, 0.3, 0.5}) {
          int good = 0, bad = 0;
          double abs_error = 0.0;
          for (int trial = 0; trial < trials; ++trial) {
            const double edge = 10.0 + 6.0 * rng.uniform() - 3.0;
            const double level = 0.2 + 0.4 * rng.uniform();
            const double ramp = (rng.uniform() - 0.5) * 0.01;
            const double spread = std::sqrt(blur * blur + 0.35 * 0.35);  // optics and pixel area
            // Noise blurred with the image: a white field blurred by the optics' 7-tap Gaussian.
            double noise[kMaxBand][kCount] = {};
            if (v.noise_blurred) blurredNoise(rng, sigma, blur, v.band_lines, noise);
            double s[kCount];
            for (int k = 0; k < kCount; ++k) {
              double acc = 0.0;
              for (int j = 0; j < v.band_lines; ++j) {
                const double value =
                    level + ramp * k +
                    contrast * 0.5 * (1.0 + std::erf((k - edge) / (spread * std::sqrt(2.0)))) +
                    (v.noise_blurred ? noise[j][k] : sigma * gaussian(rng));
                acc += std::round(std::clamp(value, 0.0, 1.0) * 255.0) / 255.0;
              }
              s[k] = acc / v.band_lines;
            }
            const EdgeHit hit = v.paper ? paperRule(s) : visnav::findEdge(s, kCount, params, 0);
            if (hit.method == EdgeMethod::kNone) continue;
            const double error = std::fabs(10.0 + hit.offset_px - edge);
            if (contrast > 0.0 && error <= 1.0) {
              ++good;
              abs_error += error;
            } else {
              ++bad;
            }
          }
          if (contrast > 0.0) {
            t.good += static_cast<double>(good) / trials;
            t.bad += static_cast<double>(bad) / trials;
            t.abs_error += good > 0 ? abs_error / good : 0.5;
            ++t.edge_cells;
          } else {
            t.false_alarm += static_cast<double>(bad) / trials;
            ++t.empty_cells;
          }
        }
      }
    }
    std::printf("%-40s %8.3f %8.3f %8.3f %8.3f\n", v.name, t.good / t.edge_cells, t.bad / t.edge_cells,
                t.false_alarm / t.empty_cells, t.abs_error / t.edge_cells);
  }
  std::printf(
      "good / bad: a point within 1 px of the edge / farther (mean over 48 cells with an edge); empty: a "
      "point on a scanline with no edge (mean over 12 cells); %d scanlines per cell\n",
      trials);
  return 0;
}
