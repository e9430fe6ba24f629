#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "visnav/core/rng.hpp"
#include "visnav/nearrange/edge_detector.hpp"

namespace visnav {
namespace {

/// Scanline across an ideal step at `edge` (in samples from sample 0's centre), each sample the mean of its
/// unit cell (area coverage), blurred by a 3-tap [0.25 0.5 0.25] kernel like a mild optical PSF.
void stepProfile(double edge, double low, double high, int count, double* out) {
  double raw[kMaxScanlineSamples];
  for (int k = 0; k < count; ++k) {
    const double cover = std::clamp(k + 0.5 - edge, 0.0, 1.0);  // share of cell [k-0.5,k+0.5) beyond edge
    raw[k] = low + (high - low) * cover;
  }
  for (int k = 0; k < count; ++k) {
    const double l = raw[std::max(k - 1, 0)], r = raw[std::min(k + 1, count - 1)];
    out[k] = 0.25 * l + 0.5 * raw[k] + 0.25 * r;
  }
}

TEST(EdgeDetector, GradientEdgeIsSubPixelAccurate) {
  constexpr int kCount = 15;
  double s[kCount];
  double worst = 0.0;
  for (double edge = 5.0; edge <= 9.0; edge += 0.05) {
    stepProfile(edge, 0.1, 0.8, kCount, s);
    const EdgeHit hit = findEdge(s, kCount, EdgeSearchParams{}, 0);
    ASSERT_EQ(hit.method, EdgeMethod::kGradient);
    EXPECT_EQ(hit.polarity, 1);
    // offset is relative to the centre sample (index 7)
    worst = std::max(worst, std::fabs(hit.offset_px - (edge - 7.0)));
  }
  EXPECT_LT(worst, 0.08);
}

TEST(EdgeDetector, PixelLevelModeIsQuantised) {
  constexpr int kCount = 15;
  double s[kCount];
  stepProfile(7.3, 0.1, 0.8, kCount, s);
  EdgeSearchParams params;
  params.subpixel = false;
  const EdgeHit hit = findEdge(s, kCount, params, 0);
  EXPECT_DOUBLE_EQ(hit.offset_px - std::floor(hit.offset_px), 0.5);
}

TEST(EdgeDetector, ExpectedPolaritySelectsTheMatchingStep) {
  // Bright -> dark at 4.0 (strong), dark -> bright at 10.0 (weaker but still above delta).
  constexpr int kCount = 15;
  double s[kCount];
  for (int k = 0; k < kCount; ++k) s[k] = k < 4 ? 0.9 : (k < 10 ? 0.1 : 0.45);
  EXPECT_EQ(findEdge(s, kCount, EdgeSearchParams{}, 0).polarity, -1);
  const EdgeHit rising = findEdge(s, kCount, EdgeSearchParams{}, +1);
  EXPECT_EQ(rising.polarity, 1);
  EXPECT_NEAR(rising.offset_px, 9.5 - 7.0, 0.3);
}

TEST(EdgeDetector, WeakContrastFallsBackToTextureSplit) {
  // Same mean brightness, different texture: uniform grey vs. strongly alternating pixels.
  constexpr int kCount = 21;
  double s[kCount];
  Pcg32 rng(7);
  for (int k = 0; k < kCount; ++k) s[k] = k < 12 ? 0.5 + 0.01 * rng.uniform() : (k % 2 == 0 ? 0.35 : 0.62);
  // With the step test off, only Algorithm 1 can find it.
  EdgeSearchParams texture_only;
  texture_only.step_min_z = 1e9;
  const EdgeHit hit = findEdge(s, kCount, texture_only, 0);
  EXPECT_EQ(hit.method, EdgeMethod::kTexture);
  EXPECT_NEAR(hit.offset_px + 10.0, 11.5, 1.01);
  // With defaults the windowed means differ at the boundary too: either way the point lands on it.
  EXPECT_NEAR(findEdge(s, kCount, EdgeSearchParams{}, 0).offset_px + 10.0, 11.5, 1.01);
}

/// Mean signed error of texture hits across a weak step from a uniform target (0.40, sigma 0.005) to a
/// noisy brighter background (0.50, sigma 0.04), over sub-pixel edge positions and noise draws.
double textureBias(bool subpixel, int& texture_hits) {
  constexpr int kCount = 21;
  EdgeSearchParams params;
  params.subpixel = subpixel;
  params.step_min_z = 1e9;  // the texture path alone (a 0.1 step this clean is otherwise a weak step)
  Pcg32 rng(17);
  double sum = 0.0;
  texture_hits = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double edge = 9.5 + (trial % 20) * 0.05;
    double s[kCount];
    stepProfile(edge, 0.40, 0.50, kCount, s);
    for (int k = 0; k < kCount; ++k) s[k] += (k < edge ? 0.005 : 0.04) * (2.0 * rng.uniform() - 1.0) * 1.732;
    const EdgeHit hit = findEdge(s, kCount, params, 0);
    if (hit.method != EdgeMethod::kTexture) continue;
    ++texture_hits;
    sum += hit.offset_px - (edge - 10.0);
  }
  return texture_hits > 0 ? sum / texture_hits : 1e9;
}

TEST(EdgeDetector, TextureSplitIsRefinedToAnUnbiasedSubPixelEdge) {
  // The pixel-level split gives the blurred straddling samples to the wider (noisier) class, which pulls
  // the edge towards the uniform side; the sub-pixel refinement must remove that bias.
  int pixel_hits = 0, subpixel_hits = 0;
  const double pixel_bias = textureBias(false, pixel_hits);
  const double subpixel_bias = textureBias(true, subpixel_hits);
  ASSERT_GT(pixel_hits, 300);
  ASSERT_GT(subpixel_hits, 300);
  EXPECT_LT(pixel_bias, -0.15);  // the bias is real (this is what made low_contrast fail the 0.25 px bound)
  EXPECT_LT(std::fabs(subpixel_bias), 0.08);
}

TEST(EdgeDetector, UniformScanlineHasNoEdge) {
  double s[15];
  Pcg32 rng(9);
  for (double& v : s) v = 0.3 + 0.02 * rng.uniform();
  EXPECT_EQ(findEdge(s, 15, EdgeSearchParams{}, 0).method, EdgeMethod::kNone);
}

/// Gaussian draw from two uniforms (Box-Muller), for noise models of the statistical tests below.
double gaussian(Pcg32& rng) {
  const double u1 = std::max(rng.uniform(), 1e-12);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * rng.uniform());
}

