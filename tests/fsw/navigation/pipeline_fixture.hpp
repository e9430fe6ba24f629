// The fixture of the navigation pipeline's end-to-end tests (test_pipeline.cpp,
// test_pipeline_reacquisition.cpp, test_pipeline_branch.cpp, test_pipeline_gates.cpp): the paper's plate
// rendered at 5 Hz, and a plate hidden for ten frames (an eclipse).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "../../support/alloc_counter.hpp"
#include "../nearrange/tracker_fixture.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"

namespace visnav::nav::test_support {

/// The paper's plate approaching from 26 m to 20 m (frames at 5 Hz), rendered with the paper's recipe.
class PipelineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    model = makeRectanglePlate(2.3, 1.8);
    ASSERT_TRUE(renderer.init(test::vgaCamera(), model, synthetic::RenderOptions{}).ok);
    for (int i = 0; i < kFrames; ++i) {
      const double d = 26.0 - 0.1 * i;
      frames.push_back(test::renderFrame(renderer, test::plateAt(d, 0.1, 1.0, -1.0), 100U + i));
    }
    // gamma for this plate (visnav-calibrate-gamma on approach_ci prints 2011): far range then reads ~26 m.
    params.farrange.gamma = 2011.0;
  }
  /// Frame i of a rendered sequence at 5 Hz (exposure 200 ms apart, sequence number i).
  static Frame frameOf(const std::vector<test::RenderedFrame>& sequence, int i) {
    Frame f;
    f.image = sequence[static_cast<std::size_t>(i)].image();
    f.exposure_time_ns = 200000000LL * i;
    f.sequence = static_cast<std::uint64_t>(i);
    return f;
  }
  Frame frameAt(int i) const { return frameOf(frames, i); }
  /// A still `sequence` of `target` tracked from its `truth` (the given start pose) under `p`: how many
  /// frames were valid. Every frame must stay in near range with a fit (not lost) within 2 deg of the truth;
  /// `each(pipeline, out, i)` checks the case on every frame.
  template <typename EachFrame>
  static int validFromTruth(const PolygonModel& target, const std::vector<test::RenderedFrame>& sequence,
                            const Pose& truth, const PipelineParams& p, EachFrame each) {
    NavigationPipeline pipeline;
    EXPECT_TRUE(pipeline.init(test::vgaCamera(), target, p).ok);
    pipeline.startNearRange(truth, 0);
    int valid = 0;
    for (int i = 0; i < static_cast<int>(sequence.size()); ++i) {
      const Frame f = frameOf(sequence, i);
      NavSolution out;
      EXPECT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
      EXPECT_EQ(pipeline.mode(), NavMode::kNearRange) << "frame " << i;
      EXPECT_NE(pipeline.lastNearRange().status, TrackStatus::kLost) << "frame " << i;
      EXPECT_LT(rotationAngleRad(out.pose.R_c_m, truth.R_c_m) * kDegPerRad, 2.0) << "tracked: frame " << i;
      each(pipeline, out, i);
      valid += out.pose_valid ? 1 : 0;
    }
    return valid;
  }
  /// The plate's `sequence` under `p` from its first frame's truth (the given start pose): every frame's
  /// solution; `each(pipeline, i)` sees the pipeline right after frame i.
  template <typename EachFrame>
  std::vector<NavSolution> solutionsFromFirstTruth(const std::vector<test::RenderedFrame>& sequence,
                                                   const PipelineParams& p, EachFrame each) {
    NavigationPipeline pipeline;
    EXPECT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(sequence.front().truth, 0);
    std::vector<NavSolution> out(sequence.size());
    for (int i = 0; i < static_cast<int>(sequence.size()); ++i) {
      const Frame f = frameOf(sequence, i);
      EXPECT_EQ(pipeline.process(&f, f.exposure_time_ns, out[static_cast<std::size_t>(i)]), Status::kOk);
      each(pipeline, i);
    }
    return out;
  }
  std::vector<NavSolution> solutionsFromFirstTruth(const std::vector<test::RenderedFrame>& sequence,
                                                   const PipelineParams& p) {
    return solutionsFromFirstTruth(sequence, p, [](const NavigationPipeline&, int) {});
  }
  /// The plate's `sequence` tracked under `p` from its first frame's truth (the given start pose): every
  /// frame stays in near range with a pose within 0.1 m of that frame's truth; `each(pipeline, out, i)`
  /// checks the case on every frame.
  template <typename EachFrame>
  void trackFromFirstTruth(const std::vector<test::RenderedFrame>& sequence, const PipelineParams& p,
                           EachFrame each) {
    NavigationPipeline pipeline;
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(sequence.front().truth, 0);
    for (int i = 0; i < static_cast<int>(sequence.size()); ++i) {
      const Frame f = frameOf(sequence, i);
      NavSolution out;
      ASSERT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
      ASSERT_EQ(out.mode, NavMode::kNearRange) << i;
      EXPECT_LT((out.pose.t_c_m - sequence[static_cast<std::size_t>(i)].truth.t_c_m).norm(), 0.1) << i;
      each(pipeline, out, i);
    }
  }
  /// Ten frames of the plate from its true start at 26 m under `p`: how many were valid; `out` is the last
  /// solution. Every frame stays in near range, and symmetric_twins is set exactly on the valid ones (the
  /// plate's half turn).
  int validOverTenFrames(const PipelineParams& p, NavSolution& out,
                         const Pose& start = test::plateAt(26.0, 0.1, 1.0, -1.0)) {
    NavigationPipeline pipeline;
    EXPECT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(start, 0);
    int valid = 0;
    for (int i = 0; i < 10; ++i) {
      const Frame f = frameAt(i);
      EXPECT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
      if (out.pose_valid) ++valid;
      EXPECT_EQ(out.symmetric_twins, out.pose_valid ? 1 : 0) << "flagged only with a pose to flag";
      EXPECT_EQ(pipeline.mode(), NavMode::kNearRange) << "frame " << i;
    }
    return valid;
  }
  /// Tracked at 15 m for 3 frames, then hidden for 10 frames (an eclipse: background and noise only) while
  /// the plate comes 3 m closer and turns 20 deg; visible again from frame kHiddenUntil on (30 frames).
  static constexpr int kHiddenUntil = 13;
  /// Three frames of the plate at `before`, ten frames with nothing drawn (an eclipse), then the plate at
  /// `reappears` until frame 30.
  std::vector<test::RenderedFrame> hiddenApproach(const Pose& reappears = test::plateAt(12.0, 0.3, 25.0,
                                                                                        -15.0),
                                                  const Pose& before = test::plateAt(15.0, 0.3, 1.0, -1.0)) {
    std::vector<test::RenderedFrame> seq;
    synthetic::Renderer empty;
    EXPECT_TRUE(empty.init(test::vgaCamera(), model, synthetic::RenderOptions{}).ok);
    for (int i = 0; i < 30; ++i)
      pushFrame(seq, empty, i < kHiddenUntil ? before : reappears, i >= 3 && i < kHiddenUntil, 400U + i);
    return seq;
  }
  /// `count` frames of the plate at `pose_at(i)`, hidden (background and noise only) on frames
  /// `hidden_from` to `visible_from` - 1; frame i's noise seeded with `seed` + i.
  template <typename PoseAt>
  std::vector<test::RenderedFrame> eclipsedSequence(int count, int hidden_from, int visible_from,
                                                    std::uint64_t seed, PoseAt pose_at) {
    std::vector<test::RenderedFrame> seq;
    synthetic::Renderer empty;
    EXPECT_TRUE(empty.init(test::vgaCamera(), model, synthetic::RenderOptions{}).ok);
    for (int i = 0; i < count; ++i)
      pushFrame(seq, empty, pose_at(i), i >= hidden_from && i < visible_from,
                seed + static_cast<std::uint64_t>(i));
    return seq;
  }
  /// `truth`'s frame onto `seq`; `hidden`: drawn by `empty` behind the camera (background and noise only),
  /// the truth still recorded.
  void pushFrame(std::vector<test::RenderedFrame>& seq, synthetic::Renderer& empty, const Pose& truth,
                 bool hidden, std::uint64_t seed) {
    if (!hidden) {
      seq.push_back(test::renderFrame(renderer, truth, seed));
      return;
    }
    Pose behind = truth;
    behind.t_c_m.z() = -10.0;  // not drawn
    seq.push_back(test::renderFrame(empty, behind, seed));
    seq.back().truth = truth;
  }
  /// One run over hiddenApproach() from the true start pose: each frame's solution, whether the near-range
  /// tracker held, and the first visible frame on which a reacquisition found the target (-1: never).
  struct HiddenRun {
    std::vector<NavSolution> out;
    std::vector<bool> tracked;
    int found_at = -1;
    bool found_by_acquisition = false;
    bool far_cued = false;          ///< an acquisition attempt was cued by far range (reacquire_far_cue)
    bool outline_cued = false;      ///< or by the outline cue (reacquire_acquisition_outline_cue)
    std::uint64_t allocations = 0;  ///< over the frames, after init
  };
  void runHidden(const std::vector<test::RenderedFrame>& seq, const PipelineParams& p,
                 NavigationPipeline& pipeline, HiddenRun& run) {
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(seq[0].truth, 0);
    run.out.reserve(seq.size());
    run.tracked.reserve(seq.size());
    const std::uint64_t before = test::allocationCount();
    for (int i = 0; i < static_cast<int>(seq.size()); ++i) {
      const Frame f = frameOf(seq, i);
      NavSolution out;
      ASSERT_EQ(pipeline.process(&f, f.exposure_time_ns, out), Status::kOk);
      run.out.push_back(out);
      run.tracked.push_back(pipeline.lastNearRange().status != TrackStatus::kLost);
      run.far_cued = run.far_cued || pipeline.lastReacquisition().far_cue;
      run.outline_cued = run.outline_cued || pipeline.lastReacquisition().outline_cue;
      if (run.found_at < 0 && i >= kHiddenUntil && pipeline.lastReacquisition().found) {
        run.found_at = i;
        run.found_by_acquisition = pipeline.lastReacquisition().by_acquisition;
      }
    }
    run.allocations = test::allocationCount() - before;
  }
  /// runHidden, then what the doubt tests need of it: no allocation after init, and a find after the gap.
  void runHiddenToAFind(const std::vector<test::RenderedFrame>& seq, const PipelineParams& p,
                        NavigationPipeline& pipeline, HiddenRun& run) {
    ASSERT_NO_FATAL_FAILURE(runHidden(seq, p, pipeline, run));
    EXPECT_EQ(run.allocations, 0U) << "malloc counted: " << test::countsMalloc();
    ASSERT_GE(run.found_at, kHiddenUntil) << "never found again";
  }

  /// A run whose acquisition found the plate again within 8 frames of its reappearance, valid from then on
  /// but for a frame.
  static void expectFoundByAcquisitionSoon(const HiddenRun& run, int valid_after, int within_frames = 8) {
    ASSERT_GE(run.found_at, kHiddenUntil) << "never found again";
    EXPECT_TRUE(run.found_by_acquisition);
    EXPECT_LE(run.found_at, kHiddenUntil + within_frames);
    EXPECT_GE(valid_after, 30 - run.found_at - 1);
  }

  /// The plate that reappears 17 deg from the prediction's line of sight and 20 % closer, far range off
  /// (its cue would find it), run with one way of looking beyond the prediction's window switched by `set`:
  /// on, the acquisition finds it within `within_frames` of its reappearance and it stays valid; off, never
  /// in the 17 frames after it. Nothing allocated either way.
  template <typename Set>
  void expectFoundOnlyWith(Set set, int within_frames, HiddenRun& with) {
    const std::vector<test::RenderedFrame> seq =
        hiddenApproach(test::plateAt(12.0, -2.4, 25.0, -15.0), test::plateAt(15.0, 1.5, 1.0, -1.0));
    for (const bool on : {true, false}) {
      PipelineParams p = params;
      p.navigation.reacquire_far_cue = false;
      p.navigation.reacquire_acquisition_tiles = false;
      p.navigation.reacquire_acquisition_outline_cue = false;
      set(p, on);
      NavigationPipeline pipeline;
      HiddenRun run;
      runHidden(seq, p, pipeline, run);
      EXPECT_EQ(run.allocations, 0U) << "switched " << (on ? "on" : "off");
      EXPECT_FALSE(run.far_cued);
      const int valid_after = checkValidAfterHidden(seq, pipeline, run);
      if (on) {
        expectFoundByAcquisitionSoon(run, valid_after, within_frames);
        with = run;
      } else {
        EXPECT_LT(run.found_at, 0) << "found with it off: the test tests nothing";
        EXPECT_EQ(valid_after, 0);
        EXPECT_FALSE(run.outline_cued);
      }
    }
  }

  /// Every valid pose once the target reappears is within 2 % of 12 m and 2 deg of the truth (modulo the
  /// plate's half-turn symmetry about its normal); returns how many there were.
  int checkValidAfterHidden(const std::vector<test::RenderedFrame>& seq, const NavigationPipeline& pipeline,
                            const HiddenRun& run) {
    int valid_after = 0;
    for (int i = kHiddenUntil; i < 30; ++i) {
      const NavSolution& out = run.out[static_cast<std::size_t>(i)];
      if (!out.pose_valid) continue;
      ++valid_after;
      const Pose& truth = seq[static_cast<std::size_t>(i)].truth;
      EXPECT_LT((out.pose.t_c_m - truth.t_c_m).norm(), 0.02 * 12.0) << "frame " << i;
      EXPECT_LT(
          pipeline.reacquisition().symmetries().attitudeDistanceRad(out.pose.R_c_m, truth.R_c_m) * kDegPerRad,
          2.0)
          << "frame " << i;
    }
    return valid_after;
  }
  /// Ten frames of the steady approach from the start pose, then frame 10 with the plate 0.15 m (6 px)
  /// sideways of where the motion says: within the tracker's reach, far outside the filter's prediction.
  /// `steady` is the last steady frame's solution, `out` the jumped frame's.
  void runToJump(NavigationPipeline& pipeline, const PipelineParams& p, NavSolution& steady,
                 NavSolution& out) {
    ASSERT_TRUE(pipeline.init(test::vgaCamera(), model, p).ok);
    pipeline.startNearRange(test::plateAt(26.0, 0.1, 1.0, -1.0), 0);
    for (int i = 0; i < 10; ++i) {
      const Frame f = frameAt(i);
      pipeline.process(&f, f.exposure_time_ns, steady);
    }
    Frame f = frameAt(10);
    const test::RenderedFrame jumped =
        test::renderFrame(renderer, test::plateAt(25.0, 0.25, 1.0, -1.0), 777U);
    f.image = jumped.image();
    pipeline.process(&f, f.exposure_time_ns, out);
  }
  /// runToJump where the steady frames were valid and the filter disputed the jump (the case the disputed-
  /// pose tests need; call it under ASSERT_NO_FATAL_FAILURE).
  void runToDisputedJump(NavigationPipeline& pipeline, const PipelineParams& p, NavSolution& out) {
    NavSolution steady;
    runToJump(pipeline, p, steady, out);
    ASSERT_TRUE(steady.pose_valid) << "the steady frames must be valid";
    ASSERT_NE(out.fault_bits & kFaultInnovation, 0U) << "the filter must dispute the jump";
  }
  static constexpr int kFrames = 60;
  PolygonModel model;
  synthetic::Renderer renderer;
  std::vector<test::RenderedFrame> frames;
  PipelineParams params;
};

}  // namespace visnav::nav::test_support
