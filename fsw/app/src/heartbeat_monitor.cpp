#include "visnav/app/heartbeat_monitor.hpp"

namespace visnav::app {

void HeartbeatMonitor::reset() {
  m_stages = {};
  m_cycles = 0;
  m_healthy_cycles = 0;
}

void HeartbeatMonitor::registerStage(CycleStage stage) {
  StageHeartbeat& s = at(stage);
  s = StageHeartbeat{};
  s.registered = true;
}

bool HeartbeatMonitor::endCycle() {
  ++m_cycles;
  bool any = false;
  bool all = true;
  for (StageHeartbeat& s : m_stages) {
    if (!s.registered) continue;
    any = true;
    s.ended_run = 0;
    if (s.beat) {
      ++s.beats;
      s.ended_run = s.missed_run;
      s.missed_run = 0;
    } else {
      ++s.missed;
      ++s.missed_run;
      all = false;
    }
    s.beat = false;
  }
  const bool healthy = any && all;
  if (healthy) ++m_healthy_cycles;
  return healthy;
}

}  // namespace visnav::app
