#include "visnav/campaign/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "visnav/eval/report.hpp"
#include "visnav/navigation/fdir_monitor.hpp"

namespace visnav::campaign {
namespace {

std::string num(double v, const char* format = "%.6g") {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof(buf), format, v + 0.0);  // + 0.0: no "-0"
  return buf;
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string seedText(std::uint64_t seed) { return std::to_string(static_cast<unsigned long long>(seed)); }

const char* kindText(const Scene& s) { return s.approach ? "approach" : "near"; }

std::string fraction(double f) { return f < 0.0 ? std::string("-") : num(f, "%.3f"); }

std::string distributionJson(const Distribution& d) {
  return "{\"count\": " + std::to_string(d.count) + ", \"mean\": " + num(d.mean) +
         ", \"median\": " + num(d.median) + ", \"p95\": " + num(d.p95) + ", \"max\": " + num(d.max) + "}";
}

/// "slew": {"events": n, "within_target": n, "never": n}, ... for GroupSummary::recovery_by_kind.
std::string recoveryByKindJson(const GroupSummary& g) {
  std::string out;
  for (int k = 0; k < kEventKindCount; ++k) {
    const GroupSummary::KindRecovery& r = g.recovery_by_kind[static_cast<std::size_t>(k)];
    out += std::string(k == 0 ? "" : ", ") + "\"" + toString(static_cast<EventKind>(k)) +
           "\": {\"events\": " + std::to_string(r.events) +
           ", \"within_target\": " + std::to_string(r.within_target) +
           ", \"never\": " + std::to_string(r.never) + "}";
  }
  return out;
}

std::string sceneRef(const SceneRun* r) {
  return r == nullptr ? std::string("null") : eval::jsonString(r->scene.name);
}

}  // namespace

std::string sceneLine(const SceneRun& run) {
  const Scene& s = run.scene;
  const SceneResult& r = run.result;
  if (!r.error.ok) return s.name + ": NOT RUN: " + r.error.message;
  char buf[512];
  std::string recovery = "none";
  if (!r.events.empty()) {
    recovery = std::to_string(r.events.size()) + " events, max " +
               (r.recovery_max >= 0 ? std::to_string(r.recovery_max) : std::string("-")) + ", never " +
               std::to_string(r.recovery_never);
  }
  std::snprintf(buf, sizeof(buf),
                "%s (%s%s, %d frames): tracked %s (%d/%d expected), accurate %s, confidently wrong %d, "
                "recovery %s, mode changes %d%s",
                s.name.c_str(), s.is_case ? "case, " : "", kindText(s), static_cast<int>(r.frames.size()),
                fraction(r.tracked_fraction).c_str(), r.tracked, r.expected,
                fraction(r.accurate_fraction).c_str(), r.wrong, recovery.c_str(), r.mode_changes,
                r.acquisition_latency >= 0
                    ? (", acquired after " + std::to_string(r.acquisition_latency) + " frames").c_str()
                : r.acquisition_latency == -1 ? ", never acquired"
                                              : "");
  return buf;
}

std::string summaryTable(const std::vector<GroupSummary>& groups, const std::vector<SceneRun>& runs,
                         bool timing) {
  std::ostringstream o;
  char buf[512];
  // Columns: see tools/campaign/README.md "Outputs".
  const char* row = "%-8s %6s %6s %6s %6s  %-28s %6s %-9s %-15s %-11s %-15s %s\n";
  std::snprintf(buf, sizeof(buf), row, "group", "scenes", "frames", "visibl", "expect",
                "tracked mean, worst scene", "accur", "wrong(sc)", "recov md/95/max", "recov never",
                "modes near|appr", "nis mean/95/>gate");
  o << buf;
  auto whole = [](double v) { return num(v, "%.0f"); };
  for (const GroupSummary& g : groups) {
    std::string tracked = "-";
    if (g.worst_tracked != nullptr)
      tracked = num(g.tracked_fraction.mean, "%.3f") + ", " + fraction(g.tracked_fraction_worst) + " " +
                g.worst_tracked->scene.name;
    const std::string wrong = std::to_string(g.wrong) + " (" + std::to_string(g.wrong_scenes) + ")";
    const std::string rec = g.recovery.count == 0 ? std::string("-")
                                                  : whole(g.recovery.median) + "/" + whole(g.recovery.p95) +
                                                        "/" + whole(g.recovery.max);
    const std::string never = std::to_string(g.recovery_never) + " of " + std::to_string(g.recovery_events);
    const Distribution& mn = g.mode_changes_near;
    const Distribution& ma = g.mode_changes_approach;
    const std::string modes = (mn.count > 0 ? whole(mn.median) + "/" + whole(mn.max) : std::string("-")) +
                              " | " +
                              (ma.count > 0 ? whole(ma.median) + "/" + whole(ma.max) : std::string("-"));
    const std::string nis = g.nis.count == 0 ? std::string("-")
                                             : num(g.nis.mean, "%.1f") + "/" + num(g.nis.p95, "%.1f") + "/" +
                                                   num(100.0 * g.nis_above_gate / g.nis.count, "%.1f") + "%";
    const std::string accurate = g.accurate_fraction.count > 0 ? num(g.accurate_fraction.mean, "%.3f") : "-";
    std::snprintf(buf, sizeof(buf), row, g.name.c_str(), std::to_string(g.scenes).c_str(),
                  std::to_string(g.frames).c_str(), std::to_string(g.visible).c_str(),
                  std::to_string(g.expected).c_str(), tracked.c_str(), accurate.c_str(), wrong.c_str(),
                  rec.c_str(), never.c_str(), modes.c_str(), nis.c_str());
    o << buf;
  }
  const GroupSummary& all = groups.front();
  if (all.approach_scenes > 0) {
    const Distribution& acq = all.acquisition_latency;
    std::snprintf(buf, sizeof(buf), "approach scenes: %d; acquired in %d", all.approach_scenes, acq.count);
    o << buf;
    if (acq.count > 0) {
      std::snprintf(buf, sizeof(buf), " (frames from the first expected frame: median %.0f, max %.0f)",
                    acq.median, acq.max);
      o << buf;
    }
    o << "; never in " << all.acquisition_never << "\n";
  }
  if (all.recovery_events > 0) {
    o << "recovery events tracked again within " << kRecoveryTargetFrames << " frames / events (never):";
    for (int k = 0; k < kEventKindCount; ++k) {
      const GroupSummary::KindRecovery& r = all.recovery_by_kind[static_cast<std::size_t>(k)];
      std::snprintf(buf, sizeof(buf), "%s %s %d/%d (%d)", k == 0 ? "" : ";",
                    toString(static_cast<EventKind>(k)), r.within_target, r.events, r.never);
      o << buf;
    }
    o << "\n";
  }
  if (all.far_fixes > 0) {
    std::snprintf(
        buf, sizeof(buf),
        "far-range fixes with the target in view: %d; off the target (on something else): %d (%.1f %%)\n",
        all.far_fixes, all.far_off_target, 100.0 * all.far_off_target / all.far_fixes);
    o << buf;
  }
  if (timing) {
    o << "step time [us] median/p95 per mode:";
    for (int m = 0; m < kModeCount; ++m) {
      const Distribution& d = all.step_us[static_cast<std::size_t>(m)];
      if (d.count == 0) continue;
      std::snprintf(buf, sizeof(buf), "  %s %.0f/%.0f (%d)", nav::toString(static_cast<nav::NavMode>(m)),
                    d.median, d.p95, d.count);
      o << buf;
    }
    o << "\n";
  }
  // The worst confidently wrong frames (largest attitude error first).
  struct Wrong {
    const SceneRun* run;
    const FrameOutcome* f;
  };
  std::vector<Wrong> wrong;
  for (const SceneRun& r : runs)
    for (const FrameOutcome& f : r.result.frames)
      if (f.wrong) wrong.push_back({&r, &f});
  if (!wrong.empty()) {
    std::stable_sort(wrong.begin(), wrong.end(), [](const Wrong& a, const Wrong& b) {
      return a.f->attitude_error_deg + 100.0 * a.f->position_error_m / a.f->range_m >
             b.f->attitude_error_deg + 100.0 * b.f->position_error_m / b.f->range_m;
    });
    o << "confidently wrong frames: " << wrong.size() << " (worst " << std::min<std::size_t>(wrong.size(), 10)
      << "; all in campaign.json)\n";
    for (std::size_t i = 0; i < wrong.size() && i < 10; ++i) {
      const FrameOutcome& f = *wrong[i].f;
      std::snprintf(
          buf, sizeof(buf),
          "  %-22s frame %4d %-11s range %7.2f m  position %8.3f m (%6.1f %%)  attitude %7.2f deg\n",
          wrong[i].run->scene.name.c_str(), f.frame, nav::toString(f.mode), f.range_m, f.position_error_m,
          100.0 * f.position_error_m / f.range_m, f.attitude_error_deg);
      o << buf;
    }
  }
  return o.str();
}

void writeJson(std::ostream& o, const CampaignOptions& options, const std::vector<SceneRun>& runs,
               const std::vector<GroupSummary>& groups, const std::vector<GateResult>& gates) {
  const Thresholds th;
  o << "{\n  \"tool\": \"visnav-campaign\",\n";
  o << "  \"command\": {\"runs\": " << options.runs << ", \"seed\": " << seedText(options.seed)
    << ", \"families\": [";
  for (std::size_t i = 0; i < options.families.size() && options.cases.empty(); ++i)
    o << (i ? ", " : "") << eval::jsonString(toString(options.families[i]));
  o << "], \"cases\": [";
  for (std::size_t i = 0; i < options.cases.size(); ++i)
    o << (i ? ", " : "") << eval::jsonString(options.cases[i]);
  o << "], \"model\": " << eval::jsonString(options.model_path)
    << ", \"config\": " << eval::jsonString(options.config_path) << ", \"max_frames\": " << options.max_frames
    << "},\n";
  o << "  \"definitions\": {\"wrong_position_rel\": " << num(th.wrong_position_rel)
    << ", \"wrong_attitude_deg\": " << num(th.wrong_attitude_deg)
    << ", \"accurate_position_rel\": " << num(th.accurate_position_rel)
    << ", \"accurate_attitude_deg\": " << num(th.accurate_attitude_deg)
    << ", \"min_visible_px\": " << num(th.min_visible_px)
    << ", \"near_range_max_m\": " << num(th.near_range_max_m) << ", \"nis_gate\": " << num(kNisGate)
    << "},\n";
  bool passed = true;
  o << "  \"gates\": [";
  for (std::size_t i = 0; i < gates.size(); ++i) {
    const GateResult& g = gates[i];
    passed = passed && g.passed;
    o << (i ? ",\n    " : "\n    ") << "{\"name\": " << eval::jsonString(g.name)
      << ", \"passed\": " << (g.passed ? "true" : "false") << ", \"detail\": " << eval::jsonString(g.detail)
      << ", \"worst_scene\": " << sceneRef(g.worst) << ", \"rerun\": "
      << (g.worst == nullptr ? std::string("null") : eval::jsonString(rerunCommand(g.worst->scene, options)))
      << "}";
  }
  o << (gates.empty() ? "],\n" : "\n  ],\n");
  o << "  \"passed\": " << (passed ? "true" : "false") << ",\n";
  o << "  \"summary\": {";
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const GroupSummary& g = groups[i];
    o << (i ? ",\n    " : "\n    ") << eval::jsonString(g.name) << ": {\"scenes\": " << g.scenes
      << ", \"near_scenes\": " << g.near_scenes << ", \"approach_scenes\": " << g.approach_scenes
      << ", \"frames\": " << g.frames << ", \"visible\": " << g.visible << ", \"expected\": " << g.expected
      << ", \"tracked\": " << g.tracked << ", \"accurate\": " << g.accurate
      << ",\n      \"tracked_fraction\": " << distributionJson(g.tracked_fraction)
      << ", \"tracked_fraction_worst\": " << num(g.tracked_fraction_worst)
      << ", \"worst_tracked_scene\": " << sceneRef(g.worst_tracked)
      << ",\n      \"accurate_fraction\": " << distributionJson(g.accurate_fraction)
      << ",\n      \"confidently_wrong_frames\": " << g.wrong
      << ", \"confidently_wrong_scenes\": " << g.wrong_scenes
      << ", \"worst_wrong_scene\": " << sceneRef(g.worst_wrong)
      << ",\n      \"recovery_events\": " << g.recovery_events << ", \"recovery_never\": " << g.recovery_never
      << ", \"recovery_latency\": " << distributionJson(g.recovery)
      << ", \"worst_recovery_scene\": " << sceneRef(g.worst_recovery) << ", \"recovery_by_event\": {"
      << recoveryByKindJson(g) << "}"
      << ",\n      \"mode_changes_near\": " << distributionJson(g.mode_changes_near)
      << ", \"mode_changes_approach\": " << distributionJson(g.mode_changes_approach)
      << ", \"worst_modes_scene\": " << sceneRef(g.worst_modes)
      << ",\n      \"acquisition_latency\": " << distributionJson(g.acquisition_latency)
      << ", \"acquisition_never\": " << g.acquisition_never << ",\n      \"nis\": " << distributionJson(g.nis)
      << ", \"nis_above_gate\": " << g.nis_above_gate << ", \"nis_above_gate_fraction\": "
      << num(g.nis.count > 0 ? static_cast<double>(g.nis_above_gate) / g.nis.count : 0.0)
      << ",\n      \"far_fixes\": " << g.far_fixes << ", \"far_off_target\": " << g.far_off_target
      << ",\n      \"untracked_by_cause\": {";
    for (int c = 0; c < kLossCauseCount; ++c)
      o << (c ? ", " : "") << "\"" << toString(static_cast<LossCause>(c))
        << "\": " << g.untracked_by_cause[static_cast<std::size_t>(c)];
    o << "}}";
  }
  o << "\n  },\n";
  o << "  \"scenes\": [";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Scene& s = runs[i].scene;
    const SceneResult& r = runs[i].result;
    o << (i ? ",\n    " : "\n    ") << "{\"name\": " << eval::jsonString(s.name)
      << ", \"family\": " << eval::jsonString(toString(s.family))
      << ", \"kind\": " << eval::jsonString(kindText(s)) << ", \"case\": " << (s.is_case ? "true" : "false")
      << ", \"seed\": " << seedText(s.seed) << ", \"rerun\": " << eval::jsonString(rerunCommand(s, options))
      << ",\n      \"parameters\": {";
    const std::vector<SceneParam> params = sceneParameters(s);
    for (std::size_t k = 0; k < params.size(); ++k)
      o << (k ? ", " : "") << eval::jsonString(params[k].key) << ": "
        << (params[k].is_number ? params[k].value : eval::jsonString(params[k].value));
    o << "},\n      \"results\": {";
    if (!r.error.ok) {
      o << "\"error\": " << eval::jsonString(r.error.message) << "}}";
      continue;
    }
    o << "\"frames\": " << r.frames.size() << ", \"visible\": " << r.visible
      << ", \"expected\": " << r.expected << ", \"tracked\": " << r.tracked
      << ", \"accurate\": " << r.accurate << ", \"pose_frames\": " << r.pose_frames
      << ", \"confidently_wrong\": " << r.wrong
      << ", \"tracked_fraction\": " << (r.tracked_fraction < 0 ? "null" : num(r.tracked_fraction))
      << ", \"accurate_fraction\": " << (r.accurate_fraction < 0 ? "null" : num(r.accurate_fraction))
      << ", \"recovery_never\": " << r.recovery_never << ", \"recovery_max\": " << r.recovery_max
      << ", \"mode_changes\": " << r.mode_changes << ", \"acquisition_latency\": "
      << (r.acquisition_latency == -2 ? std::string("null") : std::to_string(r.acquisition_latency))
      << ", \"max_position_error_rel\": " << num(r.max_position_error_rel)
      << ", \"max_attitude_error_deg\": " << num(r.max_attitude_error_deg)
      << ", \"nis_count\": " << r.nis_count << ", \"nis_mean\": " << num(r.nis_mean)
      << ", \"far_fixes\": " << r.far_fixes << ", \"far_off_target\": " << r.far_off_target << "},\n";
    o << "      \"events\": [";
    for (std::size_t k = 0; k < r.events.size(); ++k)
      o << (k ? ", " : "") << "{\"kind\": " << eval::jsonString(toString(r.events[k].kind))
        << ", \"frame\": " << r.events[k].frame << ", \"latency\": "
        << (r.events[k].latency < 0 ? std::string("\"never\"") : std::to_string(r.events[k].latency)) << "}";
    o << "],\n      \"transitions\": [";
    for (std::size_t k = 0; k < r.transitions.size(); ++k) {
      const TransitionRecord& t = r.transitions[k];
      o << (k ? ", " : "") << "{\"frame\": " << t.frame
        << ", \"from\": " << eval::jsonString(nav::toString(t.from))
        << ", \"to\": " << eval::jsonString(nav::toString(t.to))
        << ", \"reason\": " << eval::jsonString(t.reason) << "}";
    }
    o << "]}";
  }
  o << (runs.empty() ? "],\n" : "\n  ],\n");
  o << "  \"confidently_wrong\": [";
  bool first = true;
  for (const SceneRun& run : runs) {
    for (const FrameOutcome& f : run.result.frames) {
      if (!f.wrong) continue;
      o << (first ? "\n    " : ",\n    ") << "{\"scene\": " << eval::jsonString(run.scene.name)
        << ", \"family\": " << eval::jsonString(toString(run.scene.family))
        << ", \"seed\": " << seedText(run.scene.seed) << ", \"frame\": " << f.frame
        << ", \"mode\": " << eval::jsonString(nav::toString(f.mode)) << ", \"fault_bits\": " << f.fault_bits
        << ", \"range_m\": " << num(f.range_m) << ", \"position_error_m\": " << num(f.position_error_m)
        << ", \"position_error_pct\": " << num(100.0 * f.position_error_m / f.range_m)
        << ", \"attitude_error_deg\": " << num(f.attitude_error_deg) << "}";
      first = false;
    }
  }
  o << (first ? "],\n" : "\n  ],\n");
  // Everything that depends on the machine's clock or the thread count: strip this object to compare runs.
  o << "  \"timing\": {\"enabled\": " << (options.timing ? "true" : "false") << ", \"jobs\": " << options.jobs
    << ", \"step_us\": {";
  for (std::size_t i = 0; i < groups.size(); ++i) {
    o << (i ? ", " : "") << eval::jsonString(groups[i].name) << ": {";
    for (int m = 0; m < kModeCount; ++m)
      o << (m ? ", " : "") << eval::jsonString(nav::toString(static_cast<nav::NavMode>(m))) << ": "
        << distributionJson(groups[i].step_us[static_cast<std::size_t>(m)]);
    o << "}";
  }
  o << "},\n    \"scenes\": [";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    std::vector<double> steps;
    for (const FrameOutcome& f : runs[i].result.frames) steps.push_back(f.process_us);
    const Distribution d = distribution(steps);
    o << (i ? ", " : "") << "{\"name\": " << eval::jsonString(runs[i].scene.name)
      << ", \"wall_s\": " << num(runs[i].result.wall_s) << ", \"step_median_us\": " << num(d.median)
      << ", \"step_p95_us\": " << num(d.p95) << "}";
  }
  o << "]}\n}\n";
}