/// 21 samples: level + ramp * k + a step of `contrast` at `edge` blurred by a Gaussian of `blur` px, Gaussian
/// noise `sigma`, quantised to 8 bits like a camera frame.
void noisyStep(Pcg32& rng, double edge, double contrast, double blur, double ramp, double sigma, double* s) {
  const double level = 0.2 + 0.4 * rng.uniform();
  for (int k = 0; k < 21; ++k) {
    const double v = level + ramp * k +
                     contrast * 0.5 * (1.0 + std::erf((k - edge) / (blur * 1.4142135623730951))) +
                     sigma * gaussian(rng);
    s[k] = std::round(std::clamp(v, 0.0, 1.0) * 255.0) / 255.0;
  }
}

TEST(EdgeDetector, NoiseAndRampsAloneRarelyGiveAPoint) {
  // "The texture fallback must not pick noise": scanlines with no edge, noise sigma 0.02..0.12 over a
  // background ramp of up to 0.005 per px. eq. 4 with delta 0.2 and the old 1-nat texture gain answered on
  // 23 % of such scanlines; a point from nothing is what drags RANSAC onto a wrong line.
  Pcg32 rng(23);
  int hits = 0;
  constexpr int kTrials = 4000;
  for (int trial = 0; trial < kTrials; ++trial) {
    double s[21];
    const double sigma = 0.02 + 0.1 * rng.uniform();
    noisyStep(rng, 10.0, 0.0, 1.0, (rng.uniform() - 0.5) * 0.01, sigma, s);
    if (findEdge(s, 21, EdgeSearchParams{}, 0).method != EdgeMethod::kNone) ++hits;
  }
  EXPECT_LT(hits, kTrials / 50);
}

