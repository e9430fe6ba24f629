// The navigation pipeline's output gates for a disputed pose end to end on rendered frames
// (navigation_pipeline.cpp, runNearRange): a fit the filter's innovation gate rejects is not delivered on
// weak evidence; with good evidence the measurement wins and the filter restarts from it, but the pose is
// not valid on its frame when it turned or moved faster than a target does or its NIS is far beyond the
// gate, nor on the next when it is doubted. The other output gates: test_pipeline_gates.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "pipeline_fixture.hpp"

namespace visnav::nav {
namespace {

using test_support::PipelineTest;
TEST_F(PipelineTest, WeakEvidenceTheFilterRejectsIsNotDelivered) {
  // Ten frames of a steady approach in near range, then the plate jumps 0.15 m sideways (6 px: within the
  // tracker's reach, far outside the filter's prediction, so the NIS gate rejects it). With good image
  // evidence the measurement wins and the filter restarts; when no frame's evidence counts as good
  // (evidence_max_rms_px tiny), the disputed measurement must not be delivered as valid. The doubted-pose
  // limit is off here (its own test follows).
  for (const bool weak : {false, true}) {
    PipelineParams p = params;
    p.navigation.doubted_max_attitude_sigma_deg = 0.0;
    p.navigation.disputed_max_nis = 0.0;  // its own test follows
    if (weak) p.navigation.evidence_max_rms_px = 1e-9;
    NavigationPipeline pipeline;
    NavSolution steady;
    NavSolution out;
    runToJump(pipeline, p, steady, out);
    ASSERT_TRUE(steady.pose_valid) << "weak=" << weak;
    EXPECT_NE(out.fault_bits & kFaultInnovation, 0U) << "weak=" << weak;
    if (weak) {
      EXPECT_FALSE(out.pose_valid);
    } else {
      ASSERT_TRUE(out.pose_valid);
      EXPECT_NEAR(out.pose.t_c_m.x(), 0.25, 0.02);  // the image's pose, not the prediction's
    }
  }
}

TEST_F(PipelineTest, ADisputedPoseWithWeakGeometryIsTrackedButNotValid) {
  // The same jump with good image evidence: the measurement wins and the track follows it, but the filter
  // disputes it and a plate at 25 m on VGA has about 2 deg attitude 1-sigma, above the doubted-pose limit
  // (1 deg), so that frame and the one after it are withheld. Once the fits agree with the restarted filter
  // again the branch is confirmed and the poses are valid. With a limit above the pose's sigma the disputed
  // frame is valid. The branch is confirmed by rival-free frames here, not by the look's continuity (the test
  // after next).
  for (const double limit_deg : {1.0, 2.4}) {
    PipelineParams p = params;
    p.navigation.doubted_max_attitude_sigma_deg = limit_deg;
    p.navigation.branch_continuity_frames = 0;
    p.navigation.disputed_max_nis = 0.0;  // this jump's NIS is above it (the test after next)
    NavigationPipeline pipeline;
    NavSolution out;
    ASSERT_NO_FATAL_FAILURE(runToDisputedJump(pipeline, p, out)) << "limit " << limit_deg;
    const double sigma_deg = std::sqrt(out.covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
    ASSERT_GT(sigma_deg, 1.0);
    ASSERT_LT(sigma_deg, 2.4);
    EXPECT_NEAR(out.pose.t_c_m.x(), 0.25, 0.02) << "limit " << limit_deg;  // tracked either way
    EXPECT_EQ(out.pose_valid, limit_deg > sigma_deg) << "limit " << limit_deg;
    // NavSolution::withheld says why: the doubt, and nothing else (the pose is within the undoubted limit).
    EXPECT_EQ(out.withheld, limit_deg > sigma_deg ? 0U : static_cast<std::uint32_t>(kWithheldDoubted))
        << "limit " << limit_deg;
    // The target stays where it jumped: no more doubt, and after the branch confirmation it is valid.
    int valid = 0;
    for (int i = 11; i < 16; ++i) {
      Frame g = frameAt(i);
      const test::RenderedFrame still =
          test::renderFrame(renderer, test::plateAt(25.0, 0.25, 1.0, -1.0), 800U + static_cast<unsigned>(i));
      g.image = still.image();
      pipeline.process(&g, g.exposure_time_ns, out);
      EXPECT_EQ(out.fault_bits & kFaultInnovation, 0U) << "frame " << i;
      valid += out.pose_valid ? 1 : 0;
      EXPECT_EQ(out.pose_valid, out.withheld == 0U) << "frame " << i << " withheld " << out.withheld;
    }
    EXPECT_TRUE(out.pose_valid) << "limit " << limit_deg;
    // Under the 1 deg limit the first frame after the restart is doubted too (doubt_after_filter_restart:
    // it agrees with the one disputed fit only), then the branch is confirmed.
    const int after_restart = params.navigation.doubt_after_filter_restart ? 1 : 0;
    EXPECT_EQ(valid,
              limit_deg > sigma_deg ? 5 : 5 - after_restart - (params.navigation.branch_confirm_frames - 1))
        << "limit " << limit_deg;
  }
}

TEST_F(PipelineTest, ADisputedPoseFarBeyondTheGateIsTrackedButNotValidOnItsFrame) {
  // The same 6 px jump, with good image evidence and the other jump rules and the doubted limit off: its
  // NIS is far above disputed_max_nis, so the pose is tracked (the filter restarts from it) but withheld as
  // a jump on that frame; with the check off it is valid.
  for (const double max_nis : {PipelineParams{}.navigation.disputed_max_nis, 0.0}) {
    PipelineParams p = params;
    p.navigation.doubted_max_attitude_sigma_deg = 0.0;
    p.navigation.disputed_max_look_change_deg = 0.0;
    p.navigation.disputed_max_range_change_rel = 0.0;
    p.navigation.disputed_max_nis = max_nis;
    NavigationPipeline pipeline;
    NavSolution out;
    ASSERT_NO_FATAL_FAILURE(runToDisputedJump(pipeline, p, out)) << "max NIS " << max_nis;
    ASSERT_GT(pipeline.lastPoseUpdate().nis, PipelineParams{}.navigation.disputed_max_nis)
        << "the scene must reach the case";
    EXPECT_NEAR(out.pose.t_c_m.x(), 0.25, 0.02) << "tracked either way, max NIS " << max_nis;
    EXPECT_EQ(out.pose_valid, max_nis == 0.0) << "max NIS " << max_nis;
    EXPECT_EQ(out.withheld & kWithheldJumped,
              max_nis == 0.0 ? 0U : static_cast<std::uint32_t>(kWithheldJumped));
  }
}

TEST_F(PipelineTest, ADisputedPoseThatTurnedFasterThanATargetTurnsIsTrackedButNotValid) {
  // The plate at 20 m, still for 10 frames, then turned 9 deg about the boresight from one frame to the
  // next (what a fit that jumped onto other edges looks like): the filter disputes it (innovation fault),
  // the image supports it, so the track goes on from it, but not as a valid pose on that frame.
  std::vector<test::RenderedFrame> seq;
  for (int i = 0; i < 20; ++i)
    seq.push_back(test::renderFrame(renderer, test::plateAt(20.0, 0.1, i < 10 ? 1.0 : 10.0, -1.0), 900U + i));
  for (const double limit_deg : {5.0, 0.0}) {
    PipelineParams p = params;
    p.navigation.disputed_max_look_change_deg = limit_deg;
    p.navigation.disputed_max_nis = 0.0;  // this rule alone
    p.navigation.doubted_max_attitude_sigma_deg =
        0.0;  // at 20 m the plate's 1-sigma is above it: this rule alone
    const std::vector<NavSolution> out = solutionsFromFirstTruth(seq, p);
    for (int i = 1; i < 10; ++i) EXPECT_TRUE(out[static_cast<std::size_t>(i)].pose_valid) << i;
    ASSERT_NE(out[10].fault_bits & kFaultInnovation, 0U) << "the scene must reach the case";
    EXPECT_EQ(out[10].mode, NavMode::kNearRange);
    EXPECT_EQ(out[10].pose_valid, limit_deg == 0.0) << "limit " << limit_deg;
    // Tracked on from the jump: the pose followed it, and validity returns once the track confirms.
    EXPECT_LT(rotationAngleRad(out[10].pose.R_c_m, seq[10].truth.R_c_m) * kDegPerRad, 2.0);
    EXPECT_TRUE(out.back().pose_valid) << "limit " << limit_deg;
  }
}

TEST_F(PipelineTest, ADisputedPoseThatMovedInRangeFasterThanPredictedIsTrackedButNotValid) {
  // The same still plate, 6 % further from one frame to the next with the same attitude (what a fit that
  // locked on another pair of edges looks like in depth): disputed, supported by the image, so tracked on
  // from, but not valid on that frame under disputed_max_range_change_rel; the look gate alone passes it.
  std::vector<test::RenderedFrame> seq;
  for (int i = 0; i < 20; ++i)
    seq.push_back(test::renderFrame(renderer, test::plateAt(i < 10 ? 20.0 : 21.2, 0.1, 1.0, -1.0), 900U + i));
  for (const double limit_rel : {0.03, 0.0}) {
    PipelineParams p = params;
    p.navigation.disputed_max_range_change_rel = limit_rel;
    p.navigation.disputed_max_nis = 0.0;
    p.navigation.doubted_max_attitude_sigma_deg = 0.0;  // as above: this rule alone
    bool jumped_on_the_move = false;
    const std::vector<NavSolution> out =
        solutionsFromFirstTruth(seq, p, [&](const NavigationPipeline& pipeline, int i) {
          if (i == 10) jumped_on_the_move = pipeline.lastPoseJumped();
        });
    for (int i = 1; i < 10; ++i) EXPECT_TRUE(out[static_cast<std::size_t>(i)].pose_valid) << i;
    ASSERT_NE(out[10].fault_bits & kFaultInnovation, 0U) << "the scene must reach the case";
    EXPECT_EQ(out[10].mode, NavMode::kNearRange);
    EXPECT_EQ(out[10].pose_valid, limit_rel == 0.0) << "limit " << limit_rel;
    EXPECT_EQ(jumped_on_the_move, limit_rel > 0.0) << "the replay's jumped column";
    EXPECT_NEAR(out[10].pose.t_c_m.norm(), seq[10].truth.t_c_m.norm(), 0.2) << "the track followed the move";
    EXPECT_TRUE(out.back().pose_valid) << "limit " << limit_rel;
  }
}

TEST_F(PipelineTest, TheFitAfterOneThatOverruledTheFilterMustMeetTheDoubtedLimit) {
  // The plate at 20 m (1-sigma above the doubted limit, below the valid one) jumps 6 % in range: the fit the
  // filter rejects is supported by the image, so the filter restarts from it (doubted, withheld). The next
  // fit agrees with that one disputed fit only: doubted too under doubt_after_filter_restart, valid
  // without (one rival-free frame confirms the branch here, so that the rule alone decides). Tracked either
  // way.
  std::vector<test::RenderedFrame> seq;
  for (int i = 0; i < 14; ++i)
    seq.push_back(test::renderFrame(renderer, test::plateAt(i < 10 ? 20.0 : 21.2, 0.1, 1.0, -1.0), 900U + i));
  for (const bool rule : {true, false}) {
    PipelineParams p = params;
    p.navigation.doubt_after_filter_restart = rule;
    p.navigation.disputed_max_range_change_rel = 0.0;
    p.navigation.branch_confirm_frames = 1;
    // The jump is real here, 6 % in one frame: branch_range_after_jump would withhold the fits after it
    // until its tolerance grew past 6 % (PipelineTest.AfterAJumpAFitOffTheLastValidRangeDoesNotConfirm...).
    p.navigation.branch_range_after_jump = false;
    const std::vector<NavSolution> out = solutionsFromFirstTruth(seq, p);
    ASSERT_NE(out[10].fault_bits & kFaultInnovation, 0U) << "the scene must reach the case";
    EXPECT_NEAR(out[10].pose.t_c_m.norm(), seq[10].truth.t_c_m.norm(), 0.2) << "the filter took the jump";
    const double sigma_deg = std::sqrt(out[11].covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
    ASSERT_GT(sigma_deg, p.navigation.doubted_max_attitude_sigma_deg) << "the fit must be doubtable";
    ASSERT_LT(sigma_deg, p.navigation.max_valid_attitude_sigma_deg) << "and certain enough otherwise";
    EXPECT_EQ(out[11].fault_bits & kFaultInnovation, 0U) << "the restarted filter agrees with it";
    EXPECT_EQ(out[11].pose_valid, !rule) << "rule " << rule << ", 1-sigma " << sigma_deg;
    EXPECT_EQ(out[11].mode, NavMode::kNearRange);
    EXPECT_TRUE(out[12].pose_valid) << "rule " << rule;
    EXPECT_NEAR(out.back().pose.t_c_m.norm(), seq.back().truth.t_c_m.norm(), 0.2) << "rule " << rule;
  }
}

}  // namespace
}  // namespace visnav::nav
