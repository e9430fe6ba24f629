// Shared by the two playback cameras (replay, synthetic): the pacing of a recorded timeline on
// CLOCK_MONOTONIC (or none: as fast as the consumer asks), and the small ring of frame slots that hands a
// frame out in acquire() and takes it back in release(). Neither drops frames: a late consumer gets the next
// frame of the timeline at once. The pacing's OS calls (clock_gettime, clock_nanosleep) are in
// src/playback.cpp.
#pragma once

#include <cstdint>

namespace visnav::camera {

enum class Pacing : std::uint8_t {
  kAsFastAsPossible =
      0,              ///< every acquire() returns the next frame at once; timestamps are the recorded ones
  kRecordedRate = 1,  ///< frame i is not delivered before start + (t_i - t_0) on CLOCK_MONOTONIC
};

/// The time source of the pacing: CLOCK_MONOTONIC and its absolute sleep by default (both null). Tests
/// inject a simulated one, so what they check does not depend on how fast the machine runs them.
struct PacerClock {
  std::int64_t (*now_ns)(void* context) = nullptr;
  void (*sleep_until_ns)(void* context, std::int64_t deadline_ns) = nullptr;
  void* context = nullptr;
};

/// Maps the recorded timeline (offsets from its first frame) onto the monotonic clock.
class FramePacer {
 public:
  void setClock(const PacerClock& clock) { m_clock = clock; }
  /// Forgets the origin: the next frame asked for sets it (it is then due at once).
  void start(Pacing pacing, std::int64_t recorded_first_ns);
  /// Waits at most `timeout_ns` for the frame at `offset_ns` after the first one to become due. True when
  /// it is due; false on timeout (nothing consumed: ask again).
  bool waitUntilDue(std::int64_t offset_ns, std::int64_t timeout_ns);
  /// The frame's exposure time: on CLOCK_MONOTONIC when paced, the recorded time otherwise [ns].
  std::int64_t exposureNs(std::int64_t offset_ns) const;

 private:
  Pacing m_pacing = Pacing::kAsFastAsPossible;
  std::int64_t m_recorded_first_ns = 0;
  std::int64_t m_origin_ns = 0;
  bool m_started = false;
  PacerClock m_clock;
  std::int64_t now() const;
  void sleepUntil(std::int64_t deadline_ns) const;
};

/// Which frame of a finite timeline comes next, optionally looping. A loop appends the timeline again,
/// shifted by its span plus one mean frame interval, so time and sequence numbers keep increasing.
class PlaybackCursor {
 public:
  void reset(int frame_count, bool loop) {
    m_count = frame_count;
    m_loop = loop;
    m_index = 0;
    m_loops = 0;
  }
  bool atEnd() const { return m_count <= 0 || (!m_loop && m_index >= m_count); }
  int index() const { return m_index; }
  std::int64_t loops() const { return m_loops; }
  void advance() {
    if (++m_index >= m_count && m_loop) {
      m_index = 0;
      ++m_loops;
    }
  }
  /// Span of one pass: last - first + (last - first) / (count - 1); a single frame repeats every
  /// `single_frame_period_ns`.
  static std::int64_t loopSpan(std::int64_t first, std::int64_t last, int count,
                               std::int64_t single_frame_period_ns) {
    return count > 1 ? (last - first) + (last - first) / (count - 1) : single_frame_period_ns;
  }

 private:
  int m_count = 0;
  bool m_loop = false;
  int m_index = 0;
  std::int64_t m_loops = 0;
};

/// Slot bookkeeping of a fixed ring (capacity fixed at compile time; the pixel buffers belong to the driver).
class SlotRing {
 public:
  static constexpr int kMaxSlots = 32;
  void reset(int slots) {
    m_slots = slots < 1 ? 1 : (slots > kMaxSlots ? kMaxSlots : slots);
    for (bool& used : m_in_use) used = false;
    m_next = 0;
  }
  int size() const { return m_slots; }
  /// A free slot (round robin), or -1 when every slot is still held by the consumer.
  int take() {
    for (int k = 0; k < m_slots; ++k) {
      const int slot = (m_next + k) % m_slots;
      if (!m_in_use[slot]) {
        m_in_use[slot] = true;
        m_next = (slot + 1) % m_slots;
        return slot;
      }
    }
    return -1;
  }
  /// False when `slot` is not a held slot (double release, foreign frame).
  bool give(int slot) {
    if (slot < 0 || slot >= m_slots || !m_in_use[slot]) return false;
    m_in_use[slot] = false;
    return true;
  }

 private:
  bool m_in_use[kMaxSlots] = {};
  int m_slots = 1;
  int m_next = 0;
};

}  // namespace visnav::camera
