// visnav-replay's engine: the flight pipeline (fsw/navigation NavigationPipeline: modes, far range,
// acquisition, near range, Kalman filter, FDIR) over a recorded sequence as fast as the CPU allows, on the
// sequence's own timestamps (simulated clock). A library so tests run exactly what the tool runs.
#pragma once

#include <cstdint>
#include <string>

#include "visnav/core/status.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/nearrange/near_range_params.hpp"

namespace visnav::replay_tool {

struct ReplayOptions {
  std::string sequence_dir;
  std::string config_path;  ///< optional: TOML config ([nearrange] table); built-in defaults otherwise
  std::string camera_path;  ///< optional: overrides the sequence's camera
  std::string model_path;   ///< optional: overrides the sequence's model
  std::string output_csv;   ///< required
  std::string overlay_dir;  ///< optional: PNG overlays (paper fig. 3) go here
  int overlay_every = 10;   ///< every N-th frame gets an overlay
  /// How the run starts: automatic (far range, then acquisition hands over to near range by itself), from
  /// `initial_pose`, or from the sequence's first truth row (near-range accuracy runs).
  enum class Start { kAutomatic, kInitialPose, kFirstTruth };
  Start start = Start::kAutomatic;
  Pose initial_pose;
  int max_frames = -1;    ///< -1: all
  bool progress = false;  ///< progress bar on stderr
  bool timing = true;     ///< false: timing columns are 0 (byte-identical CSVs across runs)
  bool override_residual = false;
  PoseResidualMode residual = PoseResidualMode::kVertex;
};

struct ReplaySummary {
  int frames = 0;
  // The near-range tracker's verdicts (the CSV's `flags` and internals), counted in near range.
  int tracking = 0;
  int degraded = 0;
  int lost = 0;
  /// Frames whose pose the pipeline delivered as valid: the CSV rows with a pose (status tracking or
  /// degraded). Fewer than tracking + degraded where a tracked pose was withheld (too uncertain, disputed).
  int valid_poses = 0;
  int far_range = 0;    ///< frames processed in far range
  int acquisition = 0;  ///< frames processed in acquisition
  int transitions = 0;
  double median_total_us = 0.0;
  double p95_total_us = 0.0;
};

LoadError runReplay(const ReplayOptions& options, ReplaySummary& summary);

/// "x,y,z,yaw_deg,pitch_deg,roll_deg" -> pose. False on malformed text.
bool parsePoseArgument(const std::string& text, Pose& out);

}  // namespace visnav::replay_tool
