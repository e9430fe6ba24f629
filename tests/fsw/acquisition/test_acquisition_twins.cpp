// Acquisition and a near twin the image cannot resolve (near_twin_min_separation_px): refused without a
// track to tell them apart; with one lost a few frames ago (setLookReference, the close-range
// reacquisition), the candidate continuous with it is taken, whichever of the two was found, and flagged.
// REQUIREMENT (issue 10): never deliver a wrong pose; for a model with near symmetries keep the hypothesis
// continuous with the track and flag the ambiguity.
#include <gtest/gtest.h>

#include "../../support/alloc_counter.hpp"
#include "acquisition_fixture.hpp"

namespace visnav {
namespace {

using acq::AcquisitionFailure;
using acq::AcquisitionState;

class NearTwinAcquisitionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Campaign box/187's near cube: its closest near twin moves the vertices by 15.6 mm, 1.6 px at 10 m
    // with f = 1000 px (under the 2 px an image resolves).
    scene = test::makeScene(test::Target::kBox);
    scene.model = makeBox(0.615, 0.585, 0.574);
    symmetries.find(scene.model);
    symmetries.findNear(scene.model, acq::AcquisitionParams{}.near_twin_max_rel);
    ASSERT_GT(symmetries.nearCount(), 0);
    truth.R_c_m = test::tiltedAttitude(35.0, 30.0, 20.0);
    truth.t_c_m = Vec3(0.2, -0.1, 10.0);
    ASSERT_TRUE(renderer.init(test::vgaCamera(), scene.model, scene.render).ok);
    frames = test::renderStatic(renderer, truth, 3, 41);
    ASSERT_TRUE(
        acquisition.init(test::vgaCamera(), scene.model, acq::AcquisitionParams{}, NearRangeParams{}).ok);
  }
  /// The near twin of the truth that moves the vertices least.
  Pose closestTwin() const {
    int closest = 0;
    for (int i = 1; i < symmetries.nearCount(); ++i)
      if (symmetries.nearSeparationM(i) < symmetries.nearSeparationM(closest)) closest = i;
    return symmetries.nearTwin(truth, closest);
  }
  /// One acquisition from a good cue, with the look reference set after start() when one is given.
  acq::AcquisitionResult run(const Pose* reference) {
    acquisition.start(test::perturbedCue(truth, 0.5, 30.0, 0.05));
    acq::AcquisitionResult r;
    for (int i = 0; i < 60; ++i) {
      if (reference != nullptr) acquisition.setLookReference(*reference, 20.0 * kRadPerDeg);
      acquisition.step(frames[static_cast<std::size_t>(i) % frames.size()].image(),
                       static_cast<std::uint64_t>(i), r);
      if (r.state == AcquisitionState::kSucceeded || r.state == AcquisitionState::kFailed) break;
    }
    return r;
  }
  test::Scene scene;
  ModelSymmetries symmetries;
  Pose truth;
  synthetic::Renderer renderer;
  std::vector<test::RenderedFrame> frames;
  acq::Acquisition acquisition;
};

TEST_F(NearTwinAcquisitionTest, WithoutATrackAnUnresolvableTwinIsAmbiguous) {
  const acq::AcquisitionResult r = run(nullptr);
  EXPECT_EQ(r.state, AcquisitionState::kFailed);
  EXPECT_EQ(r.failure, AcquisitionFailure::kAmbiguous) << acq::toString(r.failure);
  EXPECT_FALSE(r.twin_resolved_by_continuity);
}

TEST_F(NearTwinAcquisitionTest, ATrackLostAFewFramesAgoChoosesTheContinuousTwinAndSaysSo) {
  // The last valid pose 8 deg off the truth (the target turned while lost): the truth's look is within the
  // 20 deg tolerance, its near twin's is not.
  Pose reference = truth;
  reference.R_c_m = expSo3(Vec3(0.0, 0.0, 8.0 * kRadPerDeg)) * truth.R_c_m;
  const acq::AcquisitionResult r = run(&reference);
  ASSERT_EQ(r.state, AcquisitionState::kSucceeded) << acq::toString(r.failure);
  EXPECT_TRUE(r.twin_resolved_by_continuity);
  EXPECT_LT(test::attitudeErrorDeg(scene, truth, r.pose), 3.0);
  EXPECT_LT((r.pose.t_c_m - truth.t_c_m).norm(), 0.05 * truth.t_c_m.norm());
}

TEST_F(NearTwinAcquisitionTest, ATrackOnTheTwinKeepsTheTwin) {
  // Continuity decides, not the image: a reference on the twin's side yields the twin (the image cannot
  // tell, so this is what the track would have been; the pipeline's own look check then judges it).
  const Pose twin = closestTwin();
  const acq::AcquisitionResult r = run(&twin);
  ASSERT_EQ(r.state, AcquisitionState::kSucceeded) << acq::toString(r.failure);
  EXPECT_TRUE(r.twin_resolved_by_continuity);
  EXPECT_LT(symmetries.lookDistanceRad(twin, r.pose) * kDegPerRad, 5.0);
}

