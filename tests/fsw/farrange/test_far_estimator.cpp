// The far-range estimator on rendered frames of the far_range satellite: direction through the distorted
// camera, distance (eq. 16), the published method's weak spots against the robust method, gating, region
// of interest, coasting, the filter prediction and the NavSolution conversion.
#include <gtest/gtest.h>

#include "far_approach.hpp"
#include "visnav/farrange/nav_conversion.hpp"

namespace visnav::far {
namespace {

using namespace approach_support;

TEST(FarRangeEstimator, DirectionGoesThroughTheDistortedCameraModel) {
  Scene s;
  const test::FarFrame f = s.frame(test::satAt(400.0, 16.0, 11.5, 10.0));  // near the image corner
  const FarRangeResult r = estimateOnce(s.camera, FarRangeParams{}, f);
  ASSERT_TRUE(r.valid);
  const Vec3 truth = f.truth.t_c_m.normalized();
  EXPECT_LT(angleDeg(r.direction_c, truth), 0.03);
  EXPECT_NEAR(r.azimuth_rad, std::atan2(truth.x(), truth.z()), 1e-3);
  EXPECT_NEAR(r.elevation_rad, std::atan2(-truth.y(), std::hypot(truth.x(), truth.z())), 1e-3);
  EXPECT_NEAR(r.direction_c.norm(), 1.0, 1e-12);
  // Back-projecting the same centroid without removing the distortion is off by more than the target.
  const PinholeCamera ideal = test::farCamera(640, 480, false);
  EXPECT_GT(angleDeg(ideal.bearing(r.centroid_px), truth), 0.08);
}

TEST(FarRangeEstimator, DistanceIsEq16AndTheRobustSizeFollowsInverseSquareDistance) {
  Scene s;
  // One calibration frame at 700 m, then the whole range with that gamma. The robust method also over the
  // flattened background on every frame (background_block_px 128, not only as the fallback): the blocks'
  // median adds no halo to n.
  struct Case {
    FarRangeMethod method;
    int block_px;
  };
  for (const Case c : {Case{FarRangeMethod::kRobust, 0}, Case{FarRangeMethod::kRobust, 128},
                       Case{FarRangeMethod::kPaper, 0}}) {
    SCOPED_TRACE(c.block_px);
    const FarRangeMethod m = c.method;
    FarRangeParams p = method(m);
    p.background_block_px = c.block_px;
    p.background_fallback_only = false;
    const FarRangeResult cal = estimateOnce(s.camera, p, s.frame(test::satAt(700.0, 1.0, 1.0, 15.0), 3));
    ASSERT_TRUE(cal.valid);
    p.gamma = 700.0 * std::sqrt(static_cast<double>(cal.cluster_pixels));
    const FarRangeResult near = estimateOnce(s.camera, p, s.frame(test::satAt(60.0, 1.0, 1.0, 15.0), 4));
    ASSERT_TRUE(near.valid);
    EXPECT_NEAR(near.distance_m, p.gamma / std::sqrt(static_cast<double>(near.cluster_pixels)), 1e-9);
    const double error = std::abs(near.distance_m - 60.0) / 60.0;
    if (m == FarRangeMethod::kRobust) {
      EXPECT_LT(error, 0.10) << "filled cluster minus its outline follows 1/d^2";
    } else {
      // Weak spot: close in, the histogram filter drops the interior (its grey levels are no longer rare),
      // so n grows like 1/d instead of 1/d^2 and a far calibration overestimates the distance.
      EXPECT_GT(error, 0.5) << "paper n " << near.cluster_pixels;
    }
  }
}

TEST(FarRangeEstimator, ATinyGlintBeatsTheSatelliteOnCircularityOnlyInThePaperMethod) {
  synthetic::RenderOptions o = test::farRender();
  synthetic::Glint glint;
  glint.first_frame = 0;
  glint.last_frame = 10;
  glint.start_px = glint.end_px = Vec2(150.5, 380.5);
  glint.sigma_px = 0.6;
  glint.peak = 2.0;
  o.glints.push_back(glint);
  Scene s(o);
  const test::FarFrame f = s.frame(test::satAt(400.0, 3.0, 2.0, 20.0));
  const Vec3 truth = f.truth.t_c_m.normalized();
  const FarRangeResult paper = estimateOnce(s.camera, method(FarRangeMethod::kPaper), f);
  const FarRangeResult robust = estimateOnce(s.camera, method(FarRangeMethod::kRobust), f);
  ASSERT_TRUE(paper.valid);
  ASSERT_TRUE(robust.valid);
  EXPECT_GT(angleDeg(paper.direction_c, truth), 5.0) << "the paper method follows the glint";
  EXPECT_GT(paper.circularity, 0.3);
  EXPECT_LT(angleDeg(robust.direction_c, truth), 0.05);
}

TEST(FarRangeEstimator, OneBrightEdgeHidesTheTargetUnderMaxNormalisation) {
  synthetic::RenderOptions o = test::farRender();
  synthetic::MovingBar bar;
  bar.first_frame = 0;
  bar.last_frame = 10;
  bar.start_px = bar.end_px = Vec2(320.0, 100.0);
  bar.length_px = 160.0;
  bar.width_px = 14.0;
  bar.angle_deg = 10.0;
  bar.brightness_start = bar.brightness_end = 1.0;
  o.bars.push_back(bar);
  Scene s(o);
  const test::FarFrame f = s.frame(test::satAt(400.0, -2.0, -3.0, 20.0));
  const Vec3 truth = f.truth.t_c_m.normalized();
  FarRangeEstimator paper;
  ASSERT_TRUE(paper.init(s.camera, method(FarRangeMethod::kPaper)).ok);
  FarRangeResult r;
  paper.estimate(f.image(), r);
  Vec2 target_px;
  ASSERT_TRUE(s.camera.project(f.truth.t_c_m, target_px));
  for (const Cluster& c : paper.clusters()) {
    EXPECT_GT((c.com_px - target_px).norm(), 20.0) << "no cluster spawned on the satellite";
  }
  // Always over the flattened background too: no halo grows the bar round.
  for (const int block_px : {0, 128}) {
    FarRangeParams robust_params = method(FarRangeMethod::kRobust);
    robust_params.background_block_px = block_px;
    robust_params.background_fallback_only = false;
    const FarRangeResult robust = estimateOnce(s.camera, robust_params, f);
    ASSERT_TRUE(robust.valid) << block_px;
    EXPECT_LT(angleDeg(robust.direction_c, truth), 0.05) << block_px;
  }
}

TEST(FarRangeEstimator, RegionOfInterestGivesTheFullFrameAnswerAndGatesTheTrack) {
  Scene s;
  for (const int block_px : {0, 128}) {  // always over the flattened background too
    SCOPED_TRACE(block_px);
    FarRangeParams with_roi;
    with_roi.background_block_px = block_px;
    with_roi.background_fallback_only = false;
    FarRangeParams without_roi = with_roi;
    without_roi.use_roi = false;
    FarRangeEstimator a;
    FarRangeEstimator b;
    ASSERT_TRUE(a.init(s.camera, with_roi).ok);
    ASSERT_TRUE(b.init(s.camera, without_roi).ok);
    for (int i = 0; i < 6; ++i) {
      const test::FarFrame f = s.frame(test::satAt(300.0 - 5.0 * i, 2.0 + 0.3 * i, 1.0, 20.0 + i), 10 + i);
      FarRangeResult ra;
      FarRangeResult rb;
      a.estimate(f.image(), ra);
      b.estimate(f.image(), rb);
      ASSERT_TRUE(ra.valid && rb.valid);
      EXPECT_EQ(ra.cluster_pixels, rb.cluster_pixels) << "frame " << i;
      EXPECT_LT((ra.centroid_px - rb.centroid_px).norm(), 1e-9);
      if (i > 0) {
        EXPECT_NE(ra.flags & kFlagRoi, 0U);
        EXPECT_EQ(ra.flags & kFlagRoiFallback, 0U);
        EXPECT_NE(ra.flags & kFlagGated, 0U);
        EXPECT_LT(ra.roi.area(), 640 * 480 / 4);
      } else {
        EXPECT_NE(ra.flags & kFlagUnconfirmed, 0U);
      }
    }
  }
}

TEST(FarRangeEstimator, CoastsWithoutATargetThenDropsTheTrack) {
  Scene s;
  FarRangeParams p;
  p.max_coast_frames = 2;
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(s.camera, p).ok);
  FarRangeResult r;
  e.estimate(s.frame(test::satAt(300.0)).image(), r);
  ASSERT_TRUE(r.valid);
  const test::FarFrame empty = s.frame(test::satAt(300.0, 80.0));  // far outside the field of view
  for (int i = 0; i < 4; ++i) {
    e.estimate(empty.image(), r);
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.quality, 0.0);
    EXPECT_EQ((r.flags & kFlagCoasting) != 0U, i < 2) << "frame " << i;
  }
}

