#include "monitor_view.hpp"

#include <string>

#include "visnav/core/stage_interfaces.hpp"
#include "visnav/core/types.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::monitor {
namespace {

constexpr const char* kTaskNames[visnav_TASK_COUNT] = {"acquire", "process", "publish", "health"};

void topicLine(std::FILE* out, const char* name, const TopicStats& s) {
  const LatencySummary pub = s.publishLatency();
  const LatencySummary exp = s.exposureLatency();
  std::fprintf(out, "  %-10s %8llu %8.2f %6llu %7llu   ", name, static_cast<unsigned long long>(s.samples()),
               s.recentRateHz(), static_cast<unsigned long long>(s.lostSamples()),
               static_cast<unsigned long long>(s.lostFrames()));
  if (pub.count > 0)
    std::fprintf(out, "%6.3f/%6.3f  ", pub.median_ms, pub.p99_ms);
  else
    std::fputs("      n/a      ", out);
  if (exp.count > 0)
    std::fprintf(out, "%7.3f/%7.3f\n", exp.median_ms, exp.p99_ms);
  else
    std::fputs("      n/a\n", out);
}

/// "none", or the names of the set fault bits ("residual,innovation"), as visnavd's log spells them.
std::string faultList(std::uint32_t bits) {
  std::string text;
  for (int b = 0; b < 32; ++b) {
    if ((bits & (1U << b)) == 0U) continue;
    if (!text.empty()) text += ',';
    text += faultName(b);
  }
  return text.empty() ? "none" : text;
}

}  // namespace

void drawView(std::FILE* out, const MonitorOptions& options, const LatestSamples& latest,
              const MonitorResult& result) {
  std::fputs("\x1b[H\x1b[2J", out);  // home, clear screen
  std::fprintf(out, "visnav-monitor  domain %d  partition %s  %.1f s   (Ctrl-C: stop with summary)\n\n",
               options.link.domain_id, options.link.partitionName(), result.elapsed_s);
  if (latest.have_pose) {
    const visnav_PoseEstimate& p = latest.pose;
    std::fprintf(out, "mode %-12s status %-9s frame %-8llu quality %.3f  faults %s\n",
                 telemetry::modeName(p.mode), telemetry::trackStatusName(p.status),
                 static_cast<unsigned long long>(p.frame_number), p.quality, faultList(p.fault_bits).c_str());
    std::fprintf(out, "position t_c_m [m]   x %9.4f  y %9.4f  z %9.4f\n", p.position_m[0], p.position_m[1],
                 p.position_m[2]);
    std::fprintf(
        out,
        "attitude [deg]       yaw %8.3f  pitch %8.3f  roll %8.3f   surfaces %u lines %u/%u  twins %u%s\n",
        p.yaw_rad * kDegPerRad, p.pitch_rad * kDegPerRad, p.roll_rad * kDegPerRad, p.tracked_surfaces,
        p.lines_used, p.lines_total, p.symmetric_twins,
        p.twin_by_continuity ? " (chosen by continuity)" : "");
  } else {
    std::fputs("no PoseEstimate yet\n\n\n", out);
  }
  if (latest.have_far) {
    const visnav_FarRangeEstimate& f = latest.far;
    std::fprintf(out, "far range %-5s       az %8.3f deg  el %8.3f deg  distance %9.2f m  n %u  circ %.2f\n",
                 f.valid ? "valid" : "none", f.azimuth_rad * kDegPerRad, f.elevation_rad * kDegPerRad,
                 f.distance_m, f.cluster_pixels, f.circularity);
  } else {
    std::fputs("no FarRangeEstimate yet\n", out);
  }
  if (latest.have_health) {
    const visnav_Health& h = latest.health;
    std::fprintf(
        out, "\nhealth: mode %s  faults %s  frames %llu  dropped %llu  slips %llu  transitions %llu\n",
        telemetry::modeName(h.mode), faultList(h.fault_bits).c_str(),
        static_cast<unsigned long long>(h.frames_processed),
        static_cast<unsigned long long>(h.frames_dropped), static_cast<unsigned long long>(h.cycle_slips),
        static_cast<unsigned long long>(h.mode_transitions));
    std::fprintf(out, "  last transition %s -> %s at frame %llu: %s\n",
                 telemetry::modeName(h.last_transition.from_mode),
                 telemetry::modeName(h.last_transition.to_mode),
                 static_cast<unsigned long long>(h.last_transition.frame_number), h.last_transition.reason);
    if (h.last_command.command_id != 0) {
      std::fprintf(out, "  last command #%u %s: %s (%s)\n", h.last_command.command_id,
                   telemetry::commandKindName(h.last_command.kind),
                   h.last_command.accepted ? "accepted" : "rejected", h.last_command.reason);
    } else {
      std::fputs("  no command received\n", out);
    }
    std::fputs("  task time [us]    min     mean      p99      max\n", out);
    for (int i = 0; i < visnav_TASK_COUNT; ++i) {
      const visnav_TaskTiming& t = h.task_timing[i];
      std::fprintf(out, "  %-10s %9.1f %8.1f %8.1f %8.1f\n", kTaskNames[i], t.min_us, t.mean_us, t.p99_us,
                   t.max_us);
    }
  } else {
    std::fputs("\nno Health yet\n", out);
  }
  std::fputs("\n  topic       samples  rate Hz   lost  frames   pub->rx ms     exposure->rx ms\n", out);
  std::fputs("                                         gaps     med/p99         med/p99\n", out);
  topicLine(out, "pose", result.pose);
  topicLine(out, "far_range", result.far_range);
  topicLine(out, "health", result.health);
  std::fflush(out);
}

}  // namespace visnav::monitor
