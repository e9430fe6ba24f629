#include "visnav/executive/executive.hpp"

namespace visnav::exec {
namespace {

// A signal storm must not keep the loop in its sleep forever (every loop bounded).
constexpr int kMaxSleepAttempts = 1000;

}  // namespace

LoadError Executive::init(const ExecutiveParams& params, Clock& clock) {
  if (!(params.major_frame_hz > 0.0) || params.minor_frames_per_major < 1)
    return LoadError::failure("executive: major_frame_hz must be > 0 and minor_frames_per_major >= 1");
  if (const char* problem = params.crossCheck())
    return LoadError::failure(std::string("executive: ") + problem);
  if (params.event_throttle < 0) return LoadError::failure("executive: event_throttle must be >= 0");
  m_params = params;
  m_clock = &clock;
  m_period_ns = params.minorPeriodNs();
  m_task_count = 0;
  m_tasks = {};
  resetStatistics();
  clearStop();
  return LoadError::success();
}

LoadError Executive::addTask(TaskId& id, const char* name, TaskFn fn, void* context, int divisor,
                             int offset) {
  id = TaskId{};
  if (m_clock == nullptr) return LoadError::failure("executive: addTask() before init()");
  if (name == nullptr || fn == nullptr)
    return LoadError::failure("executive: task needs a name and a function");
  if (m_task_count >= kMaxTasks)
    return LoadError::failure(std::string("executive: task table full (") + std::to_string(kMaxTasks) +
                              " tasks), cannot add '" + name + "'");
  if (divisor < 1 || offset < 0 || offset >= divisor)
    return LoadError::failure(std::string("executive: task '") + name +
                              "' needs divisor >= 1 and 0 <= offset < divisor");
  const auto i = static_cast<std::size_t>(m_task_count++);
  m_tasks[i] = TaskEntry{fn, context, divisor, offset};
  m_stats[i] = TaskStats{};
  m_stats[i].name = name;
  id = TaskId(static_cast<int>(i));
  return LoadError::success();
}

LoadError Executive::addTask(TaskId& id, const char* name, CycleTask& task, int divisor, int offset) {
  const TaskFn trampoline = [](void* context, const CycleInfo& cycle) {
    return static_cast<CycleTask*>(context)->runCycle(cycle);
  };
  return addTask(id, name, trampoline, &task, divisor, offset);
}

void Executive::resetStatistics() {
  for (int i = 0; i < kMaxTasks; ++i) {
    TaskStats& s = m_stats[static_cast<std::size_t>(i)];
    const char* name = s.name;
    s = TaskStats{};
    s.name = name;
  }
  m_jitter.reset();
  m_busy.reset();
  m_counters = ExecutiveCounters{};
  m_slip_events = 0;
  m_failure_events = 0;
}

bool Executive::allowEvent(std::uint64_t& reported) {
  if (m_observer == nullptr) return false;
  if (reported < static_cast<std::uint64_t>(m_params.event_throttle)) {
    ++reported;
    return true;
  }
  ++m_counters.events_suppressed;
  return false;
}

bool Executive::sleepToRelease(std::int64_t release_ns) {
  for (int attempt = 0; attempt < kMaxSleepAttempts; ++attempt) {
    if (m_clock->sleepUntilNs(release_ns)) return true;
    if (stopRequested()) return false;
  }
  return true;  // interrupted over and over: run the frame rather than hang
}

void Executive::runCycle(const CycleInfo& info) {
  for (int i = 0; i < m_task_count; ++i) {
    const TaskEntry& task = m_tasks[static_cast<std::size_t>(i)];
    if (info.minor_frame % static_cast<std::uint64_t>(task.divisor) !=
        static_cast<std::uint64_t>(task.offset))
      continue;
    TaskStats& stats = m_stats[static_cast<std::size_t>(i)];
    const TaskId id(i);
    const std::int64_t start_ns = m_clock->nowNs();
    m_clock->onTaskStart(id);
    const Status status = task.fn(task.context, info);
    m_clock->onTaskEnd(id, info.minor_frame);
    stats.exec.add(m_clock->nowNs() - start_ns);
    ++stats.runs;
    if (status == Status::kOk) continue;
    ++stats.failures;
    stats.last_failure = status;
    ++m_counters.task_failures;
    if (allowEvent(m_failure_events)) m_observer->onTaskFailure({id, stats.name, status, info.minor_frame});
  }
}

StopReason Executive::run(std::uint64_t max_cycles) {
  if (m_clock == nullptr) return StopReason::kNotRun;
  const std::int64_t epoch_ns = m_clock->nowNs();
  std::uint64_t frame = 0;
  for (std::uint64_t cycles = 0;; ++cycles) {  // ends on stop or the cycle limit
    if (stopRequested()) return StopReason::kStopRequested;
    if (max_cycles != 0U && cycles >= max_cycles) return StopReason::kCycleLimit;
    const std::int64_t release_ns = epoch_ns + static_cast<std::int64_t>(frame) * m_period_ns;
    if (!sleepToRelease(release_ns)) return StopReason::kStopRequested;
    const std::int64_t wake_ns = m_clock->nowNs();
    m_jitter.add(wake_ns - release_ns);
    const CycleInfo info{frame, m_counters.cycles, release_ns, wake_ns, release_ns + m_period_ns};
    runCycle(info);
    const std::int64_t end_ns = m_clock->nowNs();
    m_busy.add(end_ns - wake_ns);
    ++m_counters.cycles;
    std::uint64_t next = frame + 1U;
    if (end_ns > info.deadline_ns) {
      // Slip: resume at the first release not in the past; the releases in between are dropped, not run.
      next = static_cast<std::uint64_t>((end_ns - epoch_ns + m_period_ns - 1) / m_period_ns);
      const SlipEvent slip{frame, end_ns - info.deadline_ns, next - frame - 1U};
      ++m_counters.slips;
      m_counters.releases_skipped += slip.releases_skipped;
      if (slip.overrun_ns > m_counters.worst_overrun_ns) m_counters.worst_overrun_ns = slip.overrun_ns;
      if (allowEvent(m_slip_events)) m_observer->onSlip(slip);
    }
    frame = next;
  }
}

}  // namespace visnav::exec
