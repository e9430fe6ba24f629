// SilhouetteExtent (fsw/farrange/silhouette_extent.hpp): the block-mean silhouette of a dim disc seeded from
// a fragment of it, on a flat and on a sloping background, and the cases that must give none: noise alone, a
// disc the image border cuts, a disc wider than the largest window. Drawn directly, not rendered.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "drawn_image.hpp"
#include "visnav/farrange/silhouette_extent.hpp"

namespace visnav::far::silhouette_test {
namespace {

using drawn::Drawn;

/// The shared drawing with this file's noise seed.
Drawn draw(const std::function<double(double, double)>& brightness, double noise) {
  return drawn::draw(brightness, noise, 11U);
}

/// A disc of `radius` about (cx, cy), `contrast` above `background(x, y)`.
std::function<double(double, double)> disc(double cx, double cy, double radius, double contrast,
                                           const std::function<double(double, double)>& background) {
  return [=](double x, double y) {
    return background(x, y) + (std::hypot(x - cx, y - cy) <= radius ? contrast : 0.0);
  };
}

const auto kFlat = [](double, double) { return 0.15; };

/// A Gaussian glow of sigma 40 px and `peak` centred at (cx, 240) on a level of 0.1.
std::function<double(double, double)> glow(double cx, double peak) {
  return [=](double x, double y) {
    return 0.1 + peak * std::exp(-0.5 * ((x - cx) * (x - cx) + (y - 240.0) * (y - 240.0)) / (40.0 * 40.0));
  };
}

TEST(SilhouetteExtent, ADimDiscInNoiseIsMeasuredWholeFromAFragmentOfIt) {
  // Contrast 0.08 under noise 0.07: about one sigma a pixel, which no pixel-wise threshold separates; a
  // 4 x 4 block's mean has a quarter of the noise. The seed is a point 25 px off the centre, as a fix on a
  // brighter face would be.
  SilhouetteExtent s;
  s.init();
  for (const double radius : {30.0, 60.0, 100.0}) {
    const Drawn d = draw(disc(300.0, 250.0, radius, 0.08, kFlat), 0.07);
    const Vec2 fragment(300.0 + 0.4 * radius, 250.0);
    const SilhouetteMeasure m = s.measure(d.view(), fragment, 4.0 * radius, 10.0, 4, 4.0);
    ASSERT_TRUE(m.found) << radius;
    EXPECT_NEAR(m.extent_px, radius, 0.12 * radius) << radius;
    EXPECT_LT((m.centroid_px - Vec2(300.0, 250.0)).norm(), 0.1 * radius) << radius;
    EXPECT_GE(m.block_px, 4);
    // The ring's spread is the block means' noise (0.07 / block side). At 4 x 4 blocks the contrast is 4.6 of
    // it, so some of the disc's blocks fall under the 4-sigma threshold (57 % kept at radius 30): the region
    // has holes but its extent is the disc's; never more than the disc.
    EXPECT_NEAR(m.noise, 0.07 / m.block_px, 0.004) << radius;
    const double disc_blocks = kPi * radius * radius / (m.block_px * m.block_px);
    EXPECT_GT(m.blocks, 0.5 * disc_blocks) << radius;
    EXPECT_LT(m.blocks, 1.1 * disc_blocks) << radius;
  }
}

TEST(SilhouetteExtent, ABackgroundSlopingAcrossTheWindowIsFittedNotTakenForTheTarget) {
  SilhouetteExtent s;
  s.init();
  const auto slope = [](double x, double y) { return 0.05 + 0.0006 * x + 0.0003 * y; };  // 0.05 .. 0.58
  const Drawn d = draw(disc(320.0, 240.0, 40.0, -0.08, slope), 0.05);                    // darker than it
  const SilhouetteMeasure m = s.measure(d.view(), Vec2(330.0, 240.0), 160.0, 10.0, 4, 4.0);
  ASSERT_TRUE(m.found);
  EXPECT_NEAR(m.extent_px, 40.0, 5.0);
  // The same window without the fit's slope terms would call a whole side of it "departing": the control.
  const Drawn flat = draw(disc(320.0, 240.0, 40.0, -0.08, kFlat), 0.05);
  EXPECT_NEAR(s.measure(flat.view(), Vec2(330.0, 240.0), 160.0, 10.0, 4, 4.0).extent_px, m.extent_px, 4.0);
}

TEST(SilhouetteExtent, NoiseAloneAndATargetFillingTheWindowGiveNone) {
  SilhouetteExtent s;
  s.init();
  const Drawn noise = draw(kFlat, 0.1);
  EXPECT_FALSE(s.measure(noise.view(), Vec2(320.0, 240.0), 96.0, 12.0, 4, 4.0).found);
  // A target that fills the window leaves no background to fit: nothing departs from its ring.
  const Drawn wide = draw(disc(320.0, 240.0, 200.0, 0.1, kFlat), 0.05);
  EXPECT_FALSE(s.measure(wide.view(), Vec2(320.0, 240.0), 96.0, 12.0, 4, 4.0).found);
}

TEST(SilhouetteExtent, ADiscReachingTheWindowsRingIsNotMeasuredUntilTheWindowHoldsIt) {
  // What the estimator's retry relies on: a region on the ring is flagged, not measured, and a window
  // twice as large (still inside the image) measures it.
  SilhouetteExtent s;
  s.init();
  // The disc reaches 10 px past the window's centre and across its left side.
  const Drawn d = draw(disc(320.0, 240.0, 40.0, 0.1, kFlat), 0.05);
  const Vec2 centre(370.0, 240.0);
  const SilhouetteMeasure small = s.measure(d.view(), centre, 64.0, 20.0, 4, 4.0);
  EXPECT_FALSE(small.found);
  EXPECT_TRUE(small.touches_window);
  EXPECT_FALSE(small.cut_by_image) << "a larger window would hold it";
  const SilhouetteMeasure large = s.measure(d.view(), centre, 128.0, 20.0, 4, 4.0);
  ASSERT_TRUE(large.found);
  EXPECT_NEAR(large.extent_px, 40.0, 5.0);
}

TEST(SilhouetteExtent, AFaintGlowBesideABrightTargetIsNotPartOfItsSilhouette) {
  // A small bright body (radius 14 px, contrast 0.6) on the flank of a faint wide glow (sigma 40 px, peak
  // 0.1), as the campaign's blobs lie beside a far satellite (smallsat/5015). Every block of the glow's core
  // departs from the ring's plane; grown over them the region is mostly glow, and far range would read the
  // target several times too near.
  SilhouetteExtent s;
  s.init();
  const Drawn d = draw(disc(300.0, 240.0, 14.0, 0.6, glow(360.0, 0.1)), 0.04);
  const Vec2 fix(300.0, 240.0);
  const SilhouetteMeasure any = s.measure(d.view(), fix, 160.0, 14.0, 4, 4.0, 0.0);
  ASSERT_TRUE(any.found) << "the control: any departing block grows the region";
  EXPECT_GT(any.extent_px, 50.0) << "it took in the glow";
  const SilhouetteMeasure body = s.measure(d.view(), fix, 160.0, 14.0, 4, 4.0, 0.25);
  ASSERT_TRUE(body.found);
  EXPECT_NEAR(body.extent_px, 14.0, 4.0) << "blocks departing by a quarter of the body's level only";
  EXPECT_GT(body.median_level_ratio, 0.5);
}

TEST(SilhouetteExtent, ARegionMostlyFainterThanItsCoreIsNotFound) {
  // The glow above, brighter (peak 0.25) and nearer (its centre 40 px from the body's), so that its core
  // passes a quarter of the body's level and joins the region: most of the region then departs by far less
  // than the body, and it is not taken.
  SilhouetteExtent s;
  s.init();
  const Drawn d = draw(disc(300.0, 240.0, 14.0, 0.6, glow(340.0, 0.25)), 0.04);
  const SilhouetteMeasure m = s.measure(d.view(), Vec2(300.0, 240.0), 160.0, 14.0, 4, 4.0, 0.25);
  EXPECT_GT(m.extent_px, 30.0) << "the region took in the glow's core";
  EXPECT_LT(m.median_level_ratio, 0.5);
  EXPECT_FALSE(m.found);
}

TEST(SilhouetteExtent, ADiscTheImageBorderCutsIsNotMeasured) {
  SilhouetteExtent s;
  s.init();
  const Drawn d = draw(disc(20.0, 240.0, 50.0, 0.1, kFlat), 0.05);
  const SilhouetteMeasure m = s.measure(d.view(), Vec2(30.0, 240.0), 200.0, 12.0, 4, 4.0);
  EXPECT_FALSE(m.found);
  EXPECT_TRUE(m.cut_by_image);
}

TEST(SilhouetteExtent, BadInputsAndAnUninitialisedInstanceGiveNone) {
  const Drawn d = draw(disc(320.0, 240.0, 40.0, 0.1, kFlat), 0.02);
  SilhouetteExtent idle;
  EXPECT_FALSE(idle.measure(d.view(), Vec2(320.0, 240.0), 96.0, 12.0, 4, 4.0).found) << "init() not called";
  SilhouetteExtent s;
  s.init();
  EXPECT_TRUE(s.measure(d.view(), Vec2(320.0, 240.0), 96.0, 12.0, 4, 4.0).found) << "the control";
  EXPECT_FALSE(s.measure(MonoImage{}, Vec2(320.0, 240.0), 96.0, 12.0, 4, 4.0).found);
  EXPECT_FALSE(s.measure(d.view(), Vec2(NAN, 240.0), 96.0, 12.0, 4, 4.0).found);
  EXPECT_FALSE(s.measure(d.view(), Vec2(320.0, 240.0), 0.0, 12.0, 4, 4.0).found);
  EXPECT_FALSE(s.measure(d.view(), Vec2(320.0, 240.0), 96.0, 12.0, 0, 4.0).found);
  EXPECT_FALSE(s.measure(d.view(), Vec2(320.0, 240.0), 96.0, 12.0, 4, 0.0).found);
  EXPECT_FALSE(s.measure(d.view(), Vec2(320.0, 240.0), 8.0, 12.0, 4, 4.0).found) << "under 8 blocks a side";
  EXPECT_FALSE(s.measure(d.view(), Vec2(2000.0, 240.0), 96.0, 12.0, 4, 4.0).found) << "window off the image";
  EXPECT_FALSE(s.measure(d.view(), Vec2(-1e300, 1e300), 96.0, 12.0, 4, 4.0).found) << "no int overflow";
}

}  // namespace
}  // namespace visnav::far::silhouette_test
