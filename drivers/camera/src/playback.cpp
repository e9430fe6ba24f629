// The OS calls of the playback pacing: CLOCK_MONOTONIC and its absolute sleep.
#include "visnav/camera/playback.hpp"

#include <ctime>

namespace visnav::camera {
namespace {

std::int64_t nowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

void monotonicSleepUntil(std::int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / 1000000000LL);
  ts.tv_nsec = static_cast<long>(deadline_ns % 1000000000LL);
  // Absolute deadline, so a retry after a signal (EINTR) does not extend the wait; bounded retries.
  for (int attempt = 0; attempt < 16; ++attempt) {
    if (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == 0) return;
  }
}

}  // namespace

std::int64_t FramePacer::now() const {
  return m_clock.now_ns != nullptr ? m_clock.now_ns(m_clock.context) : nowNs();
}

void FramePacer::sleepUntil(std::int64_t deadline_ns) const {
  if (m_clock.sleep_until_ns != nullptr)
    m_clock.sleep_until_ns(m_clock.context, deadline_ns);
  else
    monotonicSleepUntil(deadline_ns);
}

void FramePacer::start(Pacing pacing, std::int64_t recorded_first_ns) {
  m_pacing = pacing;
  m_recorded_first_ns = recorded_first_ns;
  m_origin_ns = 0;
  m_started = false;
}

bool FramePacer::waitUntilDue(std::int64_t offset_ns, std::int64_t timeout_ns) {
  if (m_pacing == Pacing::kAsFastAsPossible) return true;
  const std::int64_t now = this->now();
  if (!m_started) {
    m_origin_ns = now - offset_ns;
    m_started = true;
  }
  const std::int64_t due = m_origin_ns + offset_ns;
  if (now >= due) return true;
  const std::int64_t wait_ns = due - now;
  if (wait_ns > timeout_ns) {
    if (timeout_ns > 0) sleepUntil(now + timeout_ns);
    return false;
  }
  sleepUntil(due);
  return this->now() >= due;
}

std::int64_t FramePacer::exposureNs(std::int64_t offset_ns) const {
  return m_pacing == Pacing::kRecordedRate ? m_origin_ns + offset_ns : m_recorded_first_ns + offset_ns;
}

}  // namespace visnav::camera
