// Parameters of the cyclic executive ([executive] table; reference in config/PARAMETERS.md): the frame
// rates, the optional realtime settings of its thread, and how tasks take time on the simulated clock.
#pragma once

#include "visnav/core/param_visitor.hpp"

namespace visnav::exec {

struct ExecutiveParams {
  double major_frame_hz = 5.0;
  int minor_frames_per_major = 1;
  int sched_fifo_priority = 0;
  int cpu_affinity = -1;
  bool lock_memory = false;
  int timer_slack_ns = 1000;
  bool realtime_fatal = false;
  int event_throttle = 10;
  int sim_task_time = 0;  // SimulatedTaskTime: zero|fixed|measured
  double sim_task_us = 0.0;

  /// Minor frame period [ns] (the executive's tick).
  long long minorPeriodNs() const {
    return static_cast<long long>(1e9 / (major_frame_hz * minor_frames_per_major) + 0.5);
  }

  template <typename Visitor>
  void visit(Visitor& v) {
    v.real({"executive", "major_frame_hz", "Hz", 0.1, 1000.0,
            "rate of the major frame: the whole task schedule repeats at this rate"},
           major_frame_hz);
    v.integer({"executive", "minor_frames_per_major", "count", 1, 64,
               "minor frames (executive ticks) per major frame; a task runs in the minor frames selected by "
               "its divisor/offset (default: every task in every frame)"},
              minor_frames_per_major);
    v.integer({"executive", "sched_fifo_priority", "-", 0, 99,
               "SCHED_FIFO priority of the executive thread (needs root or CAP_SYS_NICE); 0 leaves the "
               "default scheduler"},
              sched_fifo_priority);
    v.integer(
        {"executive", "cpu_affinity", "-", -1, 1023, "pin the executive thread to this CPU; -1: no pinning"},
        cpu_affinity);
    v.boolean({"executive", "lock_memory", "-", 0, 1,
               "mlockall (current and future pages) before the loop: no page faults at run time (needs "
               "CAP_IPC_LOCK or a large enough RLIMIT_MEMLOCK)"},
              lock_memory);
    v.integer(
        {"executive", "timer_slack_ns", "ns", 0, 1000000,
         "timer slack of the executive thread (prctl PR_SET_TIMERSLACK): how late the kernel may wake a "
         "SCHED_OTHER sleep to merge wake-ups; 0 keeps the OS default (50 us); SCHED_FIFO has none"},
        timer_slack_ns);
    v.boolean({"executive", "realtime_fatal", "-", 0, 1,
               "a realtime setting above that the OS refuses (EPERM ...) stops the start-up; false: the "
               "refusal is reported and the executive runs without it"},
              realtime_fatal);
    v.integer({"executive", "event_throttle", "count", 0, 1000000,
               "slip and task-failure events reported per kind; later ones are only counted"},
              event_throttle);
    v.enumeration({"executive", "sim_task_time", "-", 0, 2,
                   "simulated clock only: a task takes no time, sim_task_us each, or its measured real time "
                   "(realistic slips, not deterministic)"},
                  "zero|fixed|measured", sim_task_time);
    v.real(
        {"executive", "sim_task_us", "us", 0.0, 1e7, "simulated clock, sim_task_time = fixed: time per task"},
        sim_task_us);
  }

  /// Cross-field checks the per-field ranges cannot express. Returns nullptr when valid.
  const char* crossCheck() const {
    if (major_frame_hz * minor_frames_per_major > 10000.0)
      return "major_frame_hz * minor_frames_per_major must be <= 10000 (minor frame >= 100 us)";
    return nullptr;
  }
};

}  // namespace visnav::exec