TEST_F(NearTwinAcquisitionTest, AReferenceThatKeepsNeitherChangesNothing) {
  // A reference 60 deg away from both: no continuity, the twin blocks as without a track.
  Pose reference = truth;
  reference.R_c_m = expSo3(Vec3(60.0 * kRadPerDeg, 0.0, 0.0)) * truth.R_c_m;
  const acq::AcquisitionResult r = run(&reference);
  EXPECT_EQ(r.state, AcquisitionState::kFailed);
  EXPECT_EQ(r.failure, AcquisitionFailure::kAmbiguous) << acq::toString(r.failure);
}

// A flat-lit box (no shading: every face the same brightness) shows its outline only, and its depth-reversed
// twin (ModelSymmetries::mirrorTwin) the same outline to within the agreement's tolerance: campaign box/120
// was confirmed 88-90 deg off at 49 m with the truth 0.02-0.12 deg from the confirmed pose's twin. With the
// twin challenged ([acquisition] mirror_twin_checks) such a candidate is not confirmed while the twin keeps
// up; close in, perspective tells the two apart. Measured on 8 views of this box at each of 30, 45, 65 and 8
// m (fsw/acquisition/README.md): without the check 18 of 32 confirmed right, 1 as the twin, 3 otherwise
// wrong; with it 11 right, none as the twin, 1 otherwise wrong. Two of those views here (a box acquisition
// costs ~25 s under the sanitizers).
class MirrorTwinAcquisitionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene = test::makeScene(test::Target::kBox);
    scene.model = makeBox(0.684, 0.846, 0.406);  // box/120's
    scene.render.shading.enabled = false;
    mirrors.findMirrors(scene.model);
    ASSERT_EQ(mirrors.mirrorCount(), 1);
    ASSERT_TRUE(renderer.init(test::vgaCamera(), scene.model, scene.render).ok);
  }
  /// One acquisition of a static `truth`, the checks on or off; with `allocations`, what it allocated after
  /// init (the twin's refits on the verify and confirmation frames included).
  test::AcquisitionRun acquire(bool mirror_twin_checks, const Pose& truth, std::uint64_t seed,
                               std::uint64_t* allocations = nullptr) {
    acq::AcquisitionParams params;
    params.mirror_twin_checks = mirror_twin_checks;
    acq::Acquisition acquisition;
    EXPECT_TRUE(acquisition.init(test::vgaCamera(), scene.model, params, NearRangeParams{}).ok);
    const auto frames = test::renderStatic(renderer, truth, 2, seed);
    const auto cue = test::perturbedCue(truth, 0.5, 30.0, 0.1);
    const std::uint64_t before = test::allocationCount();
    const test::AcquisitionRun run = test::runAcquisition(acquisition, scene, frames, cue);
    if (allocations != nullptr) *allocations = test::allocationCount() - before;
    return run;
  }
  /// Attitude error [deg] of `pose` from the truth's depth-reversed twin.
  double fromTwinDeg(const Pose& truth, const Pose& pose) const {
    return test::attitudeErrorDeg(scene, mirrors.mirrorTwin(truth, 0), pose);
  }
  test::Scene scene;
  ModelSymmetries mirrors;
  synthetic::Renderer renderer;
};

TEST_F(MirrorTwinAcquisitionTest, FarOutTheTwinBlocksWhatWouldBeConfirmedAsTheTwin) {
  const Pose truth{test::tiltedAttitude(40.0, 15.0, 60.0), Vec3(0.01, -0.013, 1.0) * 65.0};
  const test::AcquisitionRun unchecked = acquire(false, truth, 305);
  ASSERT_TRUE(unchecked.succeeded()) << acq::toString(unchecked.last.failure);
  EXPECT_GT(unchecked.attitude_error_deg, 30.0);
  EXPECT_LT(fromTwinDeg(truth, unchecked.last.pose), 5.0) << "confirmed as the truth's twin";
  std::uint64_t allocations = 1;
  const test::AcquisitionRun checked = acquire(true, truth, 305, &allocations);
  EXPECT_EQ(allocations, 0U) << "malloc counted: " << test::countsMalloc();
  EXPECT_EQ(checked.last.state, acq::AcquisitionState::kFailed);
  EXPECT_EQ(checked.last.failure, acq::AcquisitionFailure::kAmbiguous) << acq::toString(checked.last.failure);
}

TEST_F(MirrorTwinAcquisitionTest, CloseInPerspectiveTellsTheTwinApart) {
  const Pose truth{test::tiltedAttitude(40.0, 45.0, 30.0), Vec3(0.01, -0.013, 1.0) * 8.0};
  const test::AcquisitionRun checked = acquire(true, truth, 301);
  ASSERT_TRUE(checked.succeeded()) << acq::toString(checked.last.failure);
  EXPECT_LT(checked.attitude_error_deg, 5.0);
  EXPECT_LT(checked.position_error_m, 0.05 * 8.0);
}

}  // namespace
}  // namespace visnav
