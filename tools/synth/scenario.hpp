// Synthetic scenarios for visnav-synth: camera, model, render options and a trajectory (format and every key
// with its unit: tools/synth/README.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/replay/toml_reader.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::synth {

/// Frame i sits at distance d_start + i * step (towards d_end), with sinusoidal lateral offsets and attitude
/// oscillations (amp * sin(2 pi i / period)) around a base attitude, optionally tumbling at a constant body
/// rate: R_c_m(i) = R_ypr(base + oscillation(i)) * exp(i * tumble_rate) (rate vector in the model frame).
struct Trajectory {
  double d_start_m = 25.0;
  double d_end_m = 5.0;
  double step_m = 0.01;
  /// > 0: geometric steps instead, d(i) = d_start (1 -/+ step_rel)^i (constant time-to-go approach).
  double step_rel = 0.0;
  double rate_hz = 5.0;
  double base_yaw_deg = 0.0;
  double base_pitch_deg = 0.0;
  double base_roll_deg = 180.0;  ///< flips the model's +z normal onto -z_c, i.e. towards the camera
  double lateral_x_amp_m = 0.0;
  double lateral_x_period_frames = 1000.0;
  double lateral_y_amp_m = 0.0;
  double lateral_y_period_frames = 1000.0;
  /// Angular lateral offsets (far range: the target wanders over the image at every distance):
  /// x(i) += distance * tan(amp * sin(2 pi i / lateral_x_period_frames)), likewise y.
  double lateral_x_amp_deg = 0.0;
  double lateral_y_amp_deg = 0.0;
  double yaw_amp_deg = 0.0;
  double yaw_period_frames = 1000.0;
  double pitch_amp_deg = 0.0;
  double pitch_period_frames = 1000.0;
  double roll_amp_deg = 0.0;
  double roll_period_frames = 1000.0;
  Vec3 tumble_rate_deg_per_frame = Vec3::Zero();

  int frameCount() const;
  Pose pose(int frame) const;
  std::int64_t timestampNs(int frame) const;
};

struct Scenario {
  std::string name;
  std::string path;         ///< the scenario file
  std::string camera_path;  ///< resolved relative to the scenario file's directory
  std::string model_path;
  std::uint64_t seed = 1;
  int bit_depth = 8;
  std::uint16_t max_code = 255;
  Trajectory trajectory;
  synthetic::RenderOptions render;
};

/// [render.barN] / [render.glintN] tables (N = 1..8) into o.bars / o.glints (scenario_clutter.cpp).
void readDynamicClutter(replay::TomlReader& r, synthetic::RenderOptions& o);

/// Writes DIR/clutter.csv (frame,bars_in_view,glints_in_view) for the rendered frames when the scenario has
/// per-frame clutter; nothing otherwise. "In view": the object's centre lies within the image grown by its
/// half length (bars) or 3 sigma (glints). Spots with peak < 0.5 are stars and not counted as glints.
LoadError writeClutterCsv(const std::string& directory, const synthetic::RenderOptions& o,
                          const std::vector<int>& frames, int width_px, int height_px);

/// Strict: unknown keys, wrong types and out-of-range values are errors naming file, line and key.
LoadError loadScenario(const std::string& path, Scenario& out);

}  // namespace visnav::synth
