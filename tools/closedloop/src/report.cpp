#include "visnav/closedloop/report.hpp"

#include <cstdio>

#include "visnav/closedloop/guidance.hpp"
#include "visnav/visnav.h"

namespace visnav::closedloop {
namespace {

void printRun(std::FILE* out, const RunResult& r) {
  std::fprintf(out, "  %-6s: %s after %.1f s; ", r.label.c_str(), r.ended.c_str(), r.frames.back().t_s);
  if (r.arrived) {
    std::fprintf(out, "arrived at %.1f s with delta-v %.3f m/s; ", r.arrival_time_s, r.arrival_delta_v_m_s);
  } else {
    std::fputs("NOT arrived; ", out);
  }
  std::fprintf(out,
               "final error %.4f m, %.3f deg (hold window max %.4f m, %.3f deg); delta-v total %.3f m/s\n",
               r.final_position_error_m, r.final_attitude_error_deg, r.hold_max_position_error_m,
               r.hold_max_attitude_error_deg, r.total_delta_v_m_s);
}

}  // namespace

void printSummary(std::FILE* out, const ScenarioParams& p, const RunResult& v, const RunResult& t) {
  std::fprintf(
      out,
      "visnav-closedloop: scenario %s: plate from %.0f m to the hold point %.1f m in front of its face, "
      "tumbling %.2f deg/s (face normal %.0f deg off the spin axis); gates %.2f m, %.1f deg held %.0f s\n",
      p.name.c_str(), p.start_range_m, p.hold_distance_m, p.tumble_rate_deg_s, p.nutation_deg,
      p.gate_position_m, p.gate_attitude_deg, p.hold_window_s);
  printRun(out, v);
  printRun(out, t);
  if (v.arrived && t.arrived && t.arrival_delta_v_m_s > 0.0)
    std::fprintf(out, "  delta-v to arrival: visnav %.3f m/s vs truth %.3f m/s (%+.1f %%); arrival %+.1f s\n",
                 v.arrival_delta_v_m_s, t.arrival_delta_v_m_s,
                 100.0 * (v.arrival_delta_v_m_s / t.arrival_delta_v_m_s - 1.0),
                 v.arrival_time_s - t.arrival_time_s);
  // Mode timeline of the visnav run, and where the guidance changed phase.
  std::fputs("  timeline:", out);
  int mode = -2, phase = -1;
  int frames_in_mode[4] = {0, 0, 0, 0};
  double worst_estimate_near = 0.0;
  for (const FrameLog& f : v.frames) {
    if (f.mode >= 0 && f.mode < 4) ++frames_in_mode[f.mode];
    if (f.mode == VISNAV_MODE_NEAR_RANGE && f.estimate_error_m > worst_estimate_near)
      worst_estimate_near = f.estimate_error_m;
    if (f.mode != mode) {
      std::fprintf(out, " %.1f s %s (%.1f m);", f.t_s, visnav_mode_name(f.mode), f.range_m);
      mode = f.mode;
    }
    if (f.phase != phase) {
      std::fprintf(out, " %.1f s guidance %s;", f.t_s, toString(static_cast<Phase>(f.phase)));
      phase = f.phase;
    }
  }
  std::fprintf(out,
               "\n  frames: far range %d, acquisition %d, near range %d; estimator rejections %d; worst "
               "|estimate - truth| in near range %.3f m\n",
               frames_in_mode[VISNAV_MODE_FAR_RANGE], frames_in_mode[VISNAV_MODE_ACQUISITION],
               frames_in_mode[VISNAV_MODE_NEAR_RANGE], v.estimator_rejections, worst_estimate_near);
}

LoadError writeCsv(const std::string& path, const RunResult& v, const RunResult& t) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return LoadError::failure(path + ": cannot open for writing");
  std::fputs(
      "run,t_s,range_m,position_error_m,attitude_error_deg,estimate_error_m,delta_v_m_s,mode,track_status,"
      "phase\n",
      f);
  for (const RunResult* r : {&v, &t})
    for (const FrameLog& x : r->frames)
      std::fprintf(f, "%s,%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%s,%s,%s\n", r->label.c_str(), x.t_s, x.range_m,
                   x.position_error_m, x.attitude_error_deg, x.estimate_error_m, x.delta_v_m_s,
                   x.mode >= 0 ? visnav_mode_name(x.mode) : "truth",
                   x.mode >= 0 ? visnav_track_status_name(x.track_status) : "truth",
                   toString(static_cast<Phase>(x.phase)));
  if (std::fclose(f) != 0) return LoadError::failure(path + ": write failed");
  return LoadError::success();
}

}  // namespace visnav::closedloop
