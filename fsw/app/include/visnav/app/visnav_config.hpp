// The whole run configuration of visnavd (and of visnav-params --check, visnav-replay --config): every
// parameter table of the flight software plus the daemon's own [files] and [daemon] tables, loaded from one
// TOML file by fsw/io ConfigFile (each table applied, then checkNoUnknownKeys), so a typo anywhere is an
// error naming file:line:key. One source of truth: tools that read a config read it through
// loadVisnavConfig(). Init-time only (strings, files).
#pragma once

#include <string>

#include "visnav/camera/camera_params.hpp"
#include "visnav/core/param_visitor.hpp"
#include "visnav/core/status.hpp"
#include "visnav/executive/executive_params.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::app {

/// [files]: the calibration and the target model, relative to the config file's folder.
struct FilesParams {
  std::string camera;  ///< camera intrinsics (.toml or OpenCV .yaml)
  std::string model;   ///< target model (.toml or ViSP .cao)

  template <typename Visitor>
  void visit(Visitor& v) {
    v.text({"files", "camera", "-", 0, 4095,
            "camera calibration (.toml, OpenCV .yaml), relative to the config file; required for v4l2 and "
            "libcamera; replay and synthetic take their own unless this is set"},
           camera);
    v.text({"files", "model", "-", 0, 4095,
            "target model (.toml, ViSP .cao), relative to the config file; required for v4l2 and libcamera; "
            "replay and synthetic take their own unless this is set"},
           model);
  }
  const char* crossCheck() const { return nullptr; }
};

enum class PlaybackPacing : int { kRecorded = 0, kAsFastAsPossible = 1 };

/// [daemon] fault_kind: what an injected fault does to its stage (fault injection, off by default).
enum class InjectedFault : int { kFail = 0, kHang = 1 };

/// [daemon]: how visnavd runs its camera and reports (fsw/app/README.md).
struct DaemonParams {
  int playback_pacing = static_cast<int>(PlaybackPacing::kRecorded);
  bool playback_loop = false;
  bool stop_at_end_of_stream = true;
  int log_throttle = 20;
  int camera_stall_cycles = 10;
  int fault_stage = 0;  ///< fault injection: 0 none, else 1 + stageIndex() of the stage that fails or hangs
  int fault_kind = static_cast<int>(InjectedFault::kFail);
  int fault_from_cycle = 0;

  PlaybackPacing pacing() const { return static_cast<PlaybackPacing>(playback_pacing); }
  InjectedFault faultKind() const { return static_cast<InjectedFault>(fault_kind); }

  template <typename Visitor>
  void visit(Visitor& v) {
    v.enumeration(
        {"daemon", "playback_pacing", "-", 0, 1,
         "replay and synthetic cameras on the real clock: deliver frame i at its recorded time "
         "(exposure stamped on CLOCK_MONOTONIC), or one frame per acquire at once (recorded stamps: "
         "the frame-age check then fails); the simulated clock always plays as fast as possible"},
        "recorded|as_fast_as_possible", playback_pacing);
    v.boolean({"daemon", "playback_loop", "-", 0, 1,
               "replay and synthetic cameras start over after the last frame (time keeps increasing)"},
              playback_loop);
    v.boolean({"daemon", "stop_at_end_of_stream", "-", 0, 1,
               "visnavd stops (exit code 0) when a replay or synthetic camera has no frame left; false: it "
               "keeps cycling without frames"},
              stop_at_end_of_stream);
    v.integer({"daemon", "log_throttle", "count", 0, 1000000,
               "log lines per kind of repeated event (fault onset per fault, camera errors, slips); later "
               "ones are only counted (in the stop summary)"},
              log_throttle);
    v.integer(
        {"daemon", "camera_stall_cycles", "cycles", 0, 1000000,
         "the acquire stage counts as failed (no heartbeat, so no systemd WATCHDOG=1) once the camera has "
         "delivered no frame for more than this many cycles in a row (timeouts, errors, a lost device; "
         "not the end of a playback)"},
        camera_stall_cycles);
    v.enumeration(
        {"daemon", "fault_stage", "-", 0, 4,
         "FAULT INJECTION (tests, watchdog rehearsals; none in flight): the cycle stage that fails or hangs "
         "from fault_from_cycle on; logged at start (fault_injection_armed) and at onset (fault_injected, "
         "STATUS= to systemd)"},
        "none|acquire|process|publish|health", fault_stage);
    v.enumeration({"daemon", "fault_kind", "-", 0, 1,
                   "fault injection: fail = the stage does its work but reports a failure and does not beat "
                   "its heartbeat, every cycle; hang = the stage blocks until a stop request (SIGTERM), as a "
                   "deadlocked stage would; either way no WATCHDOG=1 is sent from then on"},
                  "fail|hang", fault_kind);
    v.integer({"daemon", "fault_from_cycle", "cycles", 0, 1000000000,
               "fault injection: cycles that run normally before the injected fault starts"},
              fault_from_cycle);
  }
  const char* crossCheck() const { return nullptr; }
};

struct VisnavConfig {
  std::string path;              ///< the config file as given
  nav::PipelineParams pipeline;  ///< [navigation] [nearrange] [farrange] [acquisition] [filter]
  exec::ExecutiveParams executive;
  camera::CameraParams camera;  ///< device resolved against the config folder for replay and synthetic
  telemetry::TelemetryParams telemetry;
  FilesParams files;  ///< paths resolved against the config folder (empty: not set)
  DaemonParams daemon;
};

/// Loads and validates every table (types, ranges, cross-checks, unknown keys) and resolves the relative
/// paths. Touches no file but the config itself. On error `out` is unchanged.
LoadError loadVisnavConfig(const std::string& path, VisnavConfig& out);

/// What a run of visnavd needs beyond valid tables (a live camera needs [files] camera and model, the
/// synthetic camera a scenario), or nullptr. Tools that only read the algorithm tables skip this.
const char* runProblem(const VisnavConfig& config);

/// Loads the [files] camera and model that are set (`have_camera` / `have_model` say which were). Errors
/// name the file, line and problem.
LoadError loadConfiguredFiles(const VisnavConfig& config, CameraIntrinsics& intrinsics, bool& have_camera,
                              PolygonModel& model, bool& have_model);

/// `path` when absolute or empty, else joined to the folder of `config_path`.
std::string resolveAgainstConfig(const std::string& config_path, const std::string& path);

}  // namespace visnav::app
