// measureOutlineSharpness (fsw/farrange/outline_sharpness.hpp): a body's outline against a blob's ramp, at
// several sizes, both polarities, under noise and cut by the image border; drawn directly, not rendered,
// so each case is the shape its name says.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "drawn_image.hpp"
#include "visnav/farrange/outline_sharpness.hpp"

namespace visnav::far {
namespace {

using drawn::draw;
using drawn::Drawn;

/// A disc of `radius` px around (cx, cy), `inside` on `outside`, its edge blurred by a Gaussian of
/// `blur` px (the optics).
std::function<double(double, double)> disc(double cx, double cy, double radius, double inside, double outside,
                                           double blur = 1.0) {
  return [=](double x, double y) {
    const double r = std::hypot(x - cx, y - cy);
    const double w = 0.5 * std::erfc((r - radius) / (blur * std::sqrt(2.0)));
    return outside + (inside - outside) * w;
  };
}

/// A Gaussian spot of sigma `sigma` px and `peak` over `background`, as the campaign's blobs.
std::function<double(double, double)> spot(double cx, double cy, double sigma, double peak,
                                           double background) {
  return [=](double x, double y) {
    const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
    return background + peak * std::exp(-0.5 * r2 / (sigma * sigma));
  };
}

TEST(OutlineSharpness, ABodysEdgeIsSharpAndABlobsRampIsNotAtEverySize) {
  // The cluster's radius as far range would give it: the body's, or where a blob's response ends (about
  // 1.5 sigma).
  for (const double radius : {12.0, 20.0, 30.0, 50.0, 80.0, 160.0}) {
    const Drawn body = draw(disc(320.0, 240.0, radius, 0.45, 0.05), 0.03);
    const OutlineSharpness b = measureOutlineSharpness(body.view(), Vec2(320.0, 240.0), radius);
    ASSERT_TRUE(b.measured) << radius;
    EXPECT_GT(b.ratio, 0.6) << "body of radius " << radius;
    EXPECT_EQ(b.rays, OutlineSharpnessSettings::kRays) << radius;

    const double sigma = radius / 1.5;
    const Drawn blob = draw(spot(320.0, 240.0, sigma, 0.4, 0.05), 0.03);
    const OutlineSharpness s = measureOutlineSharpness(blob.view(), Vec2(320.0, 240.0), radius);
    ASSERT_TRUE(s.measured) << radius;
    EXPECT_LT(s.ratio, 0.4) << "blob of sigma " << sigma;
  }
}

TEST(OutlineSharpness, PolarityAndAWiderBlurDoNotMakeABodyARamp) {
  const Drawn dark = draw(disc(320.0, 240.0, 40.0, 0.1, 0.6), 0.03);  // a dark body on a bright limb
  const OutlineSharpness d = measureOutlineSharpness(dark.view(), Vec2(320.0, 240.0), 40.0);
  ASSERT_TRUE(d.measured);
  EXPECT_GT(d.ratio, 0.6);
  const Drawn blurred = draw(disc(320.0, 240.0, 40.0, 0.45, 0.05, 1.5), 0.03);  // the campaign's widest blur
  const OutlineSharpness b = measureOutlineSharpness(blurred.view(), Vec2(320.0, 240.0), 40.0);
  ASSERT_TRUE(b.measured);
  EXPECT_GT(b.ratio, 0.5);
}

TEST(OutlineSharpness, NoiseWithoutAStepIsNotMeasuredAsSharp) {
  // Each ray's outline is located on its largest step; on noise alone that pick would itself make a "sharp"
  // step, so rays without a step well above their noise are left out.
  const Drawn noise = draw([](double, double) { return 0.3; }, 0.1);
  const OutlineSharpness n = measureOutlineSharpness(noise.view(), Vec2(320.0, 240.0), 40.0);
  EXPECT_FALSE(n.measured);
  EXPECT_LT(n.rays, OutlineSharpnessSettings::kRays / 2);
  // A body under noise 0.1 with a contrast of 0.4 is still measured, and sharp.
  const Drawn noisy = draw(disc(320.0, 240.0, 40.0, 0.45, 0.05), 0.1);
  const OutlineSharpness b = measureOutlineSharpness(noisy.view(), Vec2(320.0, 240.0), 40.0);
  ASSERT_TRUE(b.measured);
  EXPECT_GT(b.ratio, 0.55);
  const Drawn blob = draw(spot(320.0, 240.0, 27.0, 0.8, 0.05), 0.1);
  const OutlineSharpness s = measureOutlineSharpness(blob.view(), Vec2(320.0, 240.0), 40.0);
  ASSERT_TRUE(s.measured);
  EXPECT_LT(s.ratio, 0.45);
}

TEST(OutlineSharpness, SmallClustersAndBadInputsAreNotMeasured) {
  const Drawn body = draw(disc(320.0, 240.0, 8.0, 0.8, 0.05), 0.02);
  EXPECT_FALSE(measureOutlineSharpness(body.view(), Vec2(320.0, 240.0), 8.0).measured)
      << "under kMinRadiusPx the coarse baseline spans the whole body";
  EXPECT_FALSE(measureOutlineSharpness(MonoImage{}, Vec2(320.0, 240.0), 40.0).measured);
  const Drawn big = draw(disc(320.0, 240.0, 40.0, 0.45, 0.05), 0.03);
  EXPECT_FALSE(measureOutlineSharpness(big.view(), Vec2(std::nan(""), 240.0), 40.0).measured);
  EXPECT_FALSE(measureOutlineSharpness(big.view(), Vec2(320.0, 240.0), std::nan("")).measured);
}

TEST(OutlineSharpness, ABodyCutByTheBorderIsMeasuredOnItsVisibleSide) {
  // Centre 20 px inside the left border: the rays to the left leave the image before the outline.
  const Drawn body = draw(disc(20.0, 240.0, 60.0, 0.45, 0.05), 0.03);
  const OutlineSharpness b = measureOutlineSharpness(body.view(), Vec2(20.0, 240.0), 60.0);
  ASSERT_TRUE(b.measured);
  EXPECT_LT(b.rays, OutlineSharpnessSettings::kRays);
  EXPECT_GT(b.ratio, 0.6);
  // Centre outside the image: no ray has a sample.
  EXPECT_FALSE(measureOutlineSharpness(body.view(), Vec2(-100.0, 240.0), 60.0).measured);
}

}  // namespace
}  // namespace visnav::far