void writeCsv(std::ostream& o, const std::vector<SceneRun>& runs) {
  std::vector<std::string> param_keys;
  if (!runs.empty())
    for (const SceneParam& p : sceneParameters(runs.front().scene)) param_keys.push_back(p.key);
  o << "name,family,kind,seed";
  for (const std::string& k : param_keys) o << "," << k;
  o << ",frames_run,visible,expected,tracked,accurate,confidently_wrong,tracked_fraction,accurate_fraction,"
       "recovery_events,recovery_never,recovery_max,mode_changes,acquisition_latency,max_position_error_pct,"
       "max_attitude_error_deg,nis_count,nis_mean,far_fixes,far_off_target,error,time_wall_s,time_step_"
       "median_"
       "us,time_step_p95_us\n";
  for (const SceneRun& run : runs) {
    const Scene& s = run.scene;
    const SceneResult& r = run.result;
    o << csvField(s.name) << "," << toString(s.family) << "," << kindText(s) << "," << seedText(s.seed);
    for (const SceneParam& p : sceneParameters(s)) o << "," << csvField(p.value);
    std::vector<double> steps;
    for (const FrameOutcome& f : r.frames) steps.push_back(f.process_us);
    const Distribution d = distribution(steps);
    o << "," << r.frames.size() << "," << r.visible << "," << r.expected << "," << r.tracked << ","
      << r.accurate << "," << r.wrong << "," << (r.tracked_fraction < 0 ? "" : num(r.tracked_fraction)) << ","
      << (r.accurate_fraction < 0 ? "" : num(r.accurate_fraction)) << "," << r.events.size() << ","
      << r.recovery_never << "," << r.recovery_max << "," << r.mode_changes << ","
      << (r.acquisition_latency == -2 ? std::string() : std::to_string(r.acquisition_latency)) << ","
      << num(100.0 * r.max_position_error_rel) << "," << num(r.max_attitude_error_deg) << "," << r.nis_count
      << "," << num(r.nis_mean) << "," << r.far_fixes << "," << r.far_off_target << ","
      << csvField(r.error.message) << "," << num(r.wall_s) << "," << num(d.median) << "," << num(d.p95)
      << "\n";
  }
}

