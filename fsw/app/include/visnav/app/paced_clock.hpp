// The simulated clock of a replay that is also watched live: simulated time (so a replay is deterministic and
// matches visnav-replay), plus a real pause of `pace_ns` before every release so a ground tool on DDS keeps
// up with the publication (0: no pause, as fast as the CPU allows).
#pragma once

#include <cstdint>

#include "visnav/executive/clock.hpp"

namespace visnav::app {

class PacedSimulatedClock final : public exec::Clock {
 public:
  PacedSimulatedClock(std::int64_t start_ns, std::int64_t pace_ns)
      : m_simulated(start_ns), m_pace_ns(pace_ns) {}

  std::int64_t nowNs() override { return m_simulated.nowNs(); }
  /// Pauses pace_ns of real time (interruptible: false on a signal), then jumps to the deadline.
  bool sleepUntilNs(std::int64_t deadline_ns) override;
  void onTaskStart(exec::TaskId task) override { m_simulated.onTaskStart(task); }
  void onTaskEnd(exec::TaskId task, std::uint64_t minor_frame) override {
    m_simulated.onTaskEnd(task, minor_frame);
  }

  exec::SimulatedClock& simulated() { return m_simulated; }

 private:
  exec::SimulatedClock m_simulated;
  std::int64_t m_pace_ns;
};

}  // namespace visnav::app
