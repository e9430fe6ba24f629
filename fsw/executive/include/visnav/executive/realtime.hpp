// Optional realtime settings of the executive's thread, from ExecutiveParams: SCHED_FIFO priority, CPU
// affinity, mlockall, timer slack. Init time, called on the thread that will run the loop. Each refusal
// carries a message saying what was refused, why (errno) and how to permit it; whether a refusal stops the
// start-up is realtime_fatal. The OS calls are in src/posix_os.cpp.
#pragma once

#include <array>

#include "visnav/core/status.hpp"
#include "visnav/executive/executive_params.hpp"

namespace visnav::exec {

struct RealtimeOutcome {
  bool requested = false;
  bool applied = false;
  int error_number = 0;             ///< errno of the refusal, 0 when applied or not requested
  std::array<char, 256> message{};  ///< NUL-terminated; empty when not requested
};

struct RealtimeReport {
  RealtimeOutcome scheduler;
  RealtimeOutcome affinity;
  RealtimeOutcome memory_lock;
  RealtimeOutcome timer_slack;
  /// True when every requested setting was applied.
  bool allApplied() const {
    return (!scheduler.requested || scheduler.applied) && (!affinity.requested || affinity.applied) &&
           (!memory_lock.requested || memory_lock.applied) && (!timer_slack.requested || timer_slack.applied);
  }
};

/// Applies the requested settings to the calling thread (priority, affinity) and process (memory lock).
/// Fails only when something was refused and params.realtime_fatal is set; the message lists the refusals.
LoadError applyRealtimeSettings(const ExecutiveParams& params, RealtimeReport& report);

}  // namespace visnav::exec
