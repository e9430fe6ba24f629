// Per-stage heartbeat behind the systemd watchdog (after F Prime's health component: every component must
// answer its ping, else the health task stops stroking the hardware watchdog). Each registered cycle stage
// calls beat() when it completed its work of the cycle successfully (what "successfully" means per stage:
// fsw/app/README.md, "Watchdog"); at the end of the cycle the health task calls endCycle(), which says
// whether every registered stage beat since the previous endCycle(). Only then is WATCHDOG=1 sent, so a stage
// that keeps failing, or hangs (no endCycle() at all), lets systemd's WatchdogSec expire. Misses are counted
// per stage (total and in a row). Fixed storage, no allocation, no OS call: the caller logs and notifies.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/core/stage_interfaces.hpp"

namespace visnav::app {

struct StageHeartbeat {
  bool registered = false;
  bool beat = false;             ///< beat since the last endCycle()
  std::uint64_t beats = 0;       ///< cycles it beat
  std::uint64_t missed = 0;      ///< cycles it did not beat, in total
  std::uint64_t missed_run = 0;  ///< cycles it did not beat in a row, up to the last endCycle()
  std::uint64_t ended_run = 0;   ///< a run of misses that the last endCycle() ended with a beat (else 0)
};

class HeartbeatMonitor {
 public:
  /// Init time: forgets every stage and count; no stage is expected until registerStage().
  void reset();
  /// Init time: `stage` must beat in every cycle from now on.
  void registerStage(CycleStage stage);
  /// The stage completed its work of this cycle successfully (idempotent within a cycle).
  void beat(CycleStage stage) { at(stage).beat = true; }
  /// End of a cycle: true when every registered stage beat (the watchdog may be stroked), false when one did
  /// not or none is registered. Counts beats and misses, then clears the beats for the next cycle.
  bool endCycle();

  const StageHeartbeat& stage(CycleStage stage) const {
    return m_stages[static_cast<std::size_t>(stageIndex(stage))];
  }
  std::uint64_t cycles() const { return m_cycles; }                 ///< endCycle() calls
  std::uint64_t healthyCycles() const { return m_healthy_cycles; }  ///< of which every stage beat

 private:
  StageHeartbeat& at(CycleStage stage) { return m_stages[static_cast<std::size_t>(stageIndex(stage))]; }

  std::array<StageHeartbeat, kCycleStageCount> m_stages{};
  std::uint64_t m_cycles = 0;
  std::uint64_t m_healthy_cycles = 0;
};

}  // namespace visnav::app