void writeFramesCsv(std::ostream& o, const std::vector<SceneRun>& runs) {
  o << "scene,family,seed,frame,range_m,visible,expected,eclipsed,slew,mode,pose_valid,fault_bits,position_"
       "error_m,"
       "attitude_error_deg,wrong,tracked,accurate,nis,far_valid,far_distance_m,far_eq16_distance_m,far_"
       "extent_px,far_extent_distance_m,candidate,candidate_position_"
       "error_m,candidate_attitude_error_deg,attitude_sigma_deg,position_sigma_rel,near_flags,lines_used,"
       "lines_"
       "total,reacquired,time_process_us,symmetric_twins,shows_face,twin_by_continuity,kept_branch,jumped,"
       "oracle,near_twin_rival,scanlines,inlier_points,evidence_good,find_on_branch,candidate_range_m,range_"
       "broken,in_view,far_direction_error_deg,far_off_target,withheld,systematic_gain,cov_residual_factor,"
       "cov_vertex_factor,cov_bias_factor_per_px2,mirror_resolved,cov_interior_factor_per_px2,"
       "cov_narrow_factor_per_px2,oracle_evidence,pose_filtered,fit_attitude_sigma_deg,narrow_break\n";
  for (const SceneRun& run : runs) {
    for (const FrameOutcome& f : run.result.frames) {
      o << csvField(run.scene.name) << "," << toString(run.scene.family) << "," << seedText(run.scene.seed)
        << "," << f.frame << "," << num(f.range_m) << "," << f.visible << "," << f.expected << ","
        << f.eclipsed << "," << f.slew << "," << nav::toString(f.mode) << "," << f.pose_valid << ","
        << f.fault_bits << "," << (f.pose_valid ? num(f.position_error_m) : "") << ","
        << (f.pose_valid ? num(f.attitude_error_deg) : "") << "," << f.wrong << "," << f.tracked << ","
        << f.accurate << "," << (f.has_nis ? num(f.nis) : "") << "," << f.far_valid << ","
        << (f.far_valid ? num(f.far_distance_m) : "") << ","
        << (f.far_valid ? num(f.far_eq16_distance_m) : "") << "," << (f.far_valid ? num(f.far_extent_px) : "")
        << "," << (f.far_valid ? num(f.far_extent_distance_m) : "") << "," << f.has_candidate << ","
        << (f.has_candidate ? num(f.candidate_position_error_m) : "") << ","
        << (f.has_candidate ? num(f.candidate_attitude_error_deg) : "") << ","
        << (f.has_candidate ? num(f.attitude_sigma_deg) : "") << ","
        << (f.has_candidate ? num(f.position_sigma_rel) : "") << "," << f.near_flags << "," << f.lines_used
        << "," << f.lines_total << "," << f.reacquired << "," << num(f.process_us) << "," << f.symmetric_twins
        << "," << f.shows_face << "," << f.twin_by_continuity << "," << f.kept_branch << "," << f.jumped
        << "," << f.oracle << "," << f.near_twin_rival << "," << f.scanlines << "," << f.inlier_points << ","
        << f.evidence_good << "," << f.find_on_branch << ","
        << (f.has_candidate ? num(f.candidate_range_m) : "") << "," << f.range_broken << "," << f.in_view
        << "," << (f.far_valid ? num(f.far_direction_error_deg) : "") << "," << f.far_off_target << ","
        << f.withheld << "," << num(f.systematic_gain) << "," << num(f.cov_residual_factor) << ","
        << num(f.cov_vertex_factor) << "," << num(f.cov_bias_factor_per_px2) << "," << f.mirror_resolved
        << "," << num(f.cov_interior_factor_per_px2) << "," << num(f.cov_narrow_factor_per_px2) << ","
        << (f.oracle_evidence >= 0 ? nav::toString(static_cast<nav::EvidenceVerdict>(f.oracle_evidence)) : "")
        << "," << f.pose_filtered << ","
        << (f.has_candidate && f.mode == nav::NavMode::kNearRange ? num(f.fit_attitude_sigma_deg) : "") << ","
        << f.narrow_break << "\n";
    }
  }
}

}  // namespace visnav::campaign
