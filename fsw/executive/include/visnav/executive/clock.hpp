// The executive's time source. MonotonicClock is CLOCK_MONOTONIC with absolute-deadline sleeps (its OS calls
// live in src/posix_os.cpp); SimulatedClock jumps straight to the next deadline, so replays and tests are
// deterministic and run as fast as the CPU allows. On the simulated clock a task takes the time its model
// says (zero, fixed per task, a custom model, or the real elapsed time), charged between onTaskStart() and
// onTaskEnd().
#pragma once

#include <array>
#include <cstdint>

#include "visnav/core/rng.hpp"
#include "visnav/executive/executive_params.hpp"
#include "visnav/executive/task.hpp"

namespace visnav::exec {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual std::int64_t nowNs() = 0;
  /// Returns true once now >= deadline; false when interrupted earlier (a signal): the caller re-checks its
  /// stop flag and may call again.
  virtual bool sleepUntilNs(std::int64_t deadline_ns) = 0;
  /// Around every task run: lets a simulated clock charge the task's modelled duration.
  virtual void onTaskStart(TaskId /*task*/) {}
  virtual void onTaskEnd(TaskId /*task*/, std::uint64_t /*minor_frame*/) {}
};

/// CLOCK_MONOTONIC; sleeps with clock_nanosleep(TIMER_ABSTIME), so lateness never accumulates.
class MonotonicClock final : public Clock {
 public:
  std::int64_t nowNs() override;
  bool sleepUntilNs(std::int64_t deadline_ns) override;
};

/// Reads CLOCK_MONOTONIC [ns] (for code that needs the real time outside a Clock, e.g. camera pacing).
std::int64_t monotonicNowNs();

/// Custom duration model for the simulated clock (e.g. replayed timings).
class TaskDurationModel {
 public:
  virtual ~TaskDurationModel() = default;
  virtual std::int64_t durationNs(TaskId task, std::uint64_t minor_frame) = 0;
};

enum class SimulatedTaskTime : int { kZero = 0, kFixed = 1, kMeasured = 2 };

class SimulatedClock final : public Clock {
 public:
  explicit SimulatedClock(std::int64_t start_ns = 0) : m_now_ns(start_ns) {}

  std::int64_t nowNs() override { return m_now_ns; }
  /// Jumps to the deadline (never backwards) plus the modelled wake latency.
  bool sleepUntilNs(std::int64_t deadline_ns) override;
  void onTaskStart(TaskId task) override;
  void onTaskEnd(TaskId task, std::uint64_t minor_frame) override;

  /// Moves time forward (a task may call it to model its own duration).
  void advanceNs(std::int64_t delta_ns) {
    if (delta_ns > 0) m_now_ns += delta_ns;
  }
  /// kFixed: every task takes `task_ns[task]`; kMeasured: the real elapsed time of the task (realistic,
  /// not deterministic); kZero: tasks take no time. A custom model, when set, wins over all three.
  void setTaskTime(SimulatedTaskTime mode) { m_mode = mode; }
  void setFixedTaskNs(TaskId task, std::int64_t duration_ns);
  void setAllFixedTaskNs(std::int64_t duration_ns) { m_fixed_ns.fill(duration_ns); }
  void setDurationModel(TaskDurationModel* model) { m_model = model; }
  /// sim_task_time and sim_task_us of the [executive] config.
  void applyParams(const ExecutiveParams& params) {
    setTaskTime(static_cast<SimulatedTaskTime>(params.sim_task_time));
    setAllFixedTaskNs(static_cast<std::int64_t>(params.sim_task_us * 1e3 + 0.5));
  }
  /// Wake latency after each sleep: fixed_ns + uniform [0, spread_ns), seeded (deterministic jitter).
  void setWakeLatency(std::int64_t fixed_ns, std::int64_t spread_ns, std::uint64_t seed);

 private:
  std::int64_t m_now_ns;
  SimulatedTaskTime m_mode = SimulatedTaskTime::kZero;
  std::array<std::int64_t, kMaxTasks> m_fixed_ns{};
  TaskDurationModel* m_model = nullptr;
  std::int64_t m_task_real_start_ns = 0;
  std::int64_t m_wake_fixed_ns = 0;
  std::int64_t m_wake_spread_ns = 0;
  Pcg32 m_wake_rng;
};

}  // namespace visnav::exec
