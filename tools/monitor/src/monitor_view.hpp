// The live terminal view of visnav-monitor (internal).
#pragma once

#include <cstdio>

#include "visnav/monitor/monitor.hpp"
#include "visnav/telemetry/dds_topics.hpp"

namespace visnav::monitor {

struct LatestSamples {
  bool have_pose = false;
  bool have_far = false;
  bool have_health = false;
  visnav_PoseEstimate pose{};
  visnav_FarRangeEstimate far{};
  visnav_Health health{};
};

/// Clears the terminal and draws the current state.
void drawView(std::FILE* out, const MonitorOptions& options, const LatestSamples& latest,
              const MonitorResult& result);

}  // namespace visnav::monitor
