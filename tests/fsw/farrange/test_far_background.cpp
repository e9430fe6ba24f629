// The histogram filter over the deviation from the smooth background ([farrange] background_block_px): a
// target whose grey level lies inside a bright gradient's spread is rare against the flattened frame and
// common against the frame itself (fsw/farrange/README.md, "Background").
#include <gtest/gtest.h>

#include "far_fixture.hpp"
#include "visnav/farrange/histogram_filter.hpp"

namespace visnav::far {
namespace {

/// The satellite (grey 0.35, no shading) in the centre of a 640x480 frame, in front of a soft ramp (a
/// planet's limb far out of focus) from 0.03 at the top to 0.42 at the bottom, 0.16 behind the target; noise
/// 0.015. The target stands out from the ramp behind it by 0.19 (12 sigma), but its grey level is one the
/// ramp has lower down.
test::FarFrame rampFrame(double range_m) {
  const PinholeCamera camera = test::farCamera(640, 480, false);
  synthetic::RenderOptions o = test::farRender();
  o.shading.enabled = false;
  o.target_brightness = 0.35;
  o.limb.enabled = true;
  o.limb.radius_px = 4000.0;
  o.limb.center_x_px = 320.0;
  o.limb.center_y_px = 240.0 + 4150.0;  // the boundary runs horizontally 150 px below the centre row
  o.limb.softness_px = 120.0;
  o.limb.brightness_limb = 0.6;
  o.limb.brightness_centre = 0.6;
  synthetic::Renderer renderer;
  EXPECT_TRUE(renderer.init(camera, test::smallsat(), o).ok);
  return test::renderFar(renderer, test::satAt(range_m, 0.0, 0.0), 7U);
}

/// The block size measured on the campaign (fsw/farrange/README.md), the parameter's default.
constexpr int kBlockPx = 128;

FarRangeParams backgroundParams(int block_px, bool fallback_only) {
  FarRangeParams p;
  p.background_block_px = block_px;
  p.background_fallback_only = fallback_only;
  return p;
}

FarRangeResult estimate(const test::FarFrame& frame, int block_px, bool fallback_only = false,
                        bool silhouette = true) {
  FarRangeEstimator far;
  FarRangeParams p = backgroundParams(block_px, fallback_only);
  if (!silhouette) p.untracked_outline_fill_ratio = 0.0;
  EXPECT_TRUE(far.init(test::farCamera(640, 480, false), p).ok);
  FarRangeResult out;
  EXPECT_EQ(far.estimate(frame.image(), out), Status::kOk);
  return out;
}

TEST(FarRangeBackground, ATargetInsideABrightRampsSpreadIsFoundOnceTheRampIsTakenOut) {
  const test::FarFrame frame = rampFrame(60.0);
  const Vec3 truth = frame.truth.t_c_m.normalized();
  const FarRangeResult flat = estimate(frame, kBlockPx);
  ASSERT_TRUE(flat.valid);
  EXPECT_LT(test::angleDeg(flat.direction_c, truth), 0.2) << "the fix is on the target";
  // Its n is most of the target's area (5 468 px covered more than half) and no more: no halo from the
  // background estimate (a block mean ringed the target with one; the median does not). 0.92 of it here:
  // a body this size fills its own bins, eq. 12 calls them less rare, and some interior pixels of the
  // combined response stay below t_out (eq. 16 then reads 4 % far).
  EXPECT_LE(flat.cluster_pixels / 5468.0, 1.0);
  EXPECT_GE(flat.cluster_pixels / 5468.0, 0.85);
  const FarRangeResult raw = estimate(frame, 0, false, false);
  EXPECT_FALSE(raw.valid && test::angleDeg(raw.direction_c, truth) < 0.2)
      << "against the frame's own histogram the body's grey level is common: no fix on it";
  // Without a track, the whole frame's outline search finds it by its silhouette instead.
  const FarRangeResult outline = estimate(frame, 0);
  ASSERT_TRUE(outline.valid);
  EXPECT_NE(outline.flags & kFlagExtended, 0U);
  EXPECT_LT(test::angleDeg(outline.direction_c, truth), 0.2);
}

TEST(FarRangeBackground, AsAFallbackTheFlattenedSearchRunsOnlyWhereThePrintedOneFindsNothing) {
  // background_fallback_only: on the ramp the printed eq. 11 finds nothing in the whole frame, so the
  // flattened search runs and finds the target (flag flattened); on a dark sky the printed one finds the
  // target itself and its answer stands, exactly as without the fallback.
  const test::FarFrame ramp = rampFrame(60.0);
  const FarRangeResult on_ramp = estimate(ramp, kBlockPx, true);
  ASSERT_TRUE(on_ramp.valid);
  EXPECT_NE(on_ramp.flags & kFlagFlattened, 0U);
  EXPECT_LT(test::angleDeg(on_ramp.direction_c, ramp.truth.t_c_m.normalized()), 0.2);
  EXPECT_EQ(on_ramp.cluster_pixels, estimate(ramp, kBlockPx).cluster_pixels)
      << "the same search as always on";

  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::farCamera(640, 480, false), test::smallsat(), test::farRender()).ok);
  const test::FarFrame sky = test::renderFar(renderer, test::satAt(200.0, 1.0, -0.5), 7U);
  const FarRangeResult fallback = estimate(sky, kBlockPx, true);
  const FarRangeResult printed = estimate(sky, 0);
  ASSERT_TRUE(fallback.valid && printed.valid);
  EXPECT_EQ(fallback.flags & kFlagFlattened, 0U);
  EXPECT_EQ(fallback.cluster_pixels, printed.cluster_pixels);
  EXPECT_EQ(fallback.centroid_px, printed.centroid_px);
}