TEST(FarRangeEstimator, FilterPredictionGatesTheFirstFrame) {
  Scene s;
  const test::FarFrame f = s.frame(test::satAt(350.0, -4.0, 2.0));
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(s.camera, FarRangeParams{}).ok);
  e.setPrediction(f.truth.t_c_m.normalized(), 2.0 * e.params().gamma / 30.0);  // a plausible size
  FarRangeResult r;
  e.estimate(f.image(), r);
  ASSERT_TRUE(r.valid);
  EXPECT_NE(r.flags & kFlagGated, 0U);
  EXPECT_NE(r.flags & kFlagRoi, 0U);
  e.reset();
  e.setPrediction(Vec3(0.3, 0.2, 1.0).normalized(), 350.0);  // wrong place: gated out, full frame, no track
  e.estimate(f.image(), r);
  EXPECT_FALSE(r.valid);
  EXPECT_NE(r.flags & kFlagRoiFallback, 0U);
}

TEST(FarRangeEstimator, RejectsABadConfigAndABadImage) {
  FarRangeParams p;
  p.edge_weight = 0.6;
  FarRangeEstimator e;
  const LoadError error = e.init(test::farCamera(), p);
  EXPECT_FALSE(error.ok);
  EXPECT_NE(error.message.find("eq. 14"), std::string::npos);
  FarRangeParams window;
  window.silhouette_min_half_px = 96.0;
  window.silhouette_max_half_px = 64.0;
  const LoadError shrinking = e.init(test::farCamera(), window);
  EXPECT_FALSE(shrinking.ok);
  EXPECT_NE(shrinking.message.find("silhouette_max_half_px"), std::string::npos) << shrinking.message;
  ASSERT_TRUE(e.init(test::farCamera(), FarRangeParams{}).ok);
  std::vector<std::uint8_t> small(100U * 100U, 0);
  FarRangeResult r;
  EXPECT_EQ(e.estimate(MonoImage::from8(ImageView8(small.data(), 100, 100)), r), Status::kInvalidArgument);
  EXPECT_FALSE(r.valid);
}

