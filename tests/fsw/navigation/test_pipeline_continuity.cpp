// Which branch a track keeps across a break in its valid poses, end to end on rendered frames
// (navigation_validity.cpp keptTheBranch): after a short break a clean fit that kept the last valid pose's
// look, or one missing only a line (branch_continuity_missing_lines), continues the branch at once; after a
// longer one only a spotless fit does (branch_continuity_spotless_frames), and none does across a break in
// which a fit beside a narrow strip was withheld (narrow_break_reconfirms; test_pipeline_strip.cpp).
// Otherwise the branch waits for branch_confirm_frames rival-free fits.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline_fixture.hpp"

namespace visnav::nav {
namespace {

using test_support::PipelineTest;

TEST_F(PipelineTest, AFitThatKeptTheLastValidLookAfterAShortBreakContinuesTheBranch) {
  // Ten frames of the approach with frame 4 missing (the camera dropped it): the break makes the branch
  // unknown. Frame 5's fit is clean, accepted by the filter and looks as frame 3's did, so continuity
  // confirms it at once. Frames 5 and 6 wait for the third rival-free fit instead without the rule (0
  // frames), with a look tolerance nothing meets, with a sigma limit below the fit's (this plate at 26 m is
  // known to about 2 deg, so the test raises the doubted limit from its 1 deg default to 3), or when the
  // break is longer than the rule allows (two missing frames, 1 allowed). A break with no fit beside a narrow
  // strip continues the branch with narrow_break_reconfirms too. The covariance limit on validity
  // itself is off: the plate is near it (APoseLessCertainThanTheLimit...). The rule for longer breaks
  // (branch_continuity_spotless_frames) is off here: ASpotlessFitAfterALongerBreak... tests it.
  struct Variant {
    int frames;
    double look_deg;
    double growth_deg;
    double sigma_limit_deg;
    int missing;
    int valid;
    bool narrow_break_reconfirms;
  };
  const int waited = params.navigation.branch_confirm_frames - 1;
  for (const Variant v :
       {Variant{3, 3.0, 1.0, 3.0, 1, 9, false}, Variant{3, 3.0, 1.0, 3.0, 1, 9, true},
        Variant{0, 3.0, 1.0, 3.0, 1, 9 - waited, false}, Variant{3, 0.0, 0.0, 3.0, 1, 9 - waited, false},
        Variant{3, 3.0, 1.0, 1.0, 1, 9 - waited, false}, Variant{1, 3.0, 1.0, 3.0, 2, 8 - waited, false}}) {
    PipelineParams p = params;
    p.navigation.branch_continuity_frames = v.frames;
    p.navigation.branch_continuity_spotless_frames = 0;
    p.navigation.branch_continuity_look_deg = v.look_deg;
    p.navigation.reacquire_tolerance_growth_deg_per_frame = v.growth_deg;
    p.navigation.doubted_max_attitude_sigma_deg = v.sigma_limit_deg;
    p.navigation.max_valid_attitude_sigma_deg = 0.0;
    p.navigation.narrow_break_reconfirms = v.narrow_break_reconfirms;
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(test::plateAt(26.0, 0.1, 1.0, -1.0), 0);
    int valid = 0;
    NavSolution out;
    for (int i = 0; i < 10; ++i) {
      const Frame f = frameAt(i);
      const bool missing = i >= 4 && i < 4 + v.missing;
      pipeline.process(missing ? nullptr : &f, f.exposure_time_ns, out);
      EXPECT_EQ(pipeline.mode(), NavMode::kNearRange) << "frame " << i;
      EXPECT_TRUE(missing || pipeline.lastNearRange().status == TrackStatus::kTracking) << "frame " << i;
      valid += out.pose_valid ? 1 : 0;
    }
    EXPECT_TRUE(out.pose_valid);
    EXPECT_EQ(valid, v.valid) << "continuity frames " << v.frames << ", look " << v.look_deg
                              << " deg, sigma limit " << v.sigma_limit_deg << " deg, " << v.missing
                              << " missing";
  }
}

namespace missing_line {

/// Erases `model`'s edge `edge` from `frame` as its truth projects it, but for 6 px at either end: a
/// rectangle 16 px to either side of it is filled with the mean brightness of its inner half (the face's
/// side), so that the edge's scanlines there find no step and its line too few points.
void eraseEdge(const PolygonModel& model, int edge, test::RenderedFrame& frame) {
  const PinholeCamera camera = test::vgaCamera();
  const ModelEdge& e = model.edges()[static_cast<std::size_t>(edge)];
  Vec2 a, b, centre = Vec2::Zero();
  ASSERT_TRUE(camera.project(
      frame.truth.R_c_m * model.vertices()[static_cast<std::size_t>(e.v0)] + frame.truth.t_c_m, a));
  ASSERT_TRUE(camera.project(
      frame.truth.R_c_m * model.vertices()[static_cast<std::size_t>(e.v1)] + frame.truth.t_c_m, b));
  for (const Vec3& v : model.vertices()) {
    Vec2 px;
    ASSERT_TRUE(camera.project(frame.truth.R_c_m * v + frame.truth.t_c_m, px));
    centre += px / static_cast<double>(model.vertices().size());
  }
  const Vec2 along = (b - a).normalized();
  Vec2 inward(-along.y(), along.x());
  if (inward.dot(centre - a) < 0.0) inward = -inward;
  const double length = (b - a).norm();
  const auto inside = [&](int x, int y, double from_px, double to_px) {
    const Vec2 d = Vec2(x + 0.5, y + 0.5) - a;
    const double s = d.dot(along), n = d.dot(inward);
    return s > 6.0 && s < length - 6.0 && n >= from_px && n <= to_px;
  };
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x)
      if (inside(x, y, 2.0, 16.0)) {
        sum += frame.pixels[static_cast<std::size_t>(y) * 640U + static_cast<std::size_t>(x)];
        ++count;
      }
  ASSERT_GT(count, 100);
  const auto fill = static_cast<std::uint8_t>(std::lround(sum / count));
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x)
      if (inside(x, y, -16.0, 16.0))
        frame.pixels[static_cast<std::size_t>(y) * 640U + static_cast<std::size_t>(x)] = fill;
}

double edgeLengthM(const PolygonModel& model, int i) {
  const ModelEdge& e = model.edges()[static_cast<std::size_t>(i)];
  return (model.vertices()[static_cast<std::size_t>(e.v1)] - model.vertices()[static_cast<std::size_t>(e.v0)])
      .norm();
}

/// A valid pose of these tests is on the truth: within 1 deg and 0.15 m.
void expectOnTruth(const NavSolution& out, const Pose& truth, int frame) {
  EXPECT_LT(rotationAngleRad(out.pose.R_c_m, truth.R_c_m) * kDegPerRad, 1.0) << "frame " << frame;
  EXPECT_LT((out.pose.t_c_m - truth.t_c_m).norm(), 0.15) << "frame " << frame;
}

}  // namespace missing_line