TEST(FarRangeBackground, ATrackFoundOverTheFlattenedBackgroundGivesWayToWhatThePrintedSearchFinds) {
  // Frame 1, the ramp: only the flattened search finds the target, and a track starts on that fix. Frame 2,
  // a dark sky with the satellite 10 deg away: eq. 11 as printed finds it. With printed_search_wins its fix
  // ends the flattened track; without (the default), the track's region is searched flattened, the target
  // outside the gate is refused and far range coasts (campaign plate/114: a drifting blob held for 140
  // frames so).
  const test::FarFrame ramp = rampFrame(60.0);
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::farCamera(640, 480, false), test::smallsat(), test::farRender()).ok);
  const test::FarFrame sky = test::renderFar(renderer, test::satAt(100.0, 8.0, 6.0), 7U);
  for (const bool wins : {true, false}) {
    FarRangeParams p = backgroundParams(kBlockPx, true);
    p.printed_search_wins = wins;
    FarRangeEstimator far;
    ASSERT_TRUE(far.init(test::farCamera(640, 480, false), p).ok);
    FarRangeResult first;
    ASSERT_EQ(far.estimate(ramp.image(), first), Status::kOk);
    ASSERT_TRUE(first.valid);
    ASSERT_NE(first.flags & kFlagFlattened, 0U);
    FarRangeResult second;
    ASSERT_EQ(far.estimate(sky.image(), second), Status::kOk);
    const bool on_target =
        second.valid && test::angleDeg(second.direction_c, sky.truth.t_c_m.normalized()) < 0.2;
    if (wins) {
      EXPECT_TRUE(on_target);
      EXPECT_NE(second.flags & kFlagPrintedWins, 0U);
      EXPECT_EQ(second.flags & kFlagFlattened, 0U);
    } else {
      EXPECT_FALSE(on_target)
          << "the flattened track let the target outside its gate in: the test tests nothing";
      EXPECT_EQ(second.flags & kFlagPrintedWins, 0U);
    }
  }
}

TEST(FarRangeBackground, OnAFlatBackgroundTheFlattenedHistogramIsTheSameHistogramShifted) {
  // A uniform frame of grey 40 with one 3x3 patch of 200 off the sampling grid (the background is taken
  // from every 4th row and column): the background is 40 everywhere, so the flattened bins are 128 and
  // 128 + 160 -> 255, with the counts of the raw bins 40 and 200 (the patch's response exp(-9 / 4087 x 100)
  // = 0.80, the background's 0).
  std::vector<std::uint8_t> pixels(64U * 64U, 40U);
  for (int y = 29; y < 32; ++y)
    for (int x = 29; x < 32; ++x) pixels[static_cast<std::size_t>(y * 64 + x)] = 200U;
  const MonoImage image = MonoImage::from8(ImageView8(pixels.data(), 64, 64));
  HistogramFilter filter;
  filter.init(100.0);
  filter.setBackgroundBlock(32, 64, 64);
  ResponseImage out;
  out.init(64, 64);
  out.setRoi(Roi::full(64, 64));
  filter.apply(image, Roi::full(64, 64), out);
  EXPECT_EQ(filter.histogram()[128], 64U * 64U - 9U);
  EXPECT_EQ(filter.histogram()[255], 9U);
  EXPECT_EQ(out.row(30)[30], 205) << "the patch is rare";
  EXPECT_EQ(out.row(0)[0], 0) << "the background is not";
}

}  // namespace
}  // namespace visnav::far
