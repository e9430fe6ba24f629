// Edge filter (eq. 9/10), histogram filter (eq. 11/12), weighted sum (eq. 13/14) against independently
// computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "visnav/farrange/edge_filter.hpp"
#include "visnav/farrange/far_range_params.hpp"
#include "visnav/farrange/histogram_filter.hpp"
#include "visnav/farrange/weighted_sum.hpp"

namespace visnav::far {
namespace {

struct Image8 {
  int w, h;
  std::vector<std::uint8_t> px;
  Image8(int width, int height, std::uint8_t value)
      : w(width), h(height), px(static_cast<std::size_t>(width * height), value) {}
  std::uint8_t& at(int x, int y) { return px[static_cast<std::size_t>(y * w + x)]; }
  MonoImage view() const { return MonoImage::from8(ImageView8(px.data(), w, h)); }
};

// Direct 3x3 correlation with eq. 9's kernels (centre weight c: 1 as printed, 2 for Sobel).
int directMagnitude(const Image8& im, int x, int y, int c) {
  const auto p = [&](int dx, int dy) {
    return static_cast<int>(im.px[static_cast<std::size_t>((y + dy) * im.w + x + dx)]);
  };
  const int jx = -p(-1, -1) - c * p(-1, 0) - p(-1, 1) + p(1, -1) + c * p(1, 0) + p(1, 1);
  const int jy = -p(-1, -1) - c * p(0, -1) - p(1, -1) + p(-1, 1) + c * p(0, 1) + p(1, 1);
  return std::abs(jx) + std::abs(jy);
}

ResponseImage responseFor(int w, int h, const Roi& roi) {
  ResponseImage r;
  r.init(w, h);
  r.setRoi(roi);
  return r;
}

TEST(EdgeFilter, SobelAndPrewittMatchDirectConvolutionNormalisedByTheMaximum) {
  Image8 im(40, 30, 10);
  std::uint32_t state = 12345U;
  for (auto& v : im.px) {  // deterministic texture
    state = state * 1664525U + 1013904223U;
    v = static_cast<std::uint8_t>(state >> 24U);
  }
  for (const EdgeKernel kernel : {EdgeKernel::kSobel, EdgeKernel::kPrewitt}) {
    const int c = kernel == EdgeKernel::kSobel ? 2 : 1;
    EdgeFilter filter;
    filter.init(40, 30, {kernel, 100.0, 1.0, 0.0});
    const Roi roi = Roi::full(40, 30);
    ResponseImage out = responseFor(40, 30, roi);
    filter.apply(im.view(), roi, out);
    int max_x = 0;
    for (int y = 1; y < 29; ++y)
      for (int x = 1; x < 39; ++x) max_x = std::max(max_x, directMagnitude(im, x, y, c));
    EXPECT_EQ(filter.lastMaximum(), max_x);
    EXPECT_EQ(filter.lastReference(), max_x);
    for (int y = 0; y < 30; ++y) {
      for (int x = 0; x < 40; ++x) {
        const bool border = x == 0 || y == 0 || x == 39 || y == 29;
        const double expected = border ? 0.0 : 255.0 * directMagnitude(im, x, y, c) / max_x;
        EXPECT_NEAR(out.atImage(x, y), expected, 1.0) << "kernel " << c << " at " << x << "," << y;
      }
    }
  }
}

TEST(EdgeFilter, StepGainIsFourForSobelThreeForPrewitt) {
  Image8 im(20, 10, 0);
  for (int y = 0; y < 10; ++y)
    for (int x = 10; x < 20; ++x) im.at(x, y) = 100;
  for (const auto& [kernel, gain] : {std::pair{EdgeKernel::kSobel, 4}, std::pair{EdgeKernel::kPrewitt, 3}}) {
    EdgeFilter filter;
    filter.init(20, 10, {kernel, 100.0, 1.0, 0.0});
    ResponseImage out = responseFor(20, 10, Roi::full(20, 10));
    filter.apply(im.view(), Roi::full(20, 10), out);
    EXPECT_EQ(filter.lastMaximum(), gain * 100);
    EXPECT_EQ(filter.gain(), gain);
  }
}

TEST(EdgeFilter, OneBrightEdgeSuppressesADimTargetUnderMaxNormalisationButNotUnderThePercentile) {
  // A dim square (contrast 60) and a bright bar (contrast 240) on a noisy background.
  Image8 im(120, 80, 20);
  std::uint32_t state = 7U;
  for (auto& v : im.px) {
    state = state * 1664525U + 1013904223U;
    v = static_cast<std::uint8_t>(20 + static_cast<int>(state >> 29U));  // noise 0..7
  }
  for (int y = 30; y < 40; ++y)
    for (int x = 20; x < 30; ++x) im.at(x, y) = 80;
  for (int y = 10; y < 14; ++y)
    for (int x = 50; x < 110; ++x) im.at(x, y) = 255;
  const Roi roi = Roi::full(120, 80);
  ResponseImage out = responseFor(120, 80, roi);
  EdgeFilter paper;
  paper.init(120, 80, {EdgeKernel::kSobel, 100.0, 1.0, 0.0});
  paper.apply(im.view(), roi, out);
  const int dim_paper = out.atImage(20, 35);  // on the square's left edge
  EdgeFilter robust;
  robust.init(120, 80, {EdgeKernel::kSobel, 50.0, 3.0, 0.02});
  robust.apply(im.view(), roi, out);
  const int dim_robust = out.atImage(20, 35);
  EXPECT_LT(dim_paper, 0.3 * 255) << "max normalisation: the bright bar sets the scale";
  EXPECT_EQ(dim_robust, 255) << "3 x median of |Jx|+|Jy| is the noise scale: the square's edge saturates";
  EXPECT_LT(robust.lastReference(), 4 * 60);
}

TEST(EdgeFilter, SixteenBitInputGivesTheEightBitResponse) {
  Image8 im(30, 20, 30);
  for (int y = 5; y < 15; ++y)
    for (int x = 8; x < 22; ++x) im.at(x, y) = static_cast<std::uint8_t>(120 + 3 * x);
  std::vector<std::uint16_t> px16(im.px.size());
  for (std::size_t i = 0; i < px16.size(); ++i)
    px16[i] = static_cast<std::uint16_t>(im.px[i] * 16);  // 12 bit
  const MonoImage im16 = MonoImage::from16(ImageView16(px16.data(), 30, 20), 4095);
  const Roi roi = Roi::full(30, 20);
  EdgeFilter a;
  EdgeFilter b;
  a.init(30, 20, {});
  b.init(30, 20, {});
  ResponseImage ra = responseFor(30, 20, roi);
  ResponseImage rb = responseFor(30, 20, roi);
  a.apply(im.view(), roi, ra);
  b.apply(im16, roi, rb);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) EXPECT_NEAR(ra.atImage(x, y), rb.atImage(x, y), 1) << x << "," << y;
}

TEST(EdgeFilter, RegionOfInterestSeesTheSameGradients) {
  Image8 im(50, 40, 0);
  for (int y = 10; y < 30; ++y)
    for (int x = 15; x < 35; ++x) im.at(x, y) = 200;
  EdgeFilter filter;
  filter.init(50, 40, {});
  const Roi full = Roi::full(50, 40);
  const Roi roi{10, 5, 30, 30};
  ResponseImage a = responseFor(50, 40, full);
  ResponseImage b = responseFor(50, 40, roi);
  filter.apply(im.view(), full, a);
  filter.apply(im.view(), roi, b);  // same maximum inside: same normalisation
  for (int y = roi.y0; y < roi.y0 + roi.height; ++y)
    for (int x = roi.x0; x < roi.x0 + roi.width; ++x) EXPECT_EQ(a.atImage(x, y), b.atImage(x, y));
}

TEST(HistogramFilter, RarityTableIsEq12OfTheRawCounts) {
  Image8 im(32, 32, 10);  // 1024 px: 1000 at 10, 20 at 200, 4 at 255
  int placed = 0;
  for (int i = 0; i < 24; ++i) im.px[static_cast<std::size_t>(100 + 7 * i)] = placed++ < 20 ? 200 : 255;
  HistogramFilter filter;
  filter.init(100.0);
  const Roi roi = Roi::full(32, 32);
  ResponseImage out = responseFor(32, 32, roi);
  filter.apply(im.view(), roi, out);
  EXPECT_EQ(filter.histogram()[10], 1000U);
  EXPECT_EQ(filter.histogram()[200], 20U);
  EXPECT_EQ(filter.histogram()[255], 4U);
  EXPECT_EQ(filter.responseTable()[10], 0);  // exp(-100)
  EXPECT_EQ(filter.responseTable()[200],
            static_cast<int>(std::lround(255.0 * std::exp(-20.0 / 1000.0 * 100.0))));
  EXPECT_EQ(filter.responseTable()[255],
            static_cast<int>(std::lround(255.0 * std::exp(-4.0 / 1000.0 * 100.0))));
  EXPECT_EQ(filter.responseTable()[50], 255);  // empty bin: exp(0)
  EXPECT_EQ(out.atImage(100 % 32, 100 / 32), filter.responseTable()[200]);
  EXPECT_EQ(out.atImage(0, 0), 0);
}

TEST(HistogramFilter, SixteenBitSamplesAreBinnedAsEq11) {
  EXPECT_EQ(HistogramFilter::binOf(0, 4095), 0);
  EXPECT_EQ(HistogramFilter::binOf(4095, 4095), 255);
  EXPECT_EQ(HistogramFilter::binOf(2048, 4095), static_cast<int>(std::floor(2048.0 / 4095.0 * 255.0)));
  EXPECT_EQ(HistogramFilter::binOf(5000, 4095), 255);  // above max code: top bin
  std::vector<std::uint16_t> px(64, 100);
  px[5] = 4000;
  HistogramFilter filter;
  filter.init(100.0);
  ResponseImage out = responseFor(8, 8, Roi::full(8, 8));
  filter.apply(MonoImage::from16(ImageView16(px.data(), 8, 8), 4095), Roi::full(8, 8), out);
  EXPECT_EQ(filter.histogram()[static_cast<std::size_t>(HistogramFilter::binOf(100, 4095))], 63U);
  EXPECT_EQ(filter.histogram()[static_cast<std::size_t>(HistogramFilter::binOf(4000, 4095))], 1U);
}

TEST(HistogramFilter, CountingOutsideTheRoiKeepsTheFullFrameRarity) {
  Image8 im(64, 64, 10);
  for (int y = 30; y < 34; ++y)
    for (int x = 30; x < 34; ++x) im.at(x, y) = 200;
  const Roi roi{20, 20, 24, 24};
  HistogramFilter full;
  HistogramFilter local;
  HistogramFilter counted;
  for (HistogramFilter* f : {&full, &local, &counted}) f->init(100.0);
  counted.setCountOutsideRoi(true);
  ResponseImage out = responseFor(64, 64, Roi::full(64, 64));
  full.apply(im.view(), Roi::full(64, 64), out);
  out.setRoi(roi);
  local.apply(im.view(), roi, out);
  counted.apply(im.view(), roi, out);
  EXPECT_EQ(counted.histogram()[10], full.histogram()[10]);  // the sparse grid is exact on a flat background
  EXPECT_EQ(counted.responseTable()[200], full.responseTable()[200]);
  EXPECT_LT(local.responseTable()[200], full.responseTable()[200]);  // the ROI alone: the target looks common
}

TEST(WeightedSum, RejectsWeightsNotSummingToOne) {
  WeightedSum sum;
  const double bad[2] = {0.6, 0.5};
  const LoadError e = sum.setWeights(bad, 2);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("eq. 14"), std::string::npos) << e.message;
  const double good[3] = {0.2, 0.3, 0.5};
  EXPECT_TRUE(sum.setWeights(good, 3).ok);
  EXPECT_EQ(sum.weightsQ8()[0] + sum.weightsQ8()[1] + sum.weightsQ8()[2], 256);
  FarRangeParams params;
  params.edge_weight = 0.7;
  ASSERT_NE(params.crossCheck(), nullptr);
  EXPECT_NE(std::string(params.crossCheck()).find("eq. 14"), std::string::npos);
}

