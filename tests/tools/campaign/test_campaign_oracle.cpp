// visnav-campaign --oracle: a tracker started at the truth judges every visible frame without a valid pose
// (FrameOutcome::oracle) and says which image-evidence test a fit it cannot use fails
// (FrameOutcome::oracle_evidence), and only those frames; asked for nothing, it judges nothing.
#include <gtest/gtest.h>

#include <string>

#include "visnav/campaign/runner.hpp"
#include "visnav/campaign/scene.hpp"
#include "visnav/navigation/fdir_monitor.hpp"

namespace visnav::campaign {
namespace {

TEST(CampaignOracle, JudgesEveryVisibleFrameWithoutAValidPoseAndSeesTheReappearedBox) {
  Scene scene;
  ASSERT_TRUE(makeCase("eclipse_box", ModelLibrary{}, 0, scene).ok);  // a box: no model file
  const nav::PipelineParams params;
  const SceneResult with = runScene(scene, params, false, Thresholds{}, false, true);
  ASSERT_TRUE(with.error.ok) << with.error.message;
  int judged = 0, supported_after_eclipse = 0;
  const int eclipse_end = scene.events.eclipse_first + scene.events.eclipse_frames;
  for (const FrameOutcome& f : with.frames) {
    const bool due = f.visible && !f.pose_valid;
    EXPECT_EQ(f.oracle >= 0, due) << "frame " << f.frame;
    EXPECT_LE(f.oracle, 2);
    // Why: the first image-evidence test its fit fails, none exactly where the verdict is a fit (1 or 2).
    EXPECT_EQ(f.oracle_evidence >= 0, due) << "frame " << f.frame;
    const bool evidence_good = f.oracle_evidence == static_cast<int>(nav::EvidenceVerdict::kGood);
    EXPECT_EQ(evidence_good, f.oracle >= 1) << "frame " << f.frame;
    judged += f.oracle >= 0 ? 1 : 0;
    // The box is back in full view at 10 m while the pipeline is still finding it again: the truth's fit
    // is right and certain there.
    if (f.oracle == 2 && f.frame >= eclipse_end) ++supported_after_eclipse;
  }
  EXPECT_GT(judged, 0);
  EXPECT_GT(supported_after_eclipse, 0);

  const SceneResult without = runScene(scene, params, false, Thresholds{}, false, false);
  ASSERT_EQ(without.frames.size(), with.frames.size());
  for (std::size_t i = 0; i < without.frames.size(); ++i) {
    EXPECT_EQ(without.frames[i].oracle, -1);
    EXPECT_EQ(without.frames[i].oracle_evidence, -1);
    // The oracle only looks: the pipeline's frames are the same with it.
    EXPECT_EQ(without.frames[i].pose_valid, with.frames[i].pose_valid) << i;
    EXPECT_EQ(without.frames[i].position_error_m, with.frames[i].position_error_m) << i;
  }
}

}  // namespace
}  // namespace visnav::campaign
