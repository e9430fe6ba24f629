// One closed-loop run: renderer -> libvisnav (C ABI) -> estimator -> guidance -> chaser, frame by frame, or
// the same guidance fed the true relative state (the reference). Per-frame log and the run's figures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/closedloop/scenario.hpp"
#include "visnav/core/status.hpp"

namespace visnav::closedloop {

struct FrameLog {
  double t_s = 0.0;
  double range_m = 0.0;             ///< true distance chaser - target centre
  double position_error_m = 0.0;    ///< true distance to the hold point
  double attitude_error_deg = 0.0;  ///< true attitude error at the hold attitude (mod the plate's symmetry)
  double estimate_error_m = 0.0;    ///< |estimated - true chaser position| (0 when no estimate)
  double delta_v_m_s = 0.0;         ///< spent so far
  int mode = 0;                     ///< visnav mode (visnav_mode; the reference run logs -1)
  int track_status = 0;
  int phase = 0;  ///< guidance Phase
};

struct RunResult {
  std::string label;  ///< "visnav" or "truth"
  std::vector<FrameLog> frames;
  bool arrived = false;
  double arrival_time_s = -1.0;
  double arrival_delta_v_m_s = 0.0;
  double final_position_error_m = 0.0;  ///< at the end of the run
  double final_attitude_error_deg = 0.0;
  double hold_max_position_error_m = 0.0;  ///< worst over the hold window
  double hold_max_attitude_error_deg = 0.0;
  double total_delta_v_m_s = 0.0;
  int estimator_rejections = 0;
  std::string ended;  ///< why the run stopped
};

/// use_visnav false: the guidance gets the truth (no rendering, no visnav).
LoadError runClosedLoop(const ScenarioParams& params, bool use_visnav, RunResult& out);

}  // namespace visnav::closedloop
