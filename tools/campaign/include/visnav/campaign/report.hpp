// Statistics over the scenes of a campaign (per family and overall), the --require-* gates, and the
// outputs: the stdout table, DIR/campaign.json, DIR/scenes.csv and DIR/campaign.png. Timing numbers live
// in their own fields (JSON "timing" object, CSV time_* columns) so everything else is bit-identical
// between runs with the same arguments.
#pragma once

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include "visnav/campaign/options.hpp"
#include "visnav/campaign/runner.hpp"
#include "visnav/campaign/scene.hpp"
#include "visnav/eval/canvas.hpp"

namespace visnav::campaign {

struct SceneRun {
  Scene scene;
  SceneResult result;
};

struct Distribution {
  int count = 0;
  double mean = 0.0;
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};
Distribution distribution(std::vector<double> values);

/// Chi-square, 6 dof, 99.9 %: the filter's default pose gate.
constexpr double kNisGate = 22.46;
constexpr int kModeCount = 4;  ///< nav::NavMode values

/// The recovery target: tracked again within this many frames of the event (the per-kind counts).
constexpr int kRecoveryTargetFrames = 5;

/// Why an expected frame has no tracked pose: the first that applies, in this order (lossCause). The
/// withheld causes are NavSolution::withheld bits of a pose the pipeline computed and did not deliver.
enum class LossCause : int {
  kWrong = 0,      ///< valid, but confidently wrong
  kNotNearRange,   ///< far range, acquisition or standby: no 6-DOF pose of near range's
  kNoCandidate,    ///< near range without a pose: the tracker lost it, or the search has not found it
  kUncertain,      ///< withheld: its own 1-sigma above the validity limits
  kDoubted,        ///< withheld: doubted, above the doubted limit
  kFindDoubted,    ///< withheld: its track began with a find not yet cleared
  kWithheldOther,  ///< withheld: edge-on, jumped, missing outline lines, awaiting near range
  kBranch,         ///< withheld for the branch alone (branch_confirm_frames)
  kRejected,       ///< computed, not withheld, not valid (the pipeline's own checks refused it)
};
constexpr int kLossCauseCount = 9;
const char* toString(LossCause cause);
/// The cause for a frame that is expected and not tracked.
LossCause lossCause(const FrameOutcome& f);

struct GroupSummary {
  std::string name;  ///< family name or "overall"
  int scenes = 0;
  int near_scenes = 0;
  int approach_scenes = 0;
  int frames = 0;
  int visible = 0;
  int expected = 0;
  int tracked = 0;
  int accurate = 0;
  int wrong = 0;  ///< confidently wrong frames
  int wrong_scenes = 0;
  Distribution tracked_fraction;  ///< over scenes with expected frames
  Distribution accurate_fraction;
  double tracked_fraction_worst = -1.0;
  const SceneRun* worst_tracked = nullptr;
  const SceneRun* worst_wrong = nullptr;  ///< most confidently wrong frames
  int recovery_events = 0;
  int recovery_never = 0;
  Distribution recovery;  ///< latencies of the events that recovered [frames]
  /// Per EventKind: events, those tracked again within kRecoveryTargetFrames, and those never.
  struct KindRecovery {
    int events = 0;
    int within_target = 0;
    int never = 0;
  };
  std::array<KindRecovery, kEventKindCount> recovery_by_kind{};
  const SceneRun* worst_recovery = nullptr;  ///< a "never", else the largest latency
  Distribution mode_changes_near;
  Distribution mode_changes_approach;
  const SceneRun* worst_modes = nullptr;
  Distribution acquisition_latency;  ///< approach scenes that acquired
  int acquisition_never = 0;
  Distribution nis;
  int nis_above_gate = 0;
  int far_fixes = 0;                               ///< SceneResult::far_fixes, summed
  int far_off_target = 0;                          ///< SceneResult::far_off_target, summed
  std::array<Distribution, kModeCount> step_us{};  ///< timing: per mode the frame was processed in
  /// Expected frames without a tracked pose, per LossCause (they add up to expected - tracked).
  std::array<int, kLossCauseCount> untracked_by_cause{};
};

GroupSummary summarise(const std::string& name, const std::vector<const SceneRun*>& runs);
/// "overall" first, then one per family present, in family order.
std::vector<GroupSummary> summariseAll(const std::vector<SceneRun>& runs);

struct GateResult {
  std::string name;
  bool passed = true;
  std::string detail;
  const SceneRun* worst = nullptr;
};
std::vector<GateResult> checkGates(const std::vector<SceneRun>& runs, const Gates& gates);

/// One line per scene: "box/17 near 150 fr: tracked 0.973 (146/150) accurate 0.80 wrong 0 recovery max 3
/// ...".
std::string sceneLine(const SceneRun& run);
/// The compact stdout table (groups, then the worst confidently wrong frames).
std::string summaryTable(const std::vector<GroupSummary>& groups, const std::vector<SceneRun>& runs,
                         bool timing);

/// --oracle: per family, the expected frames without a valid pose split by what a tracker started at the
/// truth made of them (FrameOutcome::oracle): a right and certain fit (the search or the gates lost the
/// frame), a wrong or uncertain fit, no fit (the image, as this tracker measures it).
std::string oracleTable(const std::vector<SceneRun>& runs);
/// Per group, the expected frames without a tracked pose split by LossCause
/// (GroupSummary::untracked_by_cause).
std::string lossTable(const std::vector<GroupSummary>& groups);

void writeJson(std::ostream& out, const CampaignOptions& options, const std::vector<SceneRun>& runs,
               const std::vector<GroupSummary>& groups, const std::vector<GateResult>& gates);
void writeCsv(std::ostream& out, const std::vector<SceneRun>& runs);
/// --frames: one row per frame of every scene (verdicts, errors, mode; time_process_us last).
void writeFramesCsv(std::ostream& out, const std::vector<SceneRun>& runs);
eval::Canvas renderCampaignPlot(const std::vector<SceneRun>& runs, const std::vector<GroupSummary>& groups,
                                const Gates& gates);

}  // namespace visnav::campaign
