// visnav-monitor: subscribes to every telemetry topic, shows a live terminal view, optionally records every
// sample to CSV, and ends with a summary (on --samples, --duration or a stop request such as Ctrl-C).
#pragma once

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>

#include "visnav/core/status.hpp"
#include "visnav/monitor/topic_stats.hpp"
#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::monitor {

struct MonitorOptions {
  telemetry::TelemetryParams link;  ///< domain and partition (from --config / --domain / --partition)
  std::string csv_path;             ///< empty: no recording
  std::uint64_t stop_after_pose_samples = 0;  ///< 0: no sample limit
  double duration_s = 0.0;                    ///< 0: no time limit
  bool live_view = true;                      ///< redraw the terminal view (only when stdout is a terminal)
  std::string ready_file;  ///< created once every reader has matched a writer (start handshake); empty: none
  int reader_depth = 256;
};

struct MonitorResult {
  TopicStats pose;
  TopicStats far_range;
  TopicStats health;
  double elapsed_s = 0.0;
  bool reached_sample_limit = false;
  bool link_failed = false;  ///< runMonitor's error is the DDS link that did not start (exit 4, not 3)
};

/// Runs until the limits are reached or `stop` becomes true (set it from a signal handler). The summary is
/// printed to `summary_out`. An error is the DDS link that did not start (`result.link_failed`) or a file
/// (--csv, --ready-file) that cannot be written.
LoadError runMonitor(const MonitorOptions& options, const std::atomic<bool>& stop, MonitorResult& result,
                     std::FILE* summary_out);

/// The end-of-run summary: per topic samples, rates, losses, frame gaps, latency median/p99.
std::string summaryText(const MonitorResult& result);

/// Latency [ns] from a timestamp on this host's CLOCK_MONOTONIC to `now_ns`, or -1 when implausible (outside
/// 0..60 s: the stamp comes from a simulated clock or another host).
std::int64_t plausibleLatencyNs(std::int64_t stamp_ns, std::int64_t now_ns);

}  // namespace visnav::monitor
