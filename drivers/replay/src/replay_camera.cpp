#include "visnav/replay/replay_camera.hpp"

#include <cstdio>
#include <cstring>
#include <utility>

namespace visnav::replay {
namespace {

PixelFormat formatOf(std::uint16_t max_code) {
  if (max_code <= 255U) return PixelFormat::kGrey8;
  if (max_code <= 1023U) return PixelFormat::kY10;
  if (max_code <= 4095U) return PixelFormat::kY12;
  return PixelFormat::kY16;
}

}  // namespace

LoadError ReplayCamera::open() {
  close();
  if (m_options.ring_size < 1 || m_options.ring_size > camera::SlotRing::kMaxSlots)
    return LoadError::failure("replay camera: ring_size must be in [1, 32]");
  Sequence sequence;
  LoadError e = loadSequence(m_options.directory, sequence);
  if (!e.ok) return e;
  if (sequence.frames.empty())
    return LoadError::failure(m_options.directory + ": the sequence has no frames");
  const auto width = static_cast<std::size_t>(sequence.camera.width_px);
  const auto height = static_cast<std::size_t>(sequence.camera.height_px);
  m_slot_bytes = width * height * (sequence.bit_depth == 16 ? 2U : 1U);
  m_slots.assign(static_cast<std::size_t>(m_options.ring_size),
                 std::vector<std::uint16_t>((m_slot_bytes + 1U) / 2U));
  m_sequence = std::move(sequence);
  m_format = formatOf(m_sequence.max_code);
  const std::vector<FrameEntry>& frames = m_sequence.frames;
  const int count = static_cast<int>(frames.size());
  m_loop_span_ns =
      camera::PlaybackCursor::loopSpan(frames.front().timestamp_ns, frames.back().timestamp_ns, count,
                                       static_cast<std::int64_t>(1e9 / m_sequence.rate_hz));
  m_sequence_span = frames.back().frame - frames.front().frame + 1;
  m_ring.reset(m_options.ring_size);
  m_cursor.reset(count, m_options.loop);
  m_pacer.start(m_options.pacing, frames.front().timestamp_ns);
  m_counters = camera::CameraCounters{};
  m_error[0] = '\0';
  m_open = true;
  return LoadError::success();
}

camera::AcquireResult ReplayCamera::fail(camera::AcquireResult result, const char* text) {
  ++m_counters.errors;
  std::snprintf(m_error.data(), m_error.size(), "%s", text);
  return result;
}

camera::AcquireResult ReplayCamera::acquire(std::int64_t timeout_ns, Frame& frame) {
  using camera::AcquireResult;
  if (!m_open) return fail(AcquireResult::kError, "replay camera: acquire() before open()");
  if (m_cursor.atEnd()) return AcquireResult::kEndOfStream;
  const FrameEntry& entry = m_sequence.frames[static_cast<std::size_t>(m_cursor.index())];
  const std::int64_t offset_ns =
      entry.timestamp_ns - m_sequence.frames.front().timestamp_ns + m_cursor.loops() * m_loop_span_ns;
  if (!m_pacer.waitUntilDue(offset_ns, timeout_ns)) {
    ++m_counters.timeouts;
    return AcquireResult::kTimeout;
  }
  const int slot = m_ring.take();
  if (slot < 0)
    return fail(AcquireResult::kError, "replay camera: every ring slot is held (release() missing)");
  auto* pixels = reinterpret_cast<std::uint8_t*>(m_slots[static_cast<std::size_t>(slot)].data());
  int width = 0;
  int height = 0;
  int maxval = 0;
  const LoadError e = readPgm(entry.file, pixels, m_slot_bytes, width, height, maxval, m_sequence.max_code);
  const bool wrong_size = e.ok && (width != m_sequence.camera.width_px ||
                                   height != m_sequence.camera.height_px || maxval != m_sequence.max_code);
  if (!e.ok || wrong_size) {
    m_ring.give(slot);
    m_cursor.advance();  // a bad file is skipped, not retried forever
    return fail(AcquireResult::kError, e.ok ? "replay camera: frame size or maxval differs from the sequence"
                                            : e.message.c_str());  // error path only: readPgm built a string
  }
  frame = Frame{};
  if (m_sequence.bit_depth == 16) {
    frame.image = MonoImage::from16(
        ImageView16(m_slots[static_cast<std::size_t>(slot)].data(), width, height), m_sequence.max_code);
  } else {
    frame.image = MonoImage::from8(ImageView8(pixels, width, height));
  }
  frame.exposure_time_ns = m_pacer.exposureNs(offset_ns);
  frame.sequence = static_cast<std::uint64_t>(entry.frame + m_cursor.loops() * m_sequence_span);
  frame.source_format = m_format;
  frame.buffer_index = slot;
  ++m_counters.frames_delivered;
  m_cursor.advance();
  return AcquireResult::kFrame;
}

void ReplayCamera::release(const Frame& frame) {
  if (!m_ring.give(frame.buffer_index)) {
    ++m_counters.errors;
    std::snprintf(m_error.data(), m_error.size(), "replay camera: release() of a frame not held (slot %d)",
                  frame.buffer_index);
  }
}

void ReplayCamera::close() {
  m_open = false;
  m_slots.clear();
}

}  // namespace visnav::replay
