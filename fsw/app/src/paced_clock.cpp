#include "visnav/app/paced_clock.hpp"

#include <ctime>

namespace visnav::app {

bool PacedSimulatedClock::sleepUntilNs(std::int64_t deadline_ns) {
  if (m_pace_ns > 0) {
    const timespec pause{static_cast<time_t>(m_pace_ns / 1'000'000'000),
                         static_cast<long>(m_pace_ns % 1'000'000'000)};
    if (clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr) != 0)
      return false;  // EINTR: look at the stop flag
  }
  return m_simulated.sleepUntilNs(deadline_ns);
}

}  // namespace visnav::app
