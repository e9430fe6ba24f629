// The navigation pipeline's output gates end to end on rendered frames (navigation_validity.cpp): a pose
// is tracked but not valid when it is less certain than the limits (with the lines' systematic error), is
// doubted, shows no face, or misses lines of a minimal fit, and a near twin the track lost lines to is
// followed. Disputed poses: test_pipeline_disputed.cpp; the branch across a break:
// test_pipeline_continuity.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "pipeline_fixture.hpp"

namespace visnav::nav {
namespace {

using test_support::PipelineTest;

TEST_F(PipelineTest, AnUnconfirmedTrackThatLostLinesToItsNearTwinFollowsTheTwin) {
  // Campaign octagon/172's near-square plate at 20 m, the track started on its quarter turn (as an
  // acquisition on that twin would leave it), then a dropped frame: the branch is unknown. The start pose's
  // look no longer chooses (its tolerance grows 200 deg a frame here), so the near twin checks count. With
  // follow_near_twin the track that lost lines looks again from the twin, which finds more of them, hands
  // over to it (the truth) and earns its branch: valid and right, nothing allocated. Without it the track
  // stays on the quarter turn, withheld on every frame. Either way no pose off the truth is ever valid.
  const PolygonModel octagon = makeOctagonPlate(2.658, 2.513, 0.437);
  synthetic::Renderer octagon_renderer;
  ASSERT_TRUE(octagon_renderer.init(test::vgaCamera(), octagon, synthetic::RenderOptions{}).ok);
  ModelSymmetries symmetries;
  symmetries.find(octagon);
  symmetries.findNear(octagon, params.nearrange.near_twin_rival_max_rel);
  int quarter = -1;
  for (int i = 0; i < symmetries.nearCount() && quarter < 0; ++i)
    if (std::fabs(rotationAngleRad(Mat3::Identity(), symmetries.near(i)) - 0.5 * kPi) < 1e-6) quarter = i;
  ASSERT_GE(quarter, 0);
  std::vector<test::RenderedFrame> seq;
  for (int i = 0; i < 14; ++i)
    seq.push_back(
        test::renderFrame(octagon_renderer, test::plateAt(20.0 - 0.05 * i, 0.2, 8.0, -5.0), 60U + i));
  for (const bool follow : {true, false}) {
    PipelineParams p = params;
    p.navigation.follow_near_twin = follow;
    p.navigation.reacquire_tolerance_growth_deg_per_frame = 200.0;
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), octagon, p).ok);
    pipeline.startNearRange(symmetries.nearTwin(seq[0].truth, quarter), 0);
    int valid_right = 0;
    const std::uint64_t allocations_before = test::allocationCount();
    for (int i = 0; i < static_cast<int>(seq.size()); ++i) {
      const Frame f = frameOf(seq, i);
      NavSolution out;
      pipeline.process(i == 1 ? nullptr : &f, f.exposure_time_ns, out);
      if (!out.pose_valid) continue;
      const Pose& truth = seq[static_cast<std::size_t>(i)].truth;
      const double off_deg = symmetries.attitudeDistanceRad(out.pose.R_c_m, truth.R_c_m) * kDegPerRad;
      ASSERT_LT(off_deg, 3.0) << "follow " << follow << ", frame " << i << ": a wrong pose delivered";
      if (i > 1) ++valid_right;
    }
    const std::uint64_t allocations = test::allocationCount() - allocations_before;
    SCOPED_TRACE(follow);
    EXPECT_EQ(allocations, 0U) << "malloc counted: " << test::countsMalloc();
    if (follow) {
      EXPECT_GE(pipeline.nearTwinsFollowed(), 1U);
      EXPECT_GE(valid_right, 6) << "the twin's track earned its branch";
    } else {
      EXPECT_EQ(pipeline.nearTwinsFollowed(), 0U);
      EXPECT_EQ(valid_right, 0)
          << "the quarter turn's track became right without following: the test tests nothing";
    }
  }
}