TEST_F(PipelineTest, AFitMissingOnlyALineAfterAShortBreakContinuesTheBranchWhenAllowed) {
  // An octagonal plate at 15 m, frame 4 dropped (the branch becomes unknown), and from frame 5 on one of
  // its long edges erased: each fit after the break finds 7 of its 8 lines, status degraded for that alone,
  // right, accepted by the filter and looking as frame 3's did. With branch_continuity_missing_lines 1 it
  // keeps the branch at once; at 0 (only a clean fit does) frames 5 and 6 wait for the third rival-free
  // fit; with a second edge erased (2 missing) 1 is not enough. No valid pose is ever off the truth.
  const PolygonModel octagon = makeOctagonPlate(2.658, 2.513, 0.437);
  synthetic::Renderer octagon_renderer;
  ASSERT_TRUE(octagon_renderer.init(test::vgaCamera(), octagon, synthetic::RenderOptions{}).ok);
  // The two longest edges (the plate's sides, not its chamfers).
  int longest = -1, second = -1;
  const auto edgeLength = [&](int i) { return missing_line::edgeLengthM(octagon, i); };
  for (int i = 0; i < static_cast<int>(octagon.edges().size()); ++i) {
    if (longest < 0 || edgeLength(i) > edgeLength(longest)) {
      second = longest;
      longest = i;
    } else if (second < 0 || edgeLength(i) > edgeLength(second)) {
      second = i;
    }
  }
  ASSERT_GE(second, 0);
  struct Variant {
    int allowed;
    int erased;
    int valid;
  };
  const int waited = params.navigation.branch_confirm_frames - 1;
  for (const Variant v : {Variant{1, 1, 9}, Variant{0, 1, 9 - waited}, Variant{1, 2, 9 - waited}}) {
    SCOPED_TRACE(testing::Message() << "allowed " << v.allowed << ", erased " << v.erased);
    std::vector<test::RenderedFrame> seq;
    for (int i = 0; i < 10; ++i) {
      seq.push_back(
          test::renderFrame(octagon_renderer, test::plateAt(15.0 - 0.02 * i, 0.2, 6.0, -4.0), 90U + i));
      if (i < 5) continue;
      ASSERT_NO_FATAL_FAILURE(missing_line::eraseEdge(octagon, longest, seq.back()));
      if (v.erased > 1) {
        ASSERT_NO_FATAL_FAILURE(missing_line::eraseEdge(octagon, second, seq.back()));
      }
    }
    PipelineParams p = params;
    p.navigation.branch_continuity_missing_lines = v.allowed;
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), octagon, p).ok);
    pipeline.startNearRange(seq[0].truth, 0);
    int valid = 0;
    for (int i = 0; i < 10; ++i) {
      const Frame f = frameOf(seq, i);
      NavSolution out;
      pipeline.process(i == 4 ? nullptr : &f, f.exposure_time_ns, out);
      ASSERT_EQ(pipeline.mode(), NavMode::kNearRange) << "frame " << i;
      const NearRangeResult& near = pipeline.lastNearRange();
      if (i >= 5) {
        EXPECT_EQ(near.status, TrackStatus::kDegraded) << "the case: frame " << i;
        EXPECT_EQ(near.flags & ~(kFlagLineRejected | kFlagTextureFallback), 0U) << "the case: frame " << i;
        EXPECT_EQ(near.lines_total - near.lines_used, v.erased) << "the case: frame " << i;
      }
      if (!out.pose_valid) continue;
      ++valid;
      missing_line::expectOnTruth(out, seq[static_cast<std::size_t>(i)].truth, i);
    }
    EXPECT_EQ(valid, v.valid);
  }
}