TEST(EdgeDetector, BlurredStepBelowDeltaPerPixelIsFoundAndLocated) {
  // A 0.27 step blurred over two pixels (campaign box/1: 0.37 -> 0.23 -> 0.10) never has a one-pixel
  // difference of delta = 0.2: eq. 4 alone missed it on every scanline. The w-sample step finds it, and the
  // smoothed-derivative peak puts it within 0.2 px on average (one scanline, no band averaging).
  Pcg32 rng(29);
  int found = 0;
  double abs_error = 0.0;
  constexpr int kTrials = 1000;
  for (int trial = 0; trial < kTrials; ++trial) {
    double s[21];
    const double edge = 8.0 + 4.0 * rng.uniform();
    noisyStep(rng, edge, -0.27, 0.8, 0.0, 0.02, s);
    const EdgeHit hit = findEdge(s, 21, EdgeSearchParams{}, 0);
    if (hit.method == EdgeMethod::kNone || std::fabs(hit.offset_px + 10.0 - edge) > 1.0) continue;
    ++found;
    EXPECT_EQ(hit.polarity, -1);
    abs_error += std::fabs(hit.offset_px + 10.0 - edge);
  }
  EXPECT_GE(found, kTrials * 99 / 100);
  EXPECT_LT(abs_error / found, 0.2);
}

TEST(EdgeDetector, WeakSignificantStepIsReportedAsWeakContrast) {
  double s[21];
  for (int k = 0; k < 21; ++k) s[k] = k < 10 ? 0.30 : 0.38;
  const EdgeHit hit = findEdge(s, 21, EdgeSearchParams{}, 0);
  EXPECT_EQ(hit.method, EdgeMethod::kStep);
  EXPECT_NEAR(hit.strength, 0.08, 1e-12);
  EXPECT_NEAR(hit.offset_px + 10.0, 9.5, 0.05);
  for (int k = 0; k < 21; ++k) s[k] = k < 10 ? 0.30 : 0.58;
  EXPECT_EQ(findEdge(s, 21, EdgeSearchParams{}, 0).method, EdgeMethod::kGradient);
}

TEST(EdgeDetector, BandSamplesAverageAlongTheEdge) {
  // 8x8 image, pixel value = 10 * row + col: the band mean along a vertical scanline direction's
  // perpendicular (rows fixed, columns +-1) equals the centre column's value for a linear image, and a
  // band of half-width 0 is the plain scanline.
  std::uint8_t pixels[8 * 8];
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) pixels[r * 8 + c] = static_cast<std::uint8_t>(10 * r + c * c);
  const MonoImage image = MonoImage::from8(ImageView8(pixels, 8, 8));
  double band[5], plain[5], manual[5];
  ASSERT_TRUE(sampleScanlineBand(image, Vec2(4.5, 4.5), Vec2(0.0, 1.0), 2, 1, band));
  ASSERT_TRUE(sampleScanline(image, Vec2(4.5, 4.5), Vec2(0.0, 1.0), 2, plain));
  for (int k = -2; k <= 2; ++k) {
    double sum = 0.0;
    for (int j = -1; j <= 1; ++j) {
      double v = 0.0;
      ASSERT_TRUE(sampleBrightness(image, Vec2(4.5 - j, 4.5 + k), v));
      sum += v;
    }
    manual[k + 2] = sum / 3.0;
  }
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(band[k], manual[k], 1e-12);
  EXPECT_GT(band[2], plain[2]);  // c^2 is convex: the mean of columns 3..5 exceeds column 4's value
  ASSERT_TRUE(sampleScanlineBand(image, Vec2(4.5, 4.5), Vec2(0.0, 1.0), 2, 0, band));
  for (int k = 0; k < 5; ++k) EXPECT_EQ(band[k], plain[k]);
  EXPECT_FALSE(sampleScanlineBand(image, Vec2(1.0, 4.5), Vec2(0.0, 1.0), 2, 1, band));  // column -0.5
}

