// The synthetic renderer as a live CameraSource: frame i of a trajectory is rendered exactly as visnav-synth
// renders it (same pose, same per-frame seed, same clutter frame index), so a frame is bit-identical to the
// PGM visnav-synth writes for it. Paced at the trajectory's timestamps on CLOCK_MONOTONIC, or as fast as the
// consumer asks; optionally looping. open() allocates the renderer and the frame ring; acquire() renders into
// a free slot (a VGA frame takes 8-15 ms: the cost of a "live" synthetic camera) and allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "visnav/camera/camera_source.hpp"
#include "visnav/camera/playback.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::synthetic {

/// Where the target is in frame i (e.g. a visnav-synth scenario trajectory).
class PoseTrajectory {
 public:
  virtual ~PoseTrajectory() = default;
  virtual int frameCount() const = 0;
  virtual Pose pose(int frame) const = 0;                 ///< T_c_m
  virtual std::int64_t timestampNs(int frame) const = 0;  ///< strictly increasing
};

struct SyntheticCameraConfig {
  CameraIntrinsics camera;
  PolygonModel model;
  RenderOptions render;
  const PoseTrajectory* trajectory = nullptr;  ///< must outlive the camera
  std::uint64_t seed = 1;                      ///< scenario seed; frame seed = Renderer::frameSeed(seed, i)
  int bit_depth = 8;                           ///< 8 or 16
  std::uint16_t max_code = 255;
  camera::Pacing pacing = camera::Pacing::kRecordedRate;
  bool loop = false;
  int ring_size = 2;
};

class SyntheticCamera final : public camera::CameraSource {
 public:
  /// Init time: what open() will set up (copies the config).
  void configure(const SyntheticCameraConfig& config) { m_config = config; }

  LoadError open() override;
  camera::AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) override;
  void release(const Frame& frame) override;
  bool recover() override { return false; }
  void close() override;
  const camera::CameraCounters& counters() const override { return m_counters; }
  const char* lastError() const override { return m_error.data(); }
  const char* name() const override { return "synthetic"; }

  /// Trajectory frame index of the frame with this Frame::sequence (loops repeat the trajectory).
  int trajectoryFrame(std::uint64_t sequence) const;

 private:
  camera::AcquireResult fail(const char* text);

  SyntheticCameraConfig m_config;
  Renderer m_renderer;
  std::vector<std::vector<std::uint16_t>> m_slots;  // 16-bit words: 8-bit frames use the bytes
  camera::SlotRing m_ring;
  camera::PlaybackCursor m_cursor;
  camera::FramePacer m_pacer;
  std::int64_t m_loop_span_ns = 0;
  int m_frame_count = 0;
  camera::CameraCounters m_counters;
  std::array<char, 160> m_error{};
  bool m_open = false;
};

}  // namespace visnav::synthetic
