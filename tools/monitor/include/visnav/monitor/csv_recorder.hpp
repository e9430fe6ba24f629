// visnav-monitor --csv FILE: every received sample, one CSV per topic. FILE holds the PoseEstimate rows with
// the column names of visnav-replay's CSV (frame, timestamp_ns, status, x_m ... qz, yaw_deg ...), so
// visnav-eval scores a monitor recording directly; FILE's stem + "_far_range.csv" and "_health.csv" hold the
// other topics. Reception columns (receive_time_ns, latencies) come last.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "visnav/core/status.hpp"
#include "visnav/telemetry/dds_topics.hpp"

namespace visnav::monitor {

/// Receive-side timing of one sample.
struct Reception {
  std::int64_t receive_mono_ns = 0;  ///< CLOCK_MONOTONIC at take
  std::int64_t receive_wall_ns = 0;  ///< CLOCK_REALTIME at take (dds_time())
  std::int64_t source_wall_ns = 0;   ///< DDS source timestamp (writer's CLOCK_REALTIME)
};

/// "out/run.csv" -> "out/run_far_range.csv" for suffix "_far_range".
std::string siblingPath(const std::string& path, const char* suffix);

class CsvRecorder {
 public:
  CsvRecorder() = default;
  ~CsvRecorder();
  CsvRecorder(const CsvRecorder&) = delete;
  CsvRecorder& operator=(const CsvRecorder&) = delete;

  /// Opens the three files and writes the headers.
  LoadError open(const std::string& pose_path);
  void pose(const visnav_PoseEstimate& s, const Reception& r);
  void farRange(const visnav_FarRangeEstimate& s, const Reception& r);
  void health(const visnav_Health& s, const Reception& r);
  /// Flushes and closes; false when any write failed.
  bool close();

 private:
  std::FILE* m_pose = nullptr;
  std::FILE* m_far = nullptr;
  std::FILE* m_health = nullptr;
};

}  // namespace visnav::monitor
