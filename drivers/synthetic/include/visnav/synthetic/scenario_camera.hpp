// The synthetic camera set up from a visnav-synth scenario file (tools/synth/README.md): camera, model,
// render options, seed, bit depth and trajectory all come from the file, so the daemon can run "live" on any
// shipped scenario with no hardware. A thin bridge over SyntheticCamera and the scenario loader.
#pragma once

#include <string>
#include <utility>

#include "scenario.hpp"  // tools/synth: visnav::synth::Scenario, loadScenario
#include "visnav/synthetic/synthetic_camera.hpp"

namespace visnav::synthetic {

struct ScenarioCameraOptions {
  std::string scenario_path;
  camera::Pacing pacing = camera::Pacing::kRecordedRate;
  bool loop = false;
  int ring_size = 2;
};

class ScenarioCamera final : public camera::CameraSource {
 public:
  explicit ScenarioCamera(ScenarioCameraOptions options) : m_options(std::move(options)) {}
  ScenarioCamera(const ScenarioCamera&) = delete;  // the camera points at the member trajectory
  ScenarioCamera& operator=(const ScenarioCamera&) = delete;

  /// Loads the scenario, its camera and model (errors name file, line, key), then opens the camera.
  LoadError open() override;
  camera::AcquireResult acquire(std::int64_t timeout_ns, Frame& frame) override {
    return m_camera.acquire(timeout_ns, frame);
  }
  void release(const Frame& frame) override { m_camera.release(frame); }
  bool recover() override { return false; }
  void close() override { m_camera.close(); }
  const camera::CameraCounters& counters() const override { return m_camera.counters(); }
  const char* lastError() const override { return m_camera.lastError(); }
  const char* name() const override { return "synthetic"; }

  /// Valid after open(): what the rest of the start-up needs (camera intrinsics, target model, truth poses).
  const synth::Scenario& scenario() const { return m_scenario; }
  const SyntheticCameraConfig& config() const { return m_config; }
  const SyntheticCamera& camera() const { return m_camera; }

 private:
  class Trajectory final : public PoseTrajectory {
   public:
    synth::Trajectory trajectory;
    int frameCount() const override { return trajectory.frameCount(); }
    Pose pose(int frame) const override { return trajectory.pose(frame); }
    std::int64_t timestampNs(int frame) const override { return trajectory.timestampNs(frame); }
  };

  ScenarioCameraOptions m_options;
  synth::Scenario m_scenario;
  Trajectory m_trajectory;
  SyntheticCameraConfig m_config;
  SyntheticCamera m_camera;
};

}  // namespace visnav::synthetic