TEST(FarRangeEstimator, FillsTheNavigationSolution) {
  Scene s;
  const FarRangeResult r = estimateOnce(s.camera, FarRangeParams{}, s.frame(test::satAt(500.0, 2.0)));
  const FarRangeSolution sol = toFarRangeSolution(r);
  EXPECT_EQ(sol.valid, r.valid);
  EXPECT_EQ(sol.direction_c, r.direction_c);
  EXPECT_EQ(sol.distance_m, r.distance_m);
  EXPECT_EQ(sol.cluster_pixels, r.cluster_pixels);
  EXPECT_EQ(sol.cluster_count, r.cluster_count);
  EXPECT_EQ(sol.circularity, r.circularity);
  EXPECT_EQ(sol.azimuth_rad, r.azimuth_rad);
  EXPECT_GT(sol.quality, 0.0);
  EXPECT_EQ(r.flags & kFlagExtended, 0U);
  EXPECT_FALSE(sol.outline) << "a point-like fix by eq. 13, not an outline";
}

}  // namespace
}  // namespace visnav::far

namespace visnav::far {
namespace {

using namespace approach_support;

// A third filter (sec. III-B: "it is always possible to add or modify the filters"): brightness itself.
class BrightnessFilter final : public ResponseFilter {
 public:
  const char* name() const override { return "brightness"; }
  void apply(const MonoImage& image, const Roi& roi, ResponseImage& out) override {
    for (int y = 0; y < roi.height; ++y)
      for (int x = 0; x < roi.width; ++x) out.row(y)[x] = image.u8.at(roi.x0 + x, roi.y0 + y);
  }
};

TEST(FarRangeEstimator, TheFilterSetIsOpen) {
  Scene s;
  const test::FarFrame f = s.frame(test::satAt(300.0, 1.0, 1.0));
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(s.camera, FarRangeParams{}).ok);
  BrightnessFilter brightness;
  ResponseFilter* extra[1] = {&brightness};
  const double bad[3] = {0.5, 0.5, 0.2};
  EXPECT_FALSE(e.setExtraFilters(extra, 1, bad).ok);  // eq. 14
  const double weights[3] = {0.4, 0.4, 0.2};
  ASSERT_TRUE(e.setExtraFilters(extra, 1, weights).ok);
  FarRangeResult r;
  e.estimate(f.image(), r);
  ASSERT_TRUE(r.valid);
  EXPECT_LT(angleDeg(r.direction_c, f.truth.t_c_m.normalized()), 0.05);
  // S is eq. 13 over the three responses, weights in 1/256: 0.4 -> 102.4 -> 102, 0.2 -> 51.2 -> 51; the sum
  // 255 is made 256 by the largest (the first) weight: 103, 102, 51. Checked over a window on the target.
  int checked = 0;
  for (int y = static_cast<int>(r.centroid_px.y()) - 5; y <= static_cast<int>(r.centroid_px.y()) + 5; ++y) {
    for (int x = static_cast<int>(r.centroid_px.x()) - 20; x <= static_cast<int>(r.centroid_px.x()) + 20;
         ++x) {
      const int edge = e.edgeResponse().atImage(x, y);
      const int rarity = e.histogramResponse().atImage(x, y);
      const int bright = f.pixels[static_cast<std::size_t>(y * 640 + x)];
      EXPECT_EQ(e.combinedResponse().atImage(x, y), (103 * edge + 102 * rarity + 51 * bright) / 256);
      checked += edge > 0 && edge < 255 && rarity > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 10);  // the window holds non-trivial responses
}

}  // namespace
}  // namespace visnav::far
