// The far-range estimator on an extended target (fsw/farrange/README.md): the outline search when eq. 12's
// rarity fails, an outline enclosing a fragment, and the distance from the extent when the radius is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "far_approach.hpp"
#include "visnav/farrange/nav_conversion.hpp"

namespace visnav::far {
namespace {

using namespace approach_support;

TEST(FarRangeEstimator, AnExtendedTargetIsTrackedByItsOutlineWhenItsGreyLevelsAreNoLongerRare) {
  // Once the plate's own grey levels fill the histogram, eq. 12 no longer calls them rare and no pixel
  // reaches t_in (below 19 m, about 140 px across).
  const FarRangeParams without = withoutOutlineSearch();
  double last_without = 0.0;
  approach(brightPlate(), without, last_without);
  EXPECT_GT(last_without, 17.0) << "eq. 13 alone loses the plate below 19 m";
  double last_with = 0.0;
  const std::vector<FarRangeResult> with = approach(brightPlate(), withOutlineSearch(), last_with);
  EXPECT_LT(last_with, 12.2) << "the outline search holds it to the end";
  int extended = 0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    if ((with[i].flags & kFlagExtended) == 0U) continue;
    ++extended;
    const double range = 200.0 * std::pow(0.97, static_cast<double>(i));
    EXPECT_NEAR(with[i].distance_m / range, 1.0, 0.25) << "frame " << i << " at " << range << " m";
  }
  EXPECT_GE(extended, 10);
}

TEST(FarRangeEstimator, AFragmentOfTheTargetGivesWayToTheOutlineEnclosingIt) {
  // In noise 0.08 on a contrast of 0.27, eq. 13 keeps only a few pixels of the dim plate below 40 m, and the
  // gate's size consistency holds on to such a fragment: the fixes stay on the target but read hundreds of
  // metres (none of the 40 frames below 40 m within 25 %). The outline search, also where it encloses the
  // fragment, gives 8 of them (16 when an outline twice the fragment's size replaced it, but then a
  // satellite's body gave way to its outline with the panels: extended_enclose_ratio is 4).
  const FarRangeParams without = withoutOutlineSearch();
  double last_without = 0.0;
  const std::vector<FarRangeResult> fragments = approach(dimPlateInNoise(), without, last_without);
  double last_with = 0.0;
  const std::vector<FarRangeResult> with = approach(dimPlateInNoise(), withOutlineSearch(), last_with);
  int good_without = 0;
  int good_with = 0;
  for (std::size_t i = 0; i < with.size(); ++i) {
    const double range = 200.0 * std::pow(0.97, static_cast<double>(i));
    if (range > 40.0) continue;
    good_without += fragments[i].valid && std::abs(fragments[i].distance_m / range - 1.0) < 0.25 ? 1 : 0;
    good_with += with[i].valid && std::abs(with[i].distance_m / range - 1.0) < 0.25 ? 1 : 0;
  }
  EXPECT_LT(good_without, 3);
  EXPECT_GE(good_with, 6);
}

TEST(FarRangeEstimator, AnExtendedTargetIsPutAtItsDistanceByItsExtentWhenItsRadiusIsKnown) {
  // The dim plate of the test above: where eq. 16 counts the response pixels of an outline that does not
  // close, far fewer than the plate's area, it reads too far (168 m at 26.8 m); the outline's extent and the
  // plate's bounding radius read 26.1 m. The nearer of the two is taken: on the fragments both read too far,
  // the extent less so.
  // The silhouette searches off (the whole frame's without a track, the hull of an outline with gaps): with
  // them, the outline stands for the filled plate and eq. 16 itself reads within 25 % on 15 of the 18 fixes
  // below 40 m (8 of 23 without), so no fix is left for the extent to rescue.
  const ApproachScene scene = dimPlateInNoise();
  FarRangeParams params = withOutlineSearch();
  params.outline_min_coverage = 2.0;
  params.untracked_outline_fill_ratio = 0.0;
  params.silhouette_min_half_px = 0.0;  // the cluster's own extent (the block-mean silhouette: below)
  double last_gamma = 0.0;
  const std::vector<FarRangeResult> gamma = approach(scene, params, last_gamma);
  double last_extent = 0.0;
  const std::vector<FarRangeResult> extent =
      approach(scene, params, last_extent, scene.model.boundingRadius());
  int good_gamma = 0;
  int good_extent = 0;
  int rescued = 0;
  int fixes = 0;
  for (std::size_t i = 0; i < extent.size(); ++i) {
    const double range = 200.0 * std::pow(0.97, static_cast<double>(i));
    const FarRangeResult& r = extent[i];
    if (range > 40.0 || !r.valid) continue;
    ++fixes;
    // The same cluster either way: only the distance differs.
    EXPECT_EQ(r.centroid_px, gamma[i].centroid_px) << "frame " << i;
    EXPECT_NEAR(r.extent_distance_m,
                scene.camera.intrinsics().fx_px * scene.model.boundingRadius() / r.extent_px, 1e-9);
    // The nearer of eq. 16 and the extent (a tiny cluster: eq. 16).
    const double eq16_m = gamma[i].distance_m;
    const bool by_extent =
        r.extent_px >= FarRangeParams{}.extent_distance_min_px && r.extent_distance_m < eq16_m;
    EXPECT_EQ((r.flags & kFlagExtentDistance) != 0U, by_extent) << "frame " << i;
    EXPECT_EQ(r.distance_m, by_extent ? r.extent_distance_m : eq16_m) << "frame " << i;
    const bool good = std::abs(r.distance_m / range - 1.0) < 0.25;
    good_gamma += std::abs(eq16_m / range - 1.0) < 0.25 ? 1 : 0;
    good_extent += good ? 1 : 0;
    rescued += good && eq16_m > 2.0 * range ? 1 : 0;
  }
  EXPECT_GE(fixes, 15);
  EXPECT_GE(good_extent, good_gamma) << "of " << fixes << " fixes below 40 m";
  EXPECT_GE(rescued, 1) << "eq. 16 read more than twice the range where the extent read it within 25 %";
  EXPECT_LE(last_extent, last_gamma);
}

// box/13 in kind: a plate whose grey level (0.6) lies inside a gradient that rises from about 0.15 to 0.7
// across the image (a very soft limb's edge), so eq. 12 never calls it rare; noise as given, 1024 x 768, f
// 900 px; and a small glint (sigma 1.5 px) far from it, whose bright pixels are rare and sharp. Each frame is
// searched without a track.
struct PlateOnGradientWithGlint {
  ApproachScene a;
  explicit PlateOnGradientWithGlint(double noise)
      : a(plateScene(2.0, 2.2, 0.6, 0.1, noise, 0.6, 1024, 768, 900.0)) {
    a.render.limb.enabled = true;
    a.render.limb.center_x_px = 512.0 - 6000.0;  // the limb's edge runs vertically through the image centre
    a.render.limb.center_y_px = 384.0;
    a.render.limb.radius_px = 6000.0;
    a.render.limb.brightness_limb = 0.75;
    a.render.limb.brightness_centre = 0.75;
    a.render.limb.softness_px = 250.0;
    synthetic::Glint g = test::glowAt(Vec2(850.0, 150.0));
    g.sigma_px = 1.5;
    a.render.glints.push_back(g);
  }
  // Fixes on the plate (direction inside its bounding sphere, distance within 25 %) of 12 frames at 24-35 m;
  // `extended`: of them, found by an outline.
  int onTarget(const FarRangeParams& p, int& extended) const {
    Scene s(a.render, a.camera, a.model);
    int good = 0;
    extended = 0;
    for (int i = 0; i < 12; ++i) {
      const double range = 35.0 - i;
      const test::FarFrame f = s.frame(test::satAt(range, 0.3 * (i % 4), 0.2 * (i % 3), 5.0 * i), 300 + i, i);
      FarRangeEstimator e;  // no track: every frame is the untracked search
      EXPECT_TRUE(e.init(s.camera, p).ok);
      e.setTargetRadius(s.model.boundingRadius());
      FarRangeResult r;
      EXPECT_EQ(e.estimate(f.image(), r), Status::kOk);
      const double radius_deg = std::atan(s.model.boundingRadius() / range) * kDegPerRad;
      const bool good_fix = r.valid && angleDeg(r.direction_c, f.truth.t_c_m.normalized()) < radius_deg &&
                            std::abs(r.distance_m / range - 1.0) < 0.25;
      good += good_fix ? 1 : 0;
      extended += good_fix && (r.flags & kFlagExtended) != 0U ? 1 : 0;
    }
    return good;
  }
};

TEST(FarRangeEstimator, ADimTargetsFragmentIsPutAtTheDistanceOfItsBlockMeanSilhouette) {
  // The dim plate of the test above with the same searches: the fixes below 40 m are fragments of the
  // plate's outline whose extent reads up to 4x too far. Its silhouette of 4 x 4 block means holds the
  // whole plate; where it reaches farther than the fragment, its extent's distance is delivered when
  // nearer (flag silhouette_extent). The same clusters are selected: only the distance differs.
  const ApproachScene scene = dimPlateInNoise();
  FarRangeParams params = withOutlineSearch();
  params.outline_min_coverage = 2.0;
  params.untracked_outline_fill_ratio = 0.0;
  params.silhouette_min_half_px = 48.0;  // experimental, off by default
  FarRangeParams off = params;
  off.silhouette_min_half_px = 0.0;
  const double radius_m = scene.model.boundingRadius();
  double last_off = 0.0;
  const std::vector<FarRangeResult> fragments = approach(scene, off, last_off, radius_m);
  double last_on = 0.0;
  const std::vector<FarRangeResult> silhouettes = approach(scene, params, last_on, radius_m);
  int fixes = 0;
  int good_off = 0;
  int good_on = 0;
  int measured = 0;
  double worst_short = 1.0;  // the smallest delivered / true range of a silhouette's distance
  for (std::size_t i = 0; i < silhouettes.size(); ++i) {
    const double range = 200.0 * std::pow(0.97, static_cast<double>(i));
    const FarRangeResult& r = silhouettes[i];
    ASSERT_EQ(r.valid, fragments[i].valid) << "frame " << i;
    if (!r.valid) continue;
    EXPECT_EQ(r.centroid_px, fragments[i].centroid_px) << "frame " << i;
    EXPECT_EQ(r.extent_px, fragments[i].extent_px) << "frame " << i;
    if ((r.flags & kFlagSilhouetteExtent) != 0U) {
      ++measured;
      EXPECT_GT(r.silhouette_extent_px, r.extent_px) << "frame " << i;
      EXPECT_NEAR(r.distance_m, scene.camera.intrinsics().fx_px * radius_m / r.silhouette_extent_px, 1e-9);
      EXPECT_LT(r.distance_m, fragments[i].distance_m) << "frame " << i;
      EXPECT_NE(r.flags & kFlagExtentDistance, 0U);
      worst_short = std::min(worst_short, r.distance_m / range);
    } else {
      EXPECT_EQ(r.distance_m, fragments[i].distance_m) << "frame " << i;
    }
    if (range > 40.0) continue;
    ++fixes;
    good_off += std::abs(fragments[i].distance_m / range - 1.0) < 0.25 ? 1 : 0;
    good_on += std::abs(r.distance_m / range - 1.0) < 0.25 ? 1 : 0;
  }
  std::printf("fixes below 40 m %d, within 25 %%: fragment %d, silhouette %d; silhouettes %d, worst %.3f\n",
              fixes, good_off, good_on, measured, worst_short);
  EXPECT_GE(fixes, 15);
  EXPECT_GE(measured, 5);
  EXPECT_GE(good_on, good_off + 5) << "of " << fixes << " fixes below 40 m";
  // The silhouette is never larger than the plate: its distance is never short by more than the blocks'
  // quantisation and the blur.
  EXPECT_GT(worst_short, 0.8);
}

TEST(FarRangeEstimator, WithoutATrackAnExtendedTargetOverItsOwnGreyLevelsIsFoundByItsSilhouette) {
  // eq. 13 takes the glint (the plate's grey levels are the gradient's, not rare); the plate's closed
  // outline is extended_enclose_ratio times larger and wins. Measured when added: 0, then 12 of 12.
  const PlateOnGradientWithGlint frames(0.05);
  FarRangeParams off;
  off.untracked_outline_fill_ratio = 0.0;
  int extended_off = 0;
  const int good_off = frames.onTarget(off, extended_off);
  int extended_on = 0;
  const int good_on = frames.onTarget(FarRangeParams{}, extended_on);
  EXPECT_LE(good_off, 2) << "of 12 frames";
  EXPECT_EQ(extended_off, 0);
  EXPECT_GE(good_on, 10) << "of 12 frames";
  EXPECT_GE(extended_on, good_on - good_off);
}

TEST(FarRangeEstimator, AnOutlineWithGapsStandsForItsHullWhenItRunsAlongMostOfIt) {
  // The same in noise 0.07: the outline breaks and seldom closes; its hull, covered along
  // outline_min_coverage of its boundary, is the plate. Measured when added: 0 without the silhouette
  // search, 3 of 12 with closed outlines alone, 7 with the hull (6 with outline_min_concentration 0.4, 4 at
  // 0.6: the noise the outline gathers lies inside its hull).
  const PlateOnGradientWithGlint frames(0.07);
  FarRangeParams closed_only;
  closed_only.outline_min_coverage = 2.0;
  int extended_closed = 0;
  const int good_closed = frames.onTarget(closed_only, extended_closed);
  int extended_on = 0;
  const int good_on = frames.onTarget(FarRangeParams{}, extended_on);
  EXPECT_LE(good_closed, 4) << "of 12 frames";
  EXPECT_GE(good_on, good_closed + 3) << "of 12 frames";
}

TEST(FarRangeEstimator, AFixFoundByItsOutlineIsEdgeStructureAndNotRefuted) {
  // Acquisition refutes a cue whose window's edge SNR is low (no_target); an outline is edge structure, and
  // a dim target far off has a low window SNR too. Unless outline_fix_refutable, refuteLastFix() leaves such
  // a fix alone and the next frame finds the same plate; with it, the plate is passed over.
  const PlateOnGradientWithGlint frames(0.05);
  Scene s(frames.a.render, frames.a.camera, frames.a.model);
  const test::FarFrame f = s.frame(test::satAt(30.0, 0.3, 0.2, 5.0), 300, 0);
  for (const bool refutable : {false, true}) {
    FarRangeParams p;
    p.outline_fix_refutable = refutable;
    FarRangeEstimator e;
    ASSERT_TRUE(e.init(s.camera, p).ok);
    FarRangeResult first;
    ASSERT_EQ(e.estimate(f.image(), first), Status::kOk);
    ASSERT_TRUE(first.valid);
    ASSERT_NE(first.flags & kFlagExtended, 0U);
    EXPECT_TRUE(toFarRangeSolution(first).outline) << "acquisition's outline-cue threshold applies";
    EXPECT_EQ(e.refuteLastFix(), refutable);
    e.reset();
    FarRangeResult again;
    ASSERT_EQ(e.estimate(f.image(), again), Status::kOk);
    const bool same = again.valid && (again.centroid_px - first.centroid_px).norm() < 1.0;
    EXPECT_EQ(same, !refutable) << "outline_fix_refutable " << refutable;
    EXPECT_EQ((again.flags & kFlagRefutedSkipped) != 0U, refutable);
  }
}

TEST(FarRangeEstimator, ATinyClusterKeepsEq16) {
  // Below extent_distance_min_px the cluster is a few pixels of blur: its extent says little, eq. 16 holds.
  Scene s;
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(s.camera, FarRangeParams{}).ok);
  e.setTargetRadius(s.model.boundingRadius());
  FarRangeResult r;
  ASSERT_EQ(e.estimate(s.frame(test::satAt(2500.0, 1.0, 1.0, 15.0), 3).image(), r), Status::kOk);
  ASSERT_TRUE(r.valid);
  EXPECT_LT(r.extent_px, FarRangeParams{}.extent_distance_min_px);
  EXPECT_EQ(r.flags & kFlagExtentDistance, 0U);
  EXPECT_NEAR(r.distance_m, FarRangeParams{}.gamma / std::sqrt(static_cast<double>(r.cluster_pixels)), 1e-9);
  EXPECT_GT(r.extent_distance_m, 0.0);
}

}  // namespace
}  // namespace visnav::far
