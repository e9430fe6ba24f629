// A recorded sequence directory (drivers/replay/README.md) as a CameraSource: at its recorded rate
// (timestamps of frames.csv, on CLOCK_MONOTONIC) or as fast as the consumer asks, optionally looping.
// open() loads the sequence and allocates the ring of frame buffers; acquire() reads the next PGM into a free
// slot with blocking file I/O and allocates nothing. Replay only: a VGA frame from the page cache takes
// ~26 us (bench_playback), a cold disk can take milliseconds; nothing is prefetched.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "visnav/camera/camera_source.hpp"
#include "visnav/camera/playback.hpp"
#include "visnav/replay/sequence.hpp"

namespace visnav::replay {

struct ReplayCameraOptions {
  std::string directory;  ///< the sequence directory
  camera::Pacing pacing = camera::Pacing::kRecordedRate;
  bool loop = false;  ///< start over after the last frame (else end of stream)
  int ring_size = 2;  ///< frame buffers (2..32); one is enough if each frame
                      ///< is released before the next acquire()
};

class ReplayCamera final : public camera::CameraSource {
 public:
  /// The pacing's time source (default CLOCK_MONOTONIC): tests inject a simulated one.
  void setPacerClock(const camera::PacerClock& clock) { m_pacer.setClock(clock); }
  explicit ReplayCamera(ReplayCameraOptions options) : m_options(std::move(options)) {}

  LoadError open() override;
  /// Next frame of the sequence: waits for it (paced) at most timeout_ns; kEndOfStream after the last one
  /// (not looping); kError when a frame file is unreadable or no ring slot is free.
  camera::AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) override;
  void release(const Frame& frame) override;
  /// Files do not disappear and come back: nothing to recover.
  bool recover() override { return false; }
  void close() override;
  const camera::CameraCounters& counters() const override { return m_counters; }
  const char* lastError() const override { return m_error.data(); }
  const char* name() const override { return "replay"; }

  /// The loaded sequence (camera, model, truth) for the rest of the start-up; valid after open().
  const Sequence& sequence() const { return m_sequence; }

 private:
  camera::AcquireResult fail(camera::AcquireResult result, const char* text);

  ReplayCameraOptions m_options;
  Sequence m_sequence;
  std::vector<std::vector<std::uint16_t>> m_slots;  // 16-bit words so 16-bit views are aligned
  std::size_t m_slot_bytes = 0;
  camera::SlotRing m_ring;
  camera::PlaybackCursor m_cursor;
  camera::FramePacer m_pacer;
  std::int64_t m_loop_span_ns = 0;
  std::int64_t m_sequence_span = 0;
  PixelFormat m_format = PixelFormat::kGrey8;
  camera::CameraCounters m_counters;
  std::array<char, 256> m_error{};
  bool m_open = false;
};

}  // namespace visnav::replay
