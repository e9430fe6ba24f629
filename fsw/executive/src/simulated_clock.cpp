#include "visnav/executive/clock.hpp"

namespace visnav::exec {

bool SimulatedClock::sleepUntilNs(std::int64_t deadline_ns) {
  if (deadline_ns <= m_now_ns) return true;  // nothing to sleep: no wake-up, no latency
  m_now_ns = deadline_ns + m_wake_fixed_ns;
  if (m_wake_spread_ns > 0) {
    m_now_ns += static_cast<std::int64_t>(m_wake_rng.uniform() * static_cast<double>(m_wake_spread_ns));
  }
  return true;
}

void SimulatedClock::onTaskStart(TaskId /*task*/) {
  if (m_model == nullptr && m_mode == SimulatedTaskTime::kMeasured) m_task_real_start_ns = monotonicNowNs();
}

void SimulatedClock::onTaskEnd(TaskId task, std::uint64_t minor_frame) {
  if (m_model != nullptr) {
    advanceNs(m_model->durationNs(task, minor_frame));
  } else if (m_mode == SimulatedTaskTime::kFixed && task.valid() && task.index() < kMaxTasks) {
    advanceNs(m_fixed_ns[static_cast<std::size_t>(task.index())]);
  } else if (m_mode == SimulatedTaskTime::kMeasured) {
    advanceNs(monotonicNowNs() - m_task_real_start_ns);
  }
}

void SimulatedClock::setFixedTaskNs(TaskId task, std::int64_t duration_ns) {
  if (task.valid() && task.index() < kMaxTasks)
    m_fixed_ns[static_cast<std::size_t>(task.index())] = duration_ns;
}

void SimulatedClock::setWakeLatency(std::int64_t fixed_ns, std::int64_t spread_ns, std::uint64_t seed) {
  m_wake_fixed_ns = fixed_ns > 0 ? fixed_ns : 0;
  m_wake_spread_ns = spread_ns > 0 ? spread_ns : 0;
  m_wake_rng.reseed(seed);
}

}  // namespace visnav::exec
