// visnav-closedloop's scenario: where the chaser starts, how the target tumbles, the chaser's limits and the
// guidance gains (tools/closedloop/README.md). Three presets: "ci" (60 m, the CI gate), "200" and "750".
#pragma once

#include <string>

namespace visnav::closedloop {

struct ScenarioParams {
  std::string name = "200";
  double start_range_m = 200.0;
  double start_offset_deg = 8.0;    ///< chaser's start direction off the target's spin axis
  double start_pointing_deg = 2.0;  ///< initial boresight error (target still in the field of view)
  double tumble_rate_deg_s = 1.0;   ///< target spin about a world-fixed axis
  double nutation_deg = 10.0;       ///< angle between that axis and the face normal (the hold point circles)
  double hold_distance_m = 5.0;     ///< hold point on the face normal
  double frame_rate_hz = 5.0;       ///< camera and guidance rate
  int physics_substeps = 10;        ///< dynamics integration steps per frame (commands held)
  double max_time_s = 900.0;        ///< give up after this long
  double hold_window_s = 30.0;      ///< arrived = inside the gates continuously for this long
  double gate_position_m = 0.10;
  double gate_attitude_deg = 2.0;
  // Chaser limits: a double integrator in translation, rate- and acceleration-limited in attitude.
  double accel_max_m_s2 = 0.05;
  double rate_max_deg_s = 2.0;
  double angular_accel_max_deg_s2 = 0.5;
  // Guidance.
  double far_speed_max_m_s = 2.0;  ///< line-of-sight approach: closing speed cap
  double far_gain_1_s = 0.05;      ///< closing speed = gain * (range - stage range)
  double stage_range_m = 20.0;     ///< far range brings the chaser to here (acquisition takes over < 30 m)
  double near_speed_max_m_s = 0.5;
  double near_gain_1_s = 0.1;      ///< position loop of the final approach and hold
  double velocity_gain_1_s = 0.3;  ///< inner velocity loop
  double attitude_gain_1_s = 0.5;
  int near_frames_to_switch = 3;  ///< near-range poses in a row before the 6-DOF guidance takes over
  unsigned long long seed = 12;   ///< renderer noise
  std::string config_path;        ///< visnav config (gamma for the plate, filter noise)
  std::string camera_path;
  std::string model_path;
};

/// The preset `name` ("ci", "200", "750") with its files in `config_dir` (closedloop.toml,
/// cameras/vga_6mm.toml, models/plate_2300x1800.toml). False for an unknown name.
bool presetScenario(const std::string& name, const std::string& config_dir, ScenarioParams& out);

}  // namespace visnav::closedloop