TEST_F(PipelineTest, ASpotlessFitAfterALongerBreakContinuesTheBranchWhenAllowed) {
  // The octagonal plate at 15 m, frames 4-8 dropped: five frames, longer than branch_continuity_frames (3).
  // From frame 9 every fit is spotless (all 8 lines, no flag of any doubt), right, accepted by the filter
  // and looking as frame 3's did: with branch_continuity_spotless_frames 10 it keeps the branch at once;
  // at 0 it waits for branch_confirm_frames rival-free fits. With one long side erased from frame 9 on the
  // fit misses a line: after a break this long that is not enough, and it waits either way.
  const PolygonModel octagon = makeOctagonPlate(2.658, 2.513, 0.437);
  synthetic::Renderer octagon_renderer;
  ASSERT_TRUE(octagon_renderer.init(test::vgaCamera(), octagon, synthetic::RenderOptions{}).ok);
  int longest = 0;
  for (int i = 1; i < static_cast<int>(octagon.edges().size()); ++i)
    if (missing_line::edgeLengthM(octagon, i) > missing_line::edgeLengthM(octagon, longest)) longest = i;
  struct Variant {
    int spotless_frames;
    bool erased;
    int valid;
  };
  const int waited = params.navigation.branch_confirm_frames - 1;
  ASSERT_GT(waited, 0);
  // Frames 0-3 valid, 4-8 dropped, 9-13 valid unless they wait.
  for (const Variant v :
       {Variant{10, false, 9}, Variant{0, false, 9 - waited}, Variant{10, true, 9 - waited}}) {
    SCOPED_TRACE(testing::Message() << "spotless frames " << v.spotless_frames << ", erased " << v.erased);
    std::vector<test::RenderedFrame> seq;
    for (int i = 0; i < 14; ++i) {
      seq.push_back(
          test::renderFrame(octagon_renderer, test::plateAt(15.0 - 0.02 * i, 0.2, 6.0, -4.0), 90U + i));
      if (v.erased && i >= 9) {
        ASSERT_NO_FATAL_FAILURE(missing_line::eraseEdge(octagon, longest, seq.back()));
      }
    }
    PipelineParams p = params;
    p.navigation.branch_continuity_spotless_frames = v.spotless_frames;
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), octagon, p).ok);
    pipeline.startNearRange(seq[0].truth, 0);
    int valid = 0;
    for (int i = 0; i < 14; ++i) {
      const Frame f = frameOf(seq, i);
      NavSolution out;
      const bool dropped = i >= 4 && i <= 8;
      pipeline.process(dropped ? nullptr : &f, f.exposure_time_ns, out);
      ASSERT_EQ(pipeline.mode(), NavMode::kNearRange) << "frame " << i;
      const NearRangeResult& near = pipeline.lastNearRange();
      if (i >= 9 && !v.erased) {
        EXPECT_EQ(near.status, TrackStatus::kTracking) << "the case: frame " << i;
        EXPECT_EQ(near.flags & ~kFlagTextureFallback, 0U) << "the case: frame " << i;
      }
      if (i == 9) {
        EXPECT_EQ(out.pose_valid, v.valid == 9) << "the first frame after the break";
      }
      if (!out.pose_valid) continue;
      ++valid;
      missing_line::expectOnTruth(out, seq[static_cast<std::size_t>(i)].truth, i);
    }
    EXPECT_EQ(valid, v.valid);
  }
}

}  // namespace
}  // namespace visnav::nav
