#include "visnav/synthetic/synthetic_camera.hpp"

#include <cstdio>

namespace visnav::synthetic {

LoadError SyntheticCamera::open() {
  close();
  const SyntheticCameraConfig& c = m_config;
  if (c.trajectory == nullptr || c.trajectory->frameCount() < 1)
    return LoadError::failure("synthetic camera: no trajectory (or one without frames)");
  if (c.bit_depth != 8 && c.bit_depth != 16)
    return LoadError::failure("synthetic camera: bit_depth must be 8 or 16");
  if (c.max_code == 0U || (c.bit_depth == 8 && c.max_code != 255U))
    return LoadError::failure("synthetic camera: max_code must be 255 for 8 bit and >= 1 for 16 bit");
  if (c.ring_size < 1 || c.ring_size > camera::SlotRing::kMaxSlots)
    return LoadError::failure("synthetic camera: ring_size must be in [1, 32]");
  LoadError e = m_renderer.init(PinholeCamera(c.camera), c.model, c.render);
  if (!e.ok) return e;
  const auto pixels =
      static_cast<std::size_t>(c.camera.width_px) * static_cast<std::size_t>(c.camera.height_px);
  const std::size_t words = c.bit_depth == 16 ? pixels : (pixels + 1U) / 2U;
  m_slots.assign(static_cast<std::size_t>(c.ring_size), std::vector<std::uint16_t>(words));
  m_frame_count = c.trajectory->frameCount();
  const std::int64_t first = c.trajectory->timestampNs(0);
  m_loop_span_ns = camera::PlaybackCursor::loopSpan(first, c.trajectory->timestampNs(m_frame_count - 1),
                                                    m_frame_count, 200000000);
  m_ring.reset(c.ring_size);
  m_cursor.reset(m_frame_count, c.loop);
  m_pacer.start(c.pacing, first);
  m_counters = camera::CameraCounters{};
  m_error[0] = '\0';
  m_open = true;
  return LoadError::success();
}

camera::AcquireResult SyntheticCamera::fail(const char* text) {
  ++m_counters.errors;
  std::snprintf(m_error.data(), m_error.size(), "%s", text);
  return camera::AcquireResult::kError;
}

camera::AcquireResult SyntheticCamera::acquire(std::int64_t timeout_ns, Frame& frame) {
  using camera::AcquireResult;
  if (!m_open) return fail("synthetic camera: acquire() before open()");
  if (m_cursor.atEnd()) return AcquireResult::kEndOfStream;
  const PoseTrajectory& trajectory = *m_config.trajectory;
  const int index = m_cursor.index();
  const std::int64_t offset_ns =
      trajectory.timestampNs(index) - trajectory.timestampNs(0) + m_cursor.loops() * m_loop_span_ns;
  if (!m_pacer.waitUntilDue(offset_ns, timeout_ns)) {
    ++m_counters.timeouts;
    return AcquireResult::kTimeout;
  }
  const int slot = m_ring.take();
  if (slot < 0) return fail("synthetic camera: every ring slot is held (release() missing)");
  std::uint16_t* words = m_slots[static_cast<std::size_t>(slot)].data();
  const int w = m_config.camera.width_px;
  const int h = m_config.camera.height_px;
  // The same three steps as visnav-synth (tools/synth/main.cpp), so the frames are bit-identical.
  const Pose pose = trajectory.pose(index);
  const std::uint64_t frame_seed = Renderer::frameSeed(m_config.seed, static_cast<std::uint64_t>(index));
  m_renderer.setFrameIndex(index);
  frame = Frame{};
  if (m_config.bit_depth == 16) {
    m_renderer.render(pose, frame_seed, words, 2 * static_cast<std::ptrdiff_t>(w), m_config.max_code);
    frame.image = MonoImage::from16(ImageView16(words, w, h), m_config.max_code);
    frame.source_format = m_config.max_code <= 1023U   ? PixelFormat::kY10
                          : m_config.max_code <= 4095U ? PixelFormat::kY12
                                                       : PixelFormat::kY16;
  } else {
    auto* bytes = reinterpret_cast<std::uint8_t*>(words);
    m_renderer.render(pose, frame_seed, bytes, w);
    frame.image = MonoImage::from8(ImageView8(bytes, w, h));
    frame.source_format = PixelFormat::kGrey8;
  }
  frame.exposure_time_ns = m_pacer.exposureNs(offset_ns);
  frame.sequence = static_cast<std::uint64_t>(index) +
                   static_cast<std::uint64_t>(m_cursor.loops()) * static_cast<std::uint64_t>(m_frame_count);
  frame.buffer_index = slot;
  ++m_counters.frames_delivered;
  m_cursor.advance();
  return AcquireResult::kFrame;
}

void SyntheticCamera::release(const Frame& frame) {
  if (!m_ring.give(frame.buffer_index)) {
    ++m_counters.errors;
    std::snprintf(m_error.data(), m_error.size(), "synthetic camera: release() of a frame not held (slot %d)",
                  frame.buffer_index);
  }
}

int SyntheticCamera::trajectoryFrame(std::uint64_t sequence) const {
  return m_frame_count > 0 ? static_cast<int>(sequence % static_cast<std::uint64_t>(m_frame_count)) : 0;
}

void SyntheticCamera::close() {
  m_open = false;
  m_slots.clear();
}

}  // namespace visnav::synthetic