TEST_F(PipelineTest, APoseBesideAFaceSeenEdgeOnMustMeetTheDoubtedLimit) {
  // A box nearly face-on at 26 m (campaign box/25's case): its side faces are strips of a few pixels, and
  // the lines beside them may be biased by up to that width while their scatter stays tight, so the fit's
  // own 1-sigma understates it. Here every fit is right (the test's truth) and its 1-sigma lies between the
  // doubted limit and the valid one: with doubt_narrow_face it is tracked on but never valid, without it
  // is delivered. The campaign weighs the two (README, stop 46).
  const PolygonModel box = makeBox(0.726, 0.555, 0.48);
  synthetic::Renderer box_renderer;
  synthetic::RenderOptions options;
  options.noise_sigma = 0.04;
  options.blur_sigma_px = 0.8;
  ASSERT_TRUE(box_renderer.init(test::vgaCamera(), box, options).ok);
  const Pose truth = test::plateAt(26.0, 0.2, 25.0, 7.0);
  std::vector<test::RenderedFrame> box_frames;
  for (int i = 0; i < 10; ++i) box_frames.push_back(test::renderFrame(box_renderer, truth, 700U + i));
  for (const bool doubt : {true, false}) {
    PipelineParams p;
    p.navigation.doubt_narrow_face = doubt;
    const int valid = validFromTruth(
        box, box_frames, truth, p, [&](const NavigationPipeline& pipeline, const NavSolution& out, int i) {
          EXPECT_NE(pipeline.lastNearRange().flags & kFlagNarrowFace, 0U) << "frame " << i;
          const double sigma_deg = poseSigmas(out.pose, out.covariance).attitude_deg;
          EXPECT_GT(sigma_deg, p.navigation.doubted_max_attitude_sigma_deg) << "the case: frame " << i;
          EXPECT_LE(sigma_deg, p.navigation.max_valid_attitude_sigma_deg) << "the case: frame " << i;
        });
    if (doubt)
      EXPECT_EQ(valid, 0);
    else
      EXPECT_GE(valid, 8);
  }
}

