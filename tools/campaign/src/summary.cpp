// Statistics over the scenes of a campaign (per family and overall) and the --require-* gates; the outputs
// that print them are in report.cpp.
#include <algorithm>
#include <array>
#include <cstdio>
#include <numeric>

#include "visnav/campaign/report.hpp"
#include "visnav/eval/metrics.hpp"

namespace visnav::campaign {

Distribution distribution(std::vector<double> values) {
  Distribution d;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  d.count = static_cast<int>(values.size());
  d.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  d.median = eval::percentileSorted(values, 0.5);
  d.p95 = eval::percentileSorted(values, 0.95);
  d.max = values.back();
  return d;
}

const char* toString(LossCause cause) {
  switch (cause) {
    case LossCause::kWrong: return "wrong";
    case LossCause::kNotNearRange: return "not_near_range";
    case LossCause::kNoCandidate: return "no_candidate";
    case LossCause::kUncertain: return "uncertain";
    case LossCause::kDoubted: return "doubted";
    case LossCause::kFindDoubted: return "find_doubted";
    case LossCause::kWithheldOther: return "withheld_other";
    case LossCause::kBranch: return "branch";
    case LossCause::kRejected: return "rejected";
  }
  return "?";
}

LossCause lossCause(const FrameOutcome& f) {
  if (f.pose_valid && f.wrong) return LossCause::kWrong;
  if (f.mode != nav::NavMode::kNearRange) return LossCause::kNotNearRange;
  if (!f.has_candidate) return LossCause::kNoCandidate;
  if ((f.withheld & nav::kWithheldUncertain) != 0U) return LossCause::kUncertain;
  if ((f.withheld & nav::kWithheldDoubted) != 0U) return LossCause::kDoubted;
  if ((f.withheld & nav::kWithheldFindDoubted) != 0U) return LossCause::kFindDoubted;
  if (f.withheld == nav::kWithheldBranchUnknown) return LossCause::kBranch;
  if (f.withheld != 0U) return LossCause::kWithheldOther;
  return LossCause::kRejected;
}

GroupSummary summarise(const std::string& name, const std::vector<const SceneRun*>& runs) {
  GroupSummary g;
  g.name = name;
  std::vector<double> tracked_fractions, accurate_fractions, latencies, modes_near, modes_approach,
      acquisition, nis;
  std::array<std::vector<double>, kModeCount> steps;
  int worst_wrong = 0;
  int worst_latency = -1;
  bool worst_never = false;
  int worst_modes = -1;
  for (const SceneRun* run : runs) {
    const Scene& s = run->scene;
    const SceneResult& r = run->result;
    ++g.scenes;
    (s.approach ? g.approach_scenes : g.near_scenes) += 1;
    g.frames += static_cast<int>(r.frames.size());
    g.visible += r.visible;
    g.expected += r.expected;
    g.tracked += r.tracked;
    g.accurate += r.accurate;
    g.wrong += r.wrong;
    if (r.wrong > 0) ++g.wrong_scenes;
    if (r.wrong > worst_wrong) {
      worst_wrong = r.wrong;
      g.worst_wrong = run;
    }
    if (r.tracked_fraction >= 0.0) {
      tracked_fractions.push_back(r.tracked_fraction);
      accurate_fractions.push_back(r.accurate_fraction);
      if (g.worst_tracked == nullptr || r.tracked_fraction < g.tracked_fraction_worst) {
        g.tracked_fraction_worst = r.tracked_fraction;
        g.worst_tracked = run;
      }
    }
    for (const RecoveryEvent& e : r.events) {
      ++g.recovery_events;
      GroupSummary::KindRecovery& k = g.recovery_by_kind[static_cast<std::size_t>(e.kind)];
      ++k.events;
      k.never += e.latency < 0 ? 1 : 0;
      k.within_target += e.latency >= 0 && e.latency <= kRecoveryTargetFrames ? 1 : 0;
      if (e.latency < 0) {
        ++g.recovery_never;
        if (!worst_never) {
          worst_never = true;
          g.worst_recovery = run;
        }
      } else {
        latencies.push_back(e.latency);
        if (!worst_never && e.latency > worst_latency) {
          worst_latency = e.latency;
          g.worst_recovery = run;
        }
      }
    }
    (s.approach ? modes_approach : modes_near).push_back(r.mode_changes);
    if (r.mode_changes > worst_modes) {
      worst_modes = r.mode_changes;
      g.worst_modes = run;
    }
    if (r.acquisition_latency >= 0) acquisition.push_back(r.acquisition_latency);
    if (r.acquisition_latency == -1) ++g.acquisition_never;
    g.far_fixes += r.far_fixes;
    g.far_off_target += r.far_off_target;
    for (const FrameOutcome& f : r.frames) {
      if (f.has_nis) {
        nis.push_back(f.nis);
        if (f.nis > kNisGate) ++g.nis_above_gate;
      }
      steps[static_cast<std::size_t>(f.mode)].push_back(f.process_us);
      if (f.expected && !f.tracked) ++g.untracked_by_cause[static_cast<std::size_t>(lossCause(f))];
    }
  }
  g.tracked_fraction = distribution(tracked_fractions);
  g.accurate_fraction = distribution(accurate_fractions);
  g.recovery = distribution(latencies);
  g.mode_changes_near = distribution(modes_near);
  g.mode_changes_approach = distribution(modes_approach);
  g.acquisition_latency = distribution(acquisition);
  g.nis = distribution(nis);
  for (std::size_t m = 0; m < steps.size(); ++m) g.step_us[m] = distribution(steps[m]);
  return g;
}

std::vector<GroupSummary> summariseAll(const std::vector<SceneRun>& runs) {
  std::vector<GroupSummary> groups;
  std::vector<const SceneRun*> all;
  all.reserve(runs.size());
  for (const SceneRun& r : runs) all.push_back(&r);
  groups.push_back(summarise("overall", all));
  for (int f = 0; f < kFamilyCount; ++f) {
    std::vector<const SceneRun*> some;
    for (const SceneRun& r : runs)
      if (static_cast<int>(r.scene.family) == f) some.push_back(&r);
    if (!some.empty()) groups.push_back(summarise(toString(static_cast<Family>(f)), some));
  }
  return groups;
}

std::vector<GateResult> checkGates(const std::vector<SceneRun>& runs, const Gates& gates) {
  std::vector<GateResult> out;
  std::vector<const SceneRun*> all;
  all.reserve(runs.size());
  for (const SceneRun& r : runs) all.push_back(&r);
  const GroupSummary g = summarise("overall", all);
  char buf[256];
  if (gates.tracked_fraction) {
    GateResult r;
    r.name = "tracked fraction";
    r.passed = g.worst_tracked == nullptr || g.tracked_fraction_worst >= gates.min_tracked_fraction;
    r.worst = g.worst_tracked;
    int below = 0;
    for (const SceneRun& run : runs)
      below += run.result.tracked_fraction >= 0.0 && run.result.tracked_fraction < gates.min_tracked_fraction;
    std::snprintf(buf, sizeof(buf), "worst scene %.4f, required >= %.4f; %d of %d scenes below",
                  g.tracked_fraction_worst, gates.min_tracked_fraction, below, g.tracked_fraction.count);
    r.detail = buf;
    out.push_back(r);
  }
  if (gates.no_confident_wrong) {
    GateResult r;
    r.name = "no confidently wrong pose";
    r.passed = g.wrong == 0;
    r.worst = g.worst_wrong;
    std::snprintf(buf, sizeof(buf), "%d confidently wrong frames in %d scenes", g.wrong, g.wrong_scenes);
    r.detail = buf;
    out.push_back(r);
  }
  if (gates.recovery) {
    GateResult r;
    r.name = "recovery frames";
    int over = 0;
    for (const SceneRun& run : runs)
      for (const RecoveryEvent& e : run.result.events) over += e.latency > gates.max_recovery_frames ? 1 : 0;
    r.passed = g.recovery_never == 0 && over == 0;
    r.worst = g.worst_recovery;
    std::snprintf(buf, sizeof(buf), "%d events: %d never recovered, %d took more than %d frames (max %.0f)",
                  g.recovery_events, g.recovery_never, over, gates.max_recovery_frames, g.recovery.max);
    r.detail = buf;
    out.push_back(r);
  }
  if (gates.mode_changes) {
    GateResult r;
    r.name = "mode changes";
    const int worst = g.worst_modes == nullptr ? 0 : g.worst_modes->result.mode_changes;
    r.passed = worst <= gates.max_mode_changes;
    r.worst = g.worst_modes;
    std::snprintf(buf, sizeof(buf), "worst scene %d, allowed <= %d", worst, gates.max_mode_changes);
    r.detail = buf;
    out.push_back(r);
  }
  return out;
}

}  // namespace visnav::campaign
