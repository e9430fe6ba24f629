// Runs the whole flight pipeline (nav::NavigationPipeline, as visnavd and visnav-replay run it) over one
// scene in memory: render frame i -> process -> compare with the truth, and the scene's summary.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "visnav/campaign/classify.hpp"
#include "visnav/campaign/scene.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"

namespace visnav::campaign {

struct TransitionRecord {
  int frame = 0;
  nav::NavMode from = nav::NavMode::kStandby;
  nav::NavMode to = nav::NavMode::kStandby;
  std::string reason;
};

struct SceneResult {
  LoadError error;  ///< renderer or pipeline init failed (the scene did not run)
  std::vector<FrameOutcome> frames;
  std::vector<RecoveryEvent> events;
  std::vector<TransitionRecord> transitions;  ///< during the run (the start command's own not included)
  int mode_changes = 0;                       ///< transitionCount() at the end minus after the start
  // Summary (summariseScene).
  int visible = 0;
  int expected = 0;                ///< denominator of the fractions
  int tracked = 0;                 ///< tracked among the expected frames
  int accurate = 0;                ///< accurate among the expected frames
  int wrong = 0;                   ///< confidently wrong frames (any frame with a valid pose)
  int pose_frames = 0;             ///< frames with pose_valid
  double tracked_fraction = -1.0;  ///< tracked / expected; -1 when nothing was expected
  double accurate_fraction = -1.0;
  int recovery_never = 0;
  int recovery_max = -1;         ///< largest latency of the events that recovered (-1: none)
  int acquisition_latency = -2;  ///< approach: first expected frame to the first tracked; -1 never; -2 n/a
  double max_position_error_rel = 0.0;  ///< over the frames with a valid pose
  double max_attitude_error_deg = 0.0;
  int nis_count = 0;
  double nis_mean = 0.0;
  int far_fixes = 0;       ///< far-range fixes on frames with the target in view (targetInView)
  int far_off_target = 0;  ///< of them, on something else (FrameOutcome::far_off_target)
  double wall_s = 0.0;     ///< timing field
  std::string trace;       ///< --trace: one line per frame (traceLine), empty otherwise
};

/// Counts, fractions, recovery events and acquisition latency from the classified frames. Approach scenes
/// expect a 6-DOF pose only where t_c_m.z <= th.near_range_max_m (far range delivers none before the
/// hand-over by design); near scenes on every visible frame.
void summariseScene(const Scene& scene, const Thresholds& th, SceneResult& result);

/// Runs the scene. `base` is the pipeline configuration (defaults or --config); the scene sets its far-range
/// gamma. `timing`: CLOCK_MONOTONIC step times (off: all timing fields 0). `oracle`: FrameOutcome::oracle
/// on every visible frame without a valid pose (`trace` computes it too). `dump_dir` (not empty): every
/// rendered frame is also written there as an 8-bit PGM, `<family>-<seed>-<frame>.pgm` (frame zero-padded
/// to 4 digits), to look at what a trace describes; a write that fails is the scene's error.
SceneResult runScene(const Scene& scene, const nav::PipelineParams& base, bool timing,
                     const Thresholds& th = {}, bool trace = false, bool oracle = false,
                     const std::string& dump_dir = {});

/// --trace's line for one frame: truth range, mode, near-range status, flags, line and point counts, rms,
/// filter NIS, fault bits and the pose error; what a reader needs to see why a frame went wrong.
std::string traceLine(const FrameOutcome& f, const NearRangeResult& near, const nav::FilterUpdate& update);

}  // namespace visnav::campaign