TEST_F(PipelineTest, APoseLessCertainThanTheLimitIsTrackedButNotValid) {
  // The same ten near-range frames under three limits on the pose's own 1-sigma attitude: one no fit
  // exceeds (this plate at 26 m is known to about 2.2 deg, near the 2.5 deg default), a limit below what any
  // fit reaches (the pose is still tracked, frame to frame, and reported, but never valid), and the check
  // switched off.
  for (const double limit_deg : {180.0, 1e-9, 0.0}) {
    PipelineParams p = params;
    p.navigation.max_valid_attitude_sigma_deg = limit_deg;
    NavSolution out;
    const int valid = validOverTenFrames(p, out);
    const double sigma_deg = std::sqrt(out.covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
    EXPECT_GT(sigma_deg, 0.0);
    EXPECT_EQ(valid, limit_deg == 1e-9 ? 0 : 10) << "limit " << limit_deg << ", last sigma " << sigma_deg;
    // Tracked either way: the last pose follows the plate (25.1 m at frame 9), not the start.
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "limit " << limit_deg;
  }
}

TEST_F(PipelineTest, ACompleteFitTheFilterAcceptedIsDeliveredAsTheFiltersEstimate) {
  // [navigation] deliver_filtered_pose. The paper's plate at 26 m is known to about 2.2 deg from one frame's
  // fit, certain on its own under a 4 deg limit; a doubt_nis_chi2 below any NIS doubts every fit the filter
  // accepts, and under a doubted limit of 1.6 deg no fit alone is valid. The filter's estimate after a
  // complete, certain fit it accepted carries the frames before, and its 1-sigma falls under the limit within
  // a few frames; its attitude error is smaller than the fits' (rms over the ten frames), and no pose is
  // wrong (5 deg) either way.
  double rms_deg[2] = {0.0, 0.0};
  for (const bool deliver_filtered : {false, true}) {
    PipelineParams p = params;
    p.navigation.max_valid_attitude_sigma_deg = 4.0;
    p.navigation.doubted_max_attitude_sigma_deg = 1.6;
    p.navigation.doubt_nis_chi2 = 1e-9;
    p.navigation.deliver_filtered_pose = deliver_filtered;
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(frames.front().truth, 0);
    int valid = 0;
    int filtered = 0;
    double sum_sq = 0.0;
    for (int i = 0; i < 10; ++i) {
      const Frame f = frameAt(i);
      NavSolution out;
      ASSERT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
      const NearRangeResult& fit = pipeline.lastNearRange();
      ASSERT_NE(fit.status, TrackStatus::kLost) << "frame " << i;
      const double fit_sigma_deg = std::sqrt(fit.covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
      EXPECT_GT(fit_sigma_deg * std::sqrt(fit.systematic_gain), 1.6)
          << "no doubted fit alone is valid: frame " << i;
      if (pipeline.lastPoseFiltered()) {
        ++filtered;
        EXPECT_TRUE(fitIsComplete(fit)) << "frame " << i;
        EXPECT_TRUE(withinValidSigmas(fit.pose, fit.covariance * fit.systematic_gain, p.navigation));
        EXPECT_TRUE(out.pose.t_c_m.isApprox(pipeline.filter().pose().t_c_m)) << "frame " << i;
        EXPECT_TRUE(out.covariance.isApprox(pipeline.filter().poseCovariance() * fit.systematic_gain));
      } else {
        EXPECT_TRUE(out.pose.t_c_m.isApprox(fit.pose.t_c_m)) << "the fit as measured: frame " << i;
      }
      const double error_deg =
          rotationAngleRad(out.pose.R_c_m, frames[static_cast<std::size_t>(i)].truth.R_c_m) * kDegPerRad;
      EXPECT_LT(error_deg, 5.0) << "frame " << i;
      sum_sq += error_deg * error_deg;
      valid += out.pose_valid ? 1 : 0;
    }
    rms_deg[deliver_filtered ? 1 : 0] = std::sqrt(sum_sq / 10.0);
    if (deliver_filtered) {
      EXPECT_GE(filtered, 8);
      EXPECT_GE(valid, 5);
    } else {
      EXPECT_EQ(filtered, 0);
      EXPECT_EQ(valid, 0);
    }
    std::printf("deliver_filtered_pose %d: %d of 10 frames filtered, %d valid, attitude error rms %.2f deg\n",
                deliver_filtered ? 1 : 0, filtered, valid, rms_deg[deliver_filtered ? 1 : 0]);
  }
  EXPECT_LT(rms_deg[1], rms_deg[0]);
  // A fit uncertain on its own (the same frames under a 1.6 deg limit) is delivered, and judged, as
  // measured: an uncertain fit's error repeats from frame to frame (campaign plate/5023: fits of 3-5 deg
  // 1-sigma, 4-7 deg off, filtered to 1.8 deg 1-sigma and still 5.3 deg off).
  PipelineParams p = params;
  p.navigation.max_valid_attitude_sigma_deg = 1.6;
  NavigationPipeline pipeline;
  ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
  pipeline.startNearRange(frames.front().truth, 0);
  for (int i = 0; i < 10; ++i) {
    const Frame f = frameAt(i);
    NavSolution out;
    ASSERT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
    EXPECT_FALSE(pipeline.lastPoseFiltered()) << "frame " << i;
    EXPECT_FALSE(out.pose_valid) << "frame " << i;
    EXPECT_TRUE(out.pose.t_c_m.isApprox(pipeline.lastNearRange().pose.t_c_m)) << "frame " << i;
  }
}

TEST_F(PipelineTest, TheLinesSystematicEndErrorIsInTheDeliveredCovarianceAndItsValidity) {
  // [nearrange] line_end_bias_px: this plate at 26 m is known to about 2.2-2.6 deg from its points'
  // scatter, under a 4 deg limit; a 1 px systematic error on every line end puts it far above. The delivered
  // covariance carries it, validity is judged on it, and the track goes on either way (the filter takes the
  // scatter's covariance).
  double sigma_without_deg = 0.0;
  for (const double bias_px : {0.0, 1.0}) {
    PipelineParams p = params;
    p.nearrange.line_end_bias_px = bias_px;
    p.navigation.max_valid_attitude_sigma_deg = 4.0;
    NavSolution out;
    const int valid = validOverTenFrames(p, out);
    const double sigma_deg = std::sqrt(out.covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
    if (bias_px == 0.0) {
      sigma_without_deg = sigma_deg;
      ASSERT_LT(sigma_deg, 4.0) << "the scene must be certain without the bias";
      EXPECT_EQ(valid, 10);
    } else {
      EXPECT_GT(sigma_deg, 2.0 * sigma_without_deg);
      EXPECT_EQ(valid, 0) << "1-sigma " << sigma_deg << " deg";
      EXPECT_EQ(out.withheld & kWithheldUncertain, kWithheldUncertain);
    }
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "tracked either way, bias " << bias_px;
  }
}

TEST_F(PipelineTest, APoseTheFilterFindsSurprisingMustMeetTheDoubtedLimit) {
  // The same ten frames: every fit passes the innovation gate, and this plate at 26 m is known to about
  // 2.2 deg, above the doubted limit (1 deg). A NIS limit below any fit's NIS doubts every frame after the
  // start pose started the filter (each is a 6-DOF update): tracked, never valid. Off, and at the default
  // (99 % of chi-square with 6 dof, which these consistent fits stay under), all ten are valid.
  ASSERT_GT(params.navigation.doubt_nis_chi2, 0.0);
  for (const double limit : {1e-9, 0.0, params.navigation.doubt_nis_chi2}) {
    PipelineParams p = params;
    p.navigation.doubt_nis_chi2 = limit;
    p.navigation.max_valid_attitude_sigma_deg = 0.0;  // near this plate's 1-sigma (the test above)
    NavSolution out;
    EXPECT_EQ(validOverTenFrames(p, out), limit == 1e-9 ? 0 : 10) << "limit " << limit;
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "tracked either way, limit " << limit;
  }
}

TEST_F(PipelineTest, AFirstFitThatDisagreesWithTheStartPoseMustMeetTheDoubtedLimit) {
  // The operator's start pose 4 deg off in yaw and in pitch: the first fit finds the plate (26 m, about
  // 2.2 deg 1-sigma, above the doubted limit) and disagrees with the start pose by a NIS above the chi-square
  // median. Doubted, it is withheld, which breaks the branch: validity returns once branch_confirm_frames
  // rival-free frames confirmed it again (7 of 10). With the check off all ten are valid, and a start pose
  // on the truth (NIS near 0) is not doubted at all. Tracked throughout.
  const Pose off_start = test::plateAt(26.0, 0.1, 5.0, -5.0);
  ASSERT_GT(PipelineParams{}.navigation.start_pose_doubt_nis_chi2, 0.0);
  for (const double limit : {PipelineParams{}.navigation.start_pose_doubt_nis_chi2, 0.0}) {
    PipelineParams p = params;
    p.navigation.start_pose_doubt_nis_chi2 = limit;
    p.navigation.max_valid_attitude_sigma_deg = 0.0;  // near this plate's 1-sigma (the tests above)
    NavSolution out;
    const int valid = validOverTenFrames(p, out, off_start);
    EXPECT_EQ(valid, limit > 0.0 ? 10 - 1 - (p.navigation.branch_confirm_frames - 1) : 10)
        << "limit " << limit;
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "tracked either way, limit " << limit;
    EXPECT_EQ(validOverTenFrames(p, out), 10) << "a start pose on the truth, limit " << limit;
  }
}

TEST_F(PipelineTest, TheFirstStartPoseDoubtFitsAreJudgedAgainstTheStartPose) {
  // A NIS limit below any fit's doubts each of the first start_pose_doubt_fits fits (this plate's 2.2 deg
  // 1-sigma is above the doubted limit): each is withheld, and branch_confirm_frames rival-free frames after
  // them confirm the branch again. 0 switches the check off.
  for (const int fits : {0, 1, 2, 3}) {
    PipelineParams p = params;
    p.navigation.start_pose_doubt_nis_chi2 = 1e-9;
    p.navigation.start_pose_doubt_fits = fits;
    p.navigation.max_valid_attitude_sigma_deg = 0.0;  // near this plate's 1-sigma (the tests above)
    NavSolution out;
    EXPECT_EQ(validOverTenFrames(p, out),
              fits == 0 ? 10 : 10 - fits - (p.navigation.branch_confirm_frames - 1))
        << fits << " fits";
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "tracked either way, " << fits << " fits";
  }
}

TEST_F(PipelineTest, AFourLineFitWhosePoseShowsMoreLinesThanFoundIsTrackedButNotValid) {
  // A box seen on its corner at 10 m with only its nearest face lit (the other two as dark as space): the
  // image gives that face's 4 lines, the pose predicts the other faces' outline too. A 4-line fit has no line
  // to spare, so one on a wrong edge would go unseen (campaign box/5030): with the default limit the right
  // fits here are tracked on but never valid, with the check off they are delivered.
  const PolygonModel box = makeBox(0.6, 0.6, 0.6);
  const Pose truth = test::plateAt(10.0, 0.0, 35.0, -30.0);
  synthetic::RenderOptions options;
  options.noise_sigma = 0.04;
  options.surface_albedo.assign(box.surfaces().size(), options.background);
  std::size_t front = 0;
  double best_facing = -1.0;
  for (std::size_t i = 0; i < box.surfaces().size(); ++i) {
    const ModelSurface& s = box.surfaces()[i];
    const Vec3 centre_c = truth.transform(s.centroid_m);
    const double facing = -(truth.R_c_m * s.normal_m).dot(centre_c.normalized());
    if (facing > best_facing) {
      best_facing = facing;
      front = i;
    }
  }
  options.surface_albedo[front] = 0.8;
  synthetic::Renderer box_renderer;
  ASSERT_TRUE(box_renderer.init(test::vgaCamera(), box, options).ok);
  std::vector<test::RenderedFrame> box_frames;
  for (int i = 0; i < 10; ++i) box_frames.push_back(test::renderFrame(box_renderer, truth, 900U + i));
  for (const int limit : {PipelineParams{}.navigation.minimal_fit_max_missing_lines, -1}) {
    PipelineParams p;
    p.navigation.minimal_fit_max_missing_lines = limit;
    const int valid = validFromTruth(box, box_frames, truth, p,
                                     [](const NavigationPipeline& pipeline, const NavSolution&, int i) {
                                       const NearRangeResult& r = pipeline.lastNearRange();
                                       EXPECT_LE(r.lines_used, kMinimalFitLines) << "the case: frame " << i;
                                       EXPECT_GT(r.lines_total - r.lines_used, 2) << "the case: frame " << i;
                                     });
    if (limit >= 0)
      EXPECT_EQ(valid, 0);
    else
      EXPECT_GE(valid, 8);
  }
}

TEST_F(PipelineTest, APoseShowingNoSurfaceNearFacingIsTrackedButNotValid) {
  // The plate's face turns 1.2-1.7 deg from the line of sight to its centre here (yaw 1, pitch -1 deg, 0.1 m
  // off the axis). Limits of 80 deg (edge-on only), 0.5 deg (under that angle: the plate counts as turned
  // away on every frame) and the check off, on the same ten frames. The covariance limit is off: this plate
  // at 26 m is near it (the test above).
  for (const double limit_deg : {80.0, 0.5, 0.0}) {
    PipelineParams p = params;
    p.navigation.max_valid_view_angle_deg = limit_deg;
    p.navigation.max_valid_attitude_sigma_deg = 0.0;
    NavSolution out;
    EXPECT_EQ(validOverTenFrames(p, out), limit_deg == 0.5 ? 0 : 10) << "limit " << limit_deg;
    EXPECT_NEAR(out.pose.t_c_m.z(), 26.0 - 0.1 * 9, 0.2) << "tracked either way, limit " << limit_deg;
  }
}

}  // namespace
}  // namespace visnav::nav
