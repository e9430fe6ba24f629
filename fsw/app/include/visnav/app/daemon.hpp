// visnavd's cycle: the camera, the navigation pipeline and the DDS telemetry wired to the cyclic executive.
// Per minor frame, in this fixed order:
//   acquire  camera.acquire() bounded by min([camera] acquire_timeout_ms, time left to the deadline)
//   process  pipeline.process(frame or none, now) -> NavSolution; the frame goes back to the driver
//   publish  TelemetryWriter::publishNav (PoseEstimate + FarRangeEstimate, queued for its publisher thread)
//   health   poll ModeCommands -> pipeline.command -> acknowledgment; fillHealth + the executive's task
//            timings + camera drops + cycle slips -> publishHealth; WATCHDOG=1 to systemd only when every
//            stage beat its heartbeat this cycle (heartbeat_monitor.hpp)
// Everything is sized in init(); the tasks allocate nothing, and call no dds_write: telemetry's publisher
// thread does, where Cyclone 0.10.2's own occasional allocations stay (fsw/telemetry/README.md). Events
// (mode transitions, commands, fault onsets, camera loss, slips) are logged as key=value lines
// (event_log.hpp). Design note: fsw/app/README.md.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "visnav/app/camera_factory.hpp"
#include "visnav/app/event_log.hpp"
#include "visnav/app/heartbeat_monitor.hpp"
#include "visnav/app/sd_notify.hpp"
#include "visnav/app/visnav_config.hpp"
#include "visnav/executive/executive.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"

namespace visnav::app {

/// visnavd's exit codes (fsw/app/README.md).
constexpr int kExitOk = 0;        ///< stopped by a signal, the cycle limit or the end of a playback
constexpr int kExitUsage = 2;     ///< bad command line
constexpr int kExitConfig = 3;    ///< config invalid (tables, files, calibration, model)
constexpr int kExitInit = 4;      ///< camera, pipeline, DDS or executive could not start
constexpr int kExitRealtime = 5;  ///< a realtime setting was refused and [executive] realtime_fatal is set

struct DaemonOptions {
  std::uint64_t max_cycles = 0;  ///< 0: until a stop request (or the end of a playback)
  bool simulated_clock =
      false;                 ///< simulated clock from the first frame's time; playback as fast as possible
  double pace_ms = 0.0;      ///< simulated clock: real pause before each release (ground tools keep up)
  int wait_subscribers = 0;  ///< wait for this many readers on each flight topic before the first cycle
  double wait_timeout_s = 10.0;
  std::string wait_file;  ///< with wait_subscribers: then wait for this file (a ground tool's --ready-file)
  bool apply_realtime = true;  ///< [executive] realtime settings on the run() thread
};

struct DaemonCounters {
  std::uint64_t frames = 0;                ///< cycles with a frame
  std::uint64_t first_sequence = 0;        ///< Frame::sequence of the first frame (0 before one)
  std::uint64_t last_sequence = 0;         ///< Frame::sequence of the latest frame (0 before one)
  std::uint64_t cycles_without_frame = 0;  ///< timeouts, errors, lost device (not the end of a playback)
  std::uint64_t camera_errors = 0;
  std::uint64_t commands = 0;
  std::uint64_t commands_accepted = 0;
  std::uint64_t fault_onsets = 0;
  std::uint64_t log_suppressed = 0;  ///< event lines beyond [daemon] log_throttle
  std::uint64_t watchdog_strokes =
      0;  ///< cycles every stage beat: WATCHDOG=1 was due (sent if systemd listens)
  std::uint64_t watchdog_withheld = 0;  ///< cycles a stage did not beat: no WATCHDOG=1
  std::uint64_t faults_injected = 0;    ///< stage runs failed or hung by [daemon] fault_stage (0 in flight)
  bool end_of_stream = false;
};

class Daemon final : private exec::ExecutiveObserver {
 public:
  explicit Daemon(EventLog& log) : m_log(log) {}
  ~Daemon() override;
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  /// Everything before the loop: [files], camera, pipeline, telemetry, executive, systemd socket. Logs the
  /// problem and returns its exit code (kExitOk when ready).
  int init(const VisnavConfig& config, const DaemonOptions& options);
  /// Realtime settings (on this thread), READY=1, the loop until stop, the stop summary. Exit code.
  int run();
  /// Async-signal-safe: the loop ends after the current cycle, or at once when it sleeps. `signal_number`
  /// (0: none) is named in the stop summary.
  void requestStop(int signal_number = 0) noexcept {
    m_stop_signal.store(signal_number, std::memory_order_relaxed);
    m_executive.requestStop();
  }
  /// Async-signal-safe: the next health task logs one `status` line (SIGUSR1).
  void requestStatus() noexcept { m_status_requested.store(true, std::memory_order_relaxed); }

