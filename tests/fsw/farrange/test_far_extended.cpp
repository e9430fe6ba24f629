// The far-range estimator on an extended target (fsw/farrange/README.md): the outline search when eq. 12's
// rarity fails, an outline enclosing a fragment, and the distance from the extent when the radius is known.
#include <gtest/gtest.h>

#include "far_approach.hpp"

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
  const ApproachScene scene = dimPlateInNoise();
  double last_gamma = 0.0;
  const std::vector<FarRangeResult> gamma = approach(scene, withOutlineSearch(), last_gamma);
  double last_extent = 0.0;
  const std::vector<FarRangeResult> extent =
      approach(scene, withOutlineSearch(), last_extent, scene.model.boundingRadius());
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