TEST(EdgeDetector, BandSamplingIsExactlyThePerSampleBilinearEverywhere) {
  // The band sampler checks the band's corners once and then samples without per-sample checks: its values
  // must equal sampleBrightness's bit for bit, and a band that leaves the image anywhere must still fail,
  // at random centres, directions and depths, near and across the borders.
  constexpr int kW = 40, kH = 30;
  std::uint8_t pixels8[kW * kH];
  std::uint16_t pixels16[kW * kH];
  Pcg32 rng(7U, 3U);
  for (int i = 0; i < kW * kH; ++i) {
    pixels8[i] = static_cast<std::uint8_t>(rng.uniform() * 255.0);
    pixels16[i] = static_cast<std::uint16_t>(rng.uniform() * 4095.0);
  }
  const MonoImage images[2] = {MonoImage::from8(ImageView8(pixels8, kW, kH)),
                               MonoImage::from16(ImageView16(pixels16, kW, kH), 4095)};
  int inside = 0, outside = 0;
  for (const MonoImage& image : images) {
    for (int trial = 0; trial < 4000; ++trial) {
      const Vec2 centre(-2.0 + rng.uniform() * (kW + 4.0), -2.0 + rng.uniform() * (kH + 4.0));
      const double angle = rng.uniform() * 6.283185307179586;
      const Vec2 direction(std::cos(angle), std::sin(angle));
      const int half = 1 + static_cast<int>(rng.uniform() * 8.0);
      const int band = 1 + static_cast<int>(rng.uniform() * 3.0);
      double got[kMaxScanlineSamples];
      const bool ok = sampleScanlineBand(image, centre, direction, half, band, got);
      const Vec2 along(-direction.y(), direction.x());
      bool want_ok = true;
      double want[kMaxScanlineSamples];
      for (int k = -half; k <= half && want_ok; ++k) {
        const Vec2 p = centre + static_cast<double>(k) * direction;
        double sum = 0.0;
        for (int j = -band; j <= band && want_ok; ++j) {
          double v = 0.0;
          want_ok = sampleBrightness(image, p + static_cast<double>(j) * along, v);
          sum += v;
        }
        want[k + half] = sum * (1.0 / (2 * band + 1));
      }
      ASSERT_EQ(ok, want_ok) << "trial " << trial;
      if (!ok) {
        ++outside;
        continue;
      }
      ++inside;
      for (int k = 0; k <= 2 * half; ++k) ASSERT_EQ(got[k], want[k]) << "trial " << trial << " k " << k;
    }
  }
  EXPECT_GT(inside, 1000);  // both branches exercised
  EXPECT_GT(outside, 1000);
}

TEST(EdgeDetector, TextureLikelihoodIsDirichletMultinomial) {
  // All samples in one bin: p = prod_k (1 + k) / (bins + k).
  double s[6] = {0.5, 0.5, 0.5, 0.5, 0.5, 0.5};
  double out[6];
  textureLogLikelihoodPrefix(s, 6, 32, out);
  double expected = 0.0;
  for (int k = 0; k < 6; ++k) {
    expected += std::log((1.0 + k) / (32.0 + k));
    EXPECT_NEAR(out[k], expected, 1e-12);
  }
}

TEST(EdgeDetector, TextureSplitFindsMeanShiftToo) {
  double s[20];
  for (int k = 0; k < 20; ++k) s[k] = k < 8 ? 0.2 : 0.7;
  EXPECT_DOUBLE_EQ(textureSplit(s, 20, 32), 7.5);
}

TEST(EdgeDetector, BilinearSamplingUsesPixelCentresAtHalf) {
  std::uint8_t pixels[4 * 4] = {0, 100, 200, 250, 0, 100, 200, 250, 0, 100, 200, 250, 0, 100, 200, 250};
  const MonoImage image = MonoImage::from8(ImageView8(pixels, 4, 4));
  double v = 0.0;
  ASSERT_TRUE(sampleBrightness(image, Vec2(1.5, 1.5), v));
  EXPECT_NEAR(v, 100.0 / 255.0, 1e-12);
  ASSERT_TRUE(sampleBrightness(image, Vec2(2.0, 2.2), v));
  EXPECT_NEAR(v, 150.0 / 255.0, 1e-12);
  EXPECT_FALSE(sampleBrightness(image, Vec2(0.2, 1.0), v));
  std::uint16_t deep[4] = {0, 1023, 0, 1023};
  const MonoImage image16 = MonoImage::from16(ImageView16(deep, 2, 2), 1023);
  ASSERT_TRUE(sampleBrightness(image16, Vec2(1.0, 1.0), v));
  EXPECT_NEAR(v, 0.5, 1e-12);
}

}  // namespace
}  // namespace visnav
