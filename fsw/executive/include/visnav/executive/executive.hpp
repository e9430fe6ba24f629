// The cyclic executive: one thread, a fixed task table set at init, absolute-deadline releases every minor
// frame (period = 1 / (major_frame_hz * minor_frames_per_major)), tasks called synchronously in
// registration order. A cycle that ends past its deadline is a slip: counted, reported (throttled), and the
// next release is the first one not already in the past, never a burst of catch-up cycles. A failing task is
// counted and reported; the cycle goes on. Per-task execution time and release jitter are kept in fixed
// storage (DurationStats). Nothing here allocates or calls the OS except through the Clock.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "visnav/core/status.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/executive/duration_stats.hpp"
#include "visnav/executive/executive_params.hpp"
#include "visnav/executive/task.hpp"

namespace visnav::exec {

struct SlipEvent {
  std::uint64_t minor_frame = 0;
  std::int64_t overrun_ns = 0;         ///< cycle end minus its deadline
  std::uint64_t releases_skipped = 0;  ///< releases dropped to get back in phase
};

struct TaskFailureEvent {
  TaskId task;
  const char* name = "";
  Status status = Status::kOk;
  std::uint64_t minor_frame = 0;
};

/// Receives slip and task-failure events (at most event_throttle of each kind), on the executive's thread.
class ExecutiveObserver {
 public:
  virtual ~ExecutiveObserver() = default;
  virtual void onSlip(const SlipEvent& event) = 0;
  virtual void onTaskFailure(const TaskFailureEvent& event) = 0;
};

struct TaskStats {
  const char* name = "";
  DurationStats exec;  ///< execution time per run [ns]
  std::uint64_t runs = 0;
  std::uint64_t failures = 0;
  Status last_failure = Status::kOk;
};

struct ExecutiveCounters {
  std::uint64_t cycles = 0;            ///< minor frames run
  std::uint64_t slips = 0;             ///< cycles that ended past their deadline
  std::uint64_t releases_skipped = 0;  ///< releases never run because a slip ran over them
  std::uint64_t task_failures = 0;
  std::uint64_t events_suppressed = 0;  ///< events beyond event_throttle (counted only)
  std::int64_t worst_overrun_ns = 0;
};

enum class StopReason : std::uint8_t { kNotRun = 0, kStopRequested = 1, kCycleLimit = 2 };

class Executive {
 public:
  Executive() = default;
  Executive(const Executive&) = delete;
  Executive& operator=(const Executive&) = delete;

  /// Init time: checks the parameters, forgets every task and statistic.
  LoadError init(const ExecutiveParams& params, Clock& clock);
  /// Init time: appends a task. It runs in the minor frames m with m % divisor == offset. On success `id`
  /// names the task from then on (taskStats(), TaskFailureEvent::task, the clock's hooks); on failure `id` is
  /// invalid. `name` must outlive the executive (a literal or a static names table).
  LoadError addTask(TaskId& id, const char* name, TaskFn fn, void* context, int divisor = 1, int offset = 0);
  LoadError addTask(TaskId& id, const char* name, CycleTask& task, int divisor = 1, int offset = 0);
  void setObserver(ExecutiveObserver* observer) { m_observer = observer; }

  /// Runs minor frames until requestStop() or `max_cycles` cycles (0: no limit). The first release is the
  /// clock's time at the call. Each call starts a new epoch; statistics accumulate across calls.
  StopReason run(std::uint64_t max_cycles);

  /// Async-signal-safe (a lock-free atomic store): the loop ends at the latest after the current cycle.
  void requestStop() noexcept { m_stop.store(true, std::memory_order_relaxed); }
  bool stopRequested() const noexcept { return m_stop.load(std::memory_order_relaxed); }
  void clearStop() noexcept { m_stop.store(false, std::memory_order_relaxed); }

  int taskCount() const { return m_task_count; }
  /// Statistics of a task addTask() registered (an invalid id: an empty record).
  const TaskStats& taskStats(TaskId task) const {
    if (task.valid() && task.index() < m_task_count) return m_stats[static_cast<std::size_t>(task.index())];
    return m_no_stats;
  }
  const DurationStats& releaseJitter() const { return m_jitter; }  ///< wake minus ideal release [ns]
  const DurationStats& cycleBusy() const { return m_busy; }        ///< wake to end of the last task [ns]
  const ExecutiveCounters& counters() const { return m_counters; }
  std::int64_t minorPeriodNs() const { return m_period_ns; }
  void resetStatistics();

 private:
  struct TaskEntry {
    TaskFn fn = nullptr;
    void* context = nullptr;
    int divisor = 1;
    int offset = 0;
  };
  static_assert(std::atomic<bool>::is_always_lock_free, "requestStop() must be async-signal-safe");

  void runCycle(const CycleInfo& info);
  bool sleepToRelease(std::int64_t release_ns);
  bool allowEvent(std::uint64_t& reported);

  ExecutiveParams m_params;
  Clock* m_clock = nullptr;
  ExecutiveObserver* m_observer = nullptr;
  std::int64_t m_period_ns = 0;
  std::array<TaskEntry, kMaxTasks> m_tasks{};
  std::array<TaskStats, kMaxTasks> m_stats{};
  TaskStats m_no_stats;  ///< what taskStats() of an invalid id returns
  int m_task_count = 0;
  DurationStats m_jitter;
  DurationStats m_busy;
  ExecutiveCounters m_counters;
  std::uint64_t m_slip_events = 0;
  std::uint64_t m_failure_events = 0;
  std::atomic<bool> m_stop{false};
};

}  // namespace visnav::exec
