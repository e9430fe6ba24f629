// The systematic line-end terms of interior edges and of a narrow face's strip (fsw/nearrange/README.md, "A
// line end's systematic error"), and edges hidden behind another part ("Occluded scanlines").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "tracker_fixture.hpp"

namespace visnav {
namespace {

using test::plateAt;
using test::renderFrame;
using test::vgaCamera;

// The box of ConfusableEdges (campaign box/17's size) nearly face-on: its side faces are strips of a few
// pixels.
const Pose kStripsTruth = plateAt(14.5, 0.2, 25.0, 7.0);

PolygonModel stripsBox() { return makeBox(0.726, 0.555, 0.48); }

// One track() from `predicted` by a fresh tracker with `params`.
NearRangeResult trackOnce(const PolygonModel& model, const NearRangeParams& params, const MonoImage& image,
                          const Pose& predicted) {
  NearRangeTracker tracker;
  EXPECT_TRUE(tracker.init(vgaCamera(), model, params).ok);
  NearRangeResult r;
  EXPECT_EQ(tracker.track(image, predicted, 0, r), Status::kOk);
  return r;
}

// interior_edge_bias_px and narrow_face_edge_bias_px, like line_end_bias_px, widen what validity is judged
// on (systematic_gain) by the share of the vertices' lines they concern, never the fit or the scatter's
// covariance the filter takes; a plate has neither kind of line.
TEST(SystematicTerms, InteriorAndStripEdgesWidenTheGainOnlyWhereTheFitHasSuchLines) {
  const PolygonModel model = stripsBox();
  synthetic::RenderOptions options;
  options.noise_sigma = 0.03;
  options.blur_sigma_px = 1.0;
  options.shading.enabled = true;
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(vgaCamera(), model, options).ok);
  const test::RenderedFrame frame = renderFrame(renderer, kStripsTruth, 29);
  const auto track = [&](double interior_px, double narrow_px) {
    NearRangeParams params;
    params.interior_edge_bias_px = interior_px;
    params.narrow_face_edge_bias_px = narrow_px;
    return trackOnce(model, params, frame.image(), kStripsTruth);
  };
  const NearRangeResult base = track(0.0, 0.0);
  ASSERT_NE(base.status, TrackStatus::kLost) << "flags " << base.flags;
  ASSERT_NE(base.flags & kFlagNarrowFace, 0U);
  EXPECT_EQ(base.systematic_gain, 1.0);
  const CovarianceTerms& c = base.covariance_terms;
  ASSERT_GT(c.vertex_factor, 0.0);
  // Shares of the same vertices' 1/sin^2: each between none and all of them.
  EXPECT_GT(c.interior_factor_per_px2, 0.0);
  EXPECT_LT(c.interior_factor_per_px2, c.bias_factor_per_px2);
  EXPECT_GT(c.narrow_factor_per_px2, 0.0);
  EXPECT_LE(c.narrow_factor_per_px2, c.bias_factor_per_px2);
  for (const auto& [interior_px, narrow_px] :
       {std::pair{0.5, 0.0}, std::pair{0.0, 0.5}, std::pair{0.5, 1.0}}) {
    const NearRangeResult r = track(interior_px, narrow_px);
    EXPECT_TRUE(r.pose.t_c_m == base.pose.t_c_m);  // exactly the same fit
    EXPECT_TRUE(r.covariance == base.covariance);
    const double expected =
        std::max(c.residual_factor, c.vertex_factor + interior_px * interior_px * c.interior_factor_per_px2 +
                                        narrow_px * narrow_px * c.narrow_factor_per_px2) /
        std::max(c.residual_factor, c.vertex_factor);
    EXPECT_NEAR(r.systematic_gain, expected, 1e-12) << interior_px << " " << narrow_px;
    EXPECT_GT(r.systematic_gain, 1.0) << interior_px << " " << narrow_px;
  }
  // A face-on plate: no interior edge, no strip, no term.
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  synthetic::Renderer plate_renderer;
  ASSERT_TRUE(plate_renderer.init(vgaCamera(), plate, synthetic::RenderOptions{}).ok);
  const Pose plate_truth = plateAt(15.0, 0.1, 1.0, 1.0);
  NearRangeParams params;
  params.interior_edge_bias_px = 0.5;
  params.narrow_face_edge_bias_px = 1.0;
  const NearRangeResult r =
      trackOnce(plate, params, renderFrame(plate_renderer, plate_truth, 11).image(), plate_truth);
  ASSERT_EQ(r.status, TrackStatus::kTracking);
  EXPECT_EQ(r.covariance_terms.interior_factor_per_px2, 0.0);
  EXPECT_EQ(r.covariance_terms.narrow_factor_per_px2, 0.0);
  EXPECT_EQ(r.systematic_gain, 1.0);
}

// A plate with a darker bar 0.4 m in front of it, over the middle of its right edge (a solar panel in front
// of a body edge): the bar's own edge projects 6 px inside the hidden part of the plate's edge, so those
// scanlines find the bar's step. Without occluded_scanlines they split the edge's points into two lines 6 px
// apart and the plate's edge gives no line; with it they are not cast and the visible ends give the line.
TEST(OccludedScanlines, AnEdgeBehindAnotherPartIsMeasuredWhereItShowsOnly) {
  const std::vector<Vec3> vertices = {
      {-1.15, -0.9, 0.0}, {1.15, -0.9, 0.0}, {1.15, 0.9, 0.0}, {-1.15, 0.9, 0.0},  // plate
      {1.05, -0.5, 0.4},  {1.8, -0.5, 0.4},  {1.8, 0.5, 0.4},  {1.05, 0.5, 0.4},   // bar in front
  };
  std::vector<ModelSurface> surfaces(2);
  surfaces[0].vertex_indices = {0, 1, 2, 3};
  surfaces[1].vertex_indices = {4, 5, 6, 7};
  PolygonModel model;
  ASSERT_TRUE(PolygonModel::build(vertices, surfaces, model).ok);
  synthetic::RenderOptions options;
  options.noise_sigma = 0.02;
  options.blur_sigma_px = 0.8;
  options.surface_albedo = {0.8, 0.35};
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(vgaCamera(), model, options).ok);
  const Pose truth = plateAt(10.0, -0.3, 2.0, 1.0);
  const test::RenderedFrame frame = renderFrame(renderer, truth, 37);
  const auto trackWith = [&](bool rule) {
    NearRangeParams params;
    params.occluded_scanlines = rule;
    return trackOnce(model, params, frame.image(), truth);
  };
  const NearRangeResult with_rule = trackWith(true);
  const NearRangeResult without = trackWith(false);
  const auto errors = [&](const NearRangeResult& r) {
    const Vec6 e = truth.boxMinus(r.pose);
    return std::pair{e.head<3>().norm() * kDegPerRad, e.tail<3>().norm()};
  };
  const auto [att_with, pos_with] = errors(with_rule);
  const auto [att_without, pos_without] = errors(without);
  std::printf(
      "plate behind a bar, from the true pose: %.3f deg / %.4f m with the rule (%d scanlines hidden), "
      "%.3f deg / %.4f m without\n",
      att_with, pos_with, with_rule.occluded_scanlines, att_without, pos_without);
  ASSERT_NE(with_rule.status, TrackStatus::kLost) << "flags " << with_rule.flags;
  ASSERT_NE(without.status, TrackStatus::kLost) << "flags " << without.flags;
  EXPECT_GT(with_rule.occluded_scanlines, 5);
  EXPECT_EQ(without.occluded_scanlines, 0);
  EXPECT_LT(with_rule.scanlines, without.scanlines);
  EXPECT_LT(att_with, 0.3);
  EXPECT_LT(pos_with, 0.02);
  EXPECT_EQ(with_rule.lines_used, with_rule.lines_total) << "every edge gives its line";
  EXPECT_EQ(with_rule.flags & kFlagLineRejected, 0U);
  EXPECT_EQ(without.lines_used, with_rule.lines_used - 1) << "the hidden edge's points split";
  EXPECT_NE(without.flags & kFlagLineRejected, 0U);
  // A single convex body hides none of its front faces' edges: nothing is left out.
  const PolygonModel box = makeBox(0.726, 0.555, 0.48);
  synthetic::Renderer box_renderer;
  ASSERT_TRUE(box_renderer.init(vgaCamera(), box, synthetic::RenderOptions{}).ok);
  const NearRangeResult r =
      trackOnce(box, NearRangeParams{}, renderFrame(box_renderer, kStripsTruth, 41).image(), kStripsTruth);
  EXPECT_NE(r.status, TrackStatus::kLost);
  EXPECT_EQ(r.occluded_scanlines, 0);
}

}  // namespace
}  // namespace visnav