TEST(WeightedSum, IsEq13TruncatedSoAHalfDoesNotExceedAHalf) {
  WeightedSum sum;
  sum.init(4);
  const double lambdas[2] = {0.5, 0.5};
  ASSERT_TRUE(sum.setWeights(lambdas, 2).ok);
  ResponseImage f = responseFor(4, 1, Roi::full(4, 1));
  ResponseImage g = responseFor(4, 1, Roi::full(4, 1));
  ResponseImage s = responseFor(4, 1, Roi::full(4, 1));
  const std::uint8_t fv[4] = {255, 0, 200, 255};
  const std::uint8_t gv[4] = {0, 0, 100, 255};
  for (int x = 0; x < 4; ++x) {
    f.row(0)[x] = fv[x];
    g.row(0)[x] = gv[x];
  }
  const ResponseImage* inputs[2] = {&f, &g};
  std::uint8_t row_max = 0;
  sum.apply(inputs, s, &row_max);
  for (int x = 0; x < 4; ++x) EXPECT_EQ(s.row(0)[x], (128 * fv[x] + 128 * gv[x]) / 256);
  EXPECT_EQ(s.row(0)[0], 127);  // 0.5 * 1 + 0.5 * 0 = 0.5 is not above t_out = 0.5 (127 in 1/255)
  EXPECT_EQ(row_max, 255);
}

TEST(Roi, ClipsToTheImage) {
  const Roi r = Roi{-5, 10, 20, 100}.clipped(12, 50);
  EXPECT_EQ(r.x0, 0);
  EXPECT_EQ(r.y0, 10);
  EXPECT_EQ(r.width, 12);
  EXPECT_EQ(r.height, 40);
  EXPECT_TRUE((Roi{60, 0, 5, 5}.clipped(50, 50).empty()));
}

}  // namespace
}  // namespace visnav::far