  /// The four tasks (public so tests can drive them; init() registers them in CycleStage order).
  Status acquireTask(const exec::CycleInfo& cycle);
  Status processTask(const exec::CycleInfo& cycle);
  Status publishTask(const exec::CycleInfo& cycle);
  Status healthTask(const exec::CycleInfo& cycle);

  exec::Executive& executive() { return m_executive; }
  /// The cycle's clock (monotonic, or simulated with --simulated-clock); valid after init().
  exec::Clock& clock() { return *m_clock; }
  /// The executive's id of a stage's task (invalid before init()).
  exec::TaskId taskId(CycleStage stage) const {
    return m_task_ids[static_cast<std::size_t>(stageIndex(stage))];
  }
  const HeartbeatMonitor& heartbeat() const { return m_heartbeat; }
  const nav::NavigationPipeline& pipeline() const { return m_pipeline; }
  const camera::CameraSource& camera() const { return *m_camera.source; }
  const telemetry::TelemetryWriter& telemetryWriter() const { return m_writer; }
  bool telemetryEnabled() const { return m_telemetry_on; }
  const DaemonCounters& counters() const { return m_counters; }
  const nav::NavSolution& lastSolution() const { return m_solution; }
  const nav::HealthRecord& lastHealth() const { return m_health; }
  const SdNotifier& notifier() const { return m_notifier; }

 private:
  void onSlip(const exec::SlipEvent& event) override;
  void onTaskFailure(const exec::TaskFailureEvent& event) override;
  int initTelemetry();
  bool allowLog(std::uint64_t& reported);
  void noteCameraResult(camera::AcquireResult result);
  void logCameraEvents();
  void logTransitions();
  void logFaultOnsets(std::uint32_t faults, std::uint64_t frame);
  void endHeartbeatCycle(std::uint64_t minor_frame);
  bool injectFault(CycleStage stage, const exec::CycleInfo& cycle);
  void handleCommands();
  void logStart();
  void logStatus();
  const char* signalName() const;
  void logStopSummary(exec::StopReason reason);

  EventLog& m_log;
  VisnavConfig m_config;
  DaemonOptions m_options;
  OpenedCamera m_camera;
  nav::NavigationPipeline m_pipeline;
  std::unique_ptr<exec::Clock> m_clock;
  exec::Executive m_executive;
  std::array<exec::TaskId, kCycleStageCount> m_task_ids{};  ///< CycleStage -> the executive's task
  telemetry::Participant m_participant;
  telemetry::TelemetryWriter m_writer;
  telemetry::CommandReader m_commands;
  bool m_telemetry_on = false;
  SdNotifier m_notifier;
  HeartbeatMonitor m_heartbeat;

  // Cycle state, sized here (no allocation in the tasks).
  Frame m_frame;
  bool m_have_frame = false;
  bool m_skip_cycle = false;  ///< end of a playback: the remaining tasks of the cycle do nothing
  bool m_camera_lost = false;
  std::uint64_t m_cycles_since_frame = 0;  ///< acquire calls without a frame in a row (the stall rule)
  double m_acquire_us = 0.0;
  nav::NavSolution m_solution;
  nav::HealthRecord m_health;
  std::array<telemetry::ReceivedCommand, telemetry::kMaxCommandDepth> m_received{};
  nav::CommandAck m_last_ack;
  bool m_any_command = false;
  std::uint32_t m_previous_faults = 0;
  std::uint64_t m_transitions_logged = 0;
  std::uint64_t m_slips_seen = 0;
  std::array<std::uint64_t, nav::kFaultBitCount> m_fault_logs{};
  std::uint64_t m_camera_logs = 0;
  std::array<std::uint64_t, kCycleStageCount> m_heartbeat_logs{};
  std::array<bool, kCycleStageCount> m_heartbeat_onset_logged{};
  bool m_fault_injected_logged = false;
  DaemonCounters m_counters;
  std::atomic<int> m_stop_signal{0};
  std::atomic<bool> m_status_requested{false};
};

// Fault names for logs: visnav::faultName() beside the FaultBit enum (visnav/core/stage_interfaces.hpp).

}  // namespace visnav::app
