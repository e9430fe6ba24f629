// Frame numbering shared by the live drivers: turns the driver's 32-bit sequence number into the 64-bit
// Frame::sequence and counts the gaps between delivered frames as dropped frames (frames the camera made
// that the pipeline never saw: lost in the driver, skipped as stale, or corrupt).
#pragma once

#include <cstdint>

namespace visnav::camera {

class SequenceTracker {
 public:
  /// Sequence of the next delivered frame; `dropped` grows by the gap since the previous one. A step
  /// backwards means the driver restarted its count (no gap can be known). Wrap-safe modulo 2^32.
  std::uint64_t next(std::uint32_t driver_sequence, std::uint64_t& dropped) {
    if (!m_started) {
      m_last = m_delivered_any ? m_last + 1 : driver_sequence;
    } else {
      const std::uint32_t step = driver_sequence - m_last_driver;
      if (step == 0U || step > 0x80000000U) {
        m_last += 1;
      } else {
        dropped += step - 1U;
        m_last += step;
      }
    }
    m_started = true;
    m_delivered_any = true;
    m_last_driver = driver_sequence;
    return m_last;
  }
  /// The driver restarts its count (device reopened): the next frame continues from the last one, no gap.
  void restart() { m_started = false; }
  /// Back to the state after construction (a fresh open()).
  void reset() { *this = SequenceTracker{}; }

 private:
  bool m_started = false;
  bool m_delivered_any = false;
  std::uint32_t m_last_driver = 0;
  std::uint64_t m_last = 0;
};

}  // namespace visnav::camera
