// Daemon set-up, the loop and its start and stop summaries; the four cycle tasks are in daemon_tasks.cpp.
#include "visnav/app/daemon.hpp"

#include <array>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <utility>

#include "visnav/app/paced_clock.hpp"
#include "visnav/executive/realtime.hpp"

namespace visnav::app {
namespace {

constexpr std::int64_t kDiscoverySettleNs = 500'000'000;  // reader side of a new match (see initTelemetry)
constexpr std::int64_t kFinalAckWaitNs = 2'000'000'000;   // readers acknowledge the last samples

template <Status (Daemon::*Task)(const exec::CycleInfo&)>
Status runTask(void* daemon, const exec::CycleInfo& cycle) {
  return (static_cast<Daemon*>(daemon)->*Task)(cycle);
}

/// The task of each cycle stage, in CycleStage order (the order the executive runs them).
struct StageTask {
  CycleStage stage;
  exec::TaskFn fn;
};
constexpr std::array<StageTask, kCycleStageCount> kStageTasks = {{
    {CycleStage::kAcquire, &runTask<&Daemon::acquireTask>},
    {CycleStage::kProcess, &runTask<&Daemon::processTask>},
    {CycleStage::kPublish, &runTask<&Daemon::publishTask>},
    {CycleStage::kHealth, &runTask<&Daemon::healthTask>},
}};

double us(std::int64_t ns) { return static_cast<double>(ns) * 1e-3; }

const char* stopReasonName(exec::StopReason reason, bool end_of_stream) {
  if (end_of_stream) return "end_of_stream";
  switch (reason) {
    case exec::StopReason::kStopRequested: return "stop_request";
    case exec::StopReason::kCycleLimit: return "cycle_limit";
    case exec::StopReason::kNotRun: return "not_run";
  }
  return "unknown";
}

}  // namespace

Daemon::~Daemon() {
  if (m_camera.source) m_camera.source->close();
}

int Daemon::init(const VisnavConfig& config, const DaemonOptions& options) {
  m_config = config;
  m_options = options;
  CameraIntrinsics file_camera;
  PolygonModel file_model;
  bool have_file_camera = false;
  bool have_file_model = false;
  if (const char* problem = runProblem(config)) {
    m_log.event(LogLevel::kError, "config_invalid", "message=\"%s: %s\"", config.path.c_str(), problem);
    return kExitConfig;
  }
  if (LoadError e = loadConfiguredFiles(config, file_camera, have_file_camera, file_model, have_file_model);
      !e.ok) {
    m_log.event(LogLevel::kError, "config_invalid", "message=\"%s\"", e.message.c_str());
    return kExitConfig;
  }
  if (LoadError e = openCamera(config, options.simulated_clock, m_camera); !e.ok) {
    m_log.event(LogLevel::kError, "init_failed", "stage=camera message=\"%s\"", e.message.c_str());
    return kExitInit;
  }
  if (have_file_camera) {
    if (m_camera.playback && (file_camera.width_px != m_camera.intrinsics.width_px ||
                              file_camera.height_px != m_camera.intrinsics.height_px)) {
      m_log.event(LogLevel::kError, "config_invalid",
                  "message=\"[files] camera %s is %dx%d but the camera delivers %dx%d frames\"",
                  config.files.camera.c_str(), file_camera.width_px, file_camera.height_px,
                  m_camera.intrinsics.width_px, m_camera.intrinsics.height_px);
      return kExitConfig;
    }
    m_camera.intrinsics = file_camera;
  }
  if (have_file_model) m_camera.model = file_model;
  if (LoadError e = m_pipeline.init(PinholeCamera(m_camera.intrinsics), m_camera.model, config.pipeline);
      !e.ok) {
    m_log.event(LogLevel::kError, "init_failed", "stage=pipeline message=\"%s\"", e.message.c_str());
    return kExitInit;
  }
  // Replay on the simulated clock reports zero stage timings, as visnav-replay does (bit-identical output).
  m_pipeline.setClock(options.simulated_clock ? nullptr : &exec::monotonicNowNs);
  m_pipeline.setNominalFramePeriodNs(static_cast<std::int64_t>(1e9 / config.camera.fps_hz));
  if (options.simulated_clock) {
    auto clock = std::make_unique<PacedSimulatedClock>(m_camera.first_timestamp_ns,
                                                       static_cast<std::int64_t>(options.pace_ms * 1e6));
    clock->simulated().applyParams(config.executive);
    m_clock = std::move(clock);
  } else {
    m_clock = std::make_unique<exec::MonotonicClock>();
  }
  LoadError e = m_executive.init(config.executive, *m_clock);
  m_heartbeat.reset();
  for (const StageTask& task : kStageTasks) {
    if (!e.ok) break;
    const auto i = static_cast<std::size_t>(stageIndex(task.stage));
    e = m_executive.addTask(m_task_ids[i], stageName(task.stage), task.fn, this);
    m_heartbeat.registerStage(task.stage);
  }
  if (!e.ok) {
    m_log.event(LogLevel::kError, "init_failed", "stage=executive message=\"%s\"", e.message.c_str());
    return kExitInit;
  }
  m_executive.setObserver(this);
  if (const int code = initTelemetry(); code != kExitOk) return code;
  if (LoadError n = m_notifier.initFromEnvironment(); !n.ok)
    m_log.event(LogLevel::kWarning, "systemd_notify_unavailable", "message=\"%s\"", n.message.c_str());
  m_pipeline.fillHealth(m_health);
  m_last_ack = m_health.last_command;
  m_transitions_logged = m_pipeline.modes().transitionCount();
  // Last: a live camera's stream starts now, not before DDS discovery and the subscriber wait.
  if (LoadError started = startLiveCamera(config, m_camera); !started.ok) {
    m_log.event(LogLevel::kError, "init_failed", "stage=camera message=\"%s\"", started.message.c_str());
    return kExitInit;
  }
  return kExitOk;
}

int Daemon::initTelemetry() {
  const telemetry::TelemetryParams& params = m_config.telemetry;
  m_telemetry_on = params.enabled;
  if (!m_telemetry_on) return kExitOk;
  LoadError e = m_participant.init(params);  // domain, partition, naming
  if (e.ok) e = m_writer.init(m_participant, params, m_executive.minorPeriodNs());
  if (e.ok) e = m_commands.init(m_participant, params);
  if (!e.ok) {
    m_log.event(LogLevel::kError, "init_failed", "stage=telemetry message=\"%s\"", e.message.c_str());
    return kExitInit;
  }
  if (m_options.wait_subscribers <= 0) return kExitOk;
  const auto timeout_ns = static_cast<std::int64_t>(m_options.wait_timeout_s * 1e9);
  telemetry::Topic missing = telemetry::Topic::kPose;
  if (!m_writer.waitForReaders(static_cast<std::uint32_t>(m_options.wait_subscribers), timeout_ns, missing)) {
    m_log.event(LogLevel::kError, "init_failed",
                "stage=telemetry message=\"fewer than %d readers on %s within %.1f s\"",
                m_options.wait_subscribers, telemetry::topicName(missing, params.naming),
                m_options.wait_timeout_s);
    return kExitInit;
  }
  // The writer sees the match first; the reader drops data from a writer it has not matched yet, and a
  // keep-last-1 writer may no longer hold that sample for a retransmission. The reader's ready file closes
  // the gap exactly; without one, a short pause closes it in practice.
  if (!m_options.wait_file.empty()) {
    if (!telemetry::waitForFile(m_options.wait_file.c_str(), timeout_ns)) {
      m_log.event(LogLevel::kError, "init_failed",
                  "stage=telemetry message=\"no ready file %s within %.1f s\"", m_options.wait_file.c_str(),
                  m_options.wait_timeout_s);
      return kExitInit;
    }
  } else {
    const timespec settle{0, kDiscoverySettleNs};
    nanosleep(&settle, nullptr);
  }
  m_log.event(LogLevel::kInfo, "subscribers_matched", "readers=%d", m_options.wait_subscribers);
  return kExitOk;
}

void Daemon::logStart() {
  const CameraIntrinsics& k = m_camera.intrinsics;
  m_log.event(LogLevel::kNotice, "start",
              "config=\"%s\" camera=%s device=\"%s\" image=%dx%d clock=%s major_frame_hz=%g minor_frames=%d "
              "mode=%s telemetry=%s domain=%d partition=%s naming=%s systemd=%s watchdog_usec=%" PRIu64
              " journald=%s",
              m_config.path.c_str(), m_camera.source->name(), m_config.camera.device.c_str(), k.width_px,
              k.height_px, m_options.simulated_clock ? "simulated" : "monotonic",
              m_config.executive.major_frame_hz, m_config.executive.minor_frames_per_major,
              nav::toString(m_pipeline.mode()), m_telemetry_on ? "on" : "off", m_config.telemetry.domain_id,
              m_config.telemetry.naming == telemetry::TopicNaming::kRos2 ? "none"
                                                                         : m_config.telemetry.partitionName(),
              telemetry::namingName(m_config.telemetry.naming), m_notifier.active() ? "yes" : "no",
              m_notifier.watchdogUsec(), m_log.journal() ? "yes" : "no");
}

int Daemon::run() {
  if (m_options.apply_realtime) {
    exec::RealtimeReport report;
    const LoadError e = exec::applyRealtimeSettings(m_config.executive, report);
    const std::pair<const char*, const exec::RealtimeOutcome*> outcomes[] = {
        {"scheduler", &report.scheduler},
        {"affinity", &report.affinity},
        {"memory_lock", &report.memory_lock},
        {"timer_slack", &report.timer_slack}};
    for (const auto& [name, outcome] : outcomes) {
      if (!outcome->requested) continue;
      std::array<char, 256> message{};
      m_log.event(outcome->applied ? LogLevel::kInfo : LogLevel::kWarning, "realtime",
                  "setting=%s applied=%s message=\"%s\"", name, outcome->applied ? "yes" : "no",
                  quotable(outcome->message.data(), message));
    }
    if (!e.ok) {
      m_log.event(LogLevel::kError, "init_failed", "stage=realtime message=\"%s\"", e.message.c_str());
      return kExitRealtime;
    }
  }
  logStart();
  if (m_config.daemon.fault_stage != 0)
    m_log.event(LogLevel::kWarning, "fault_injection_armed", "stage=%s kind=%s from_cycle=%d",
                stageName(static_cast<CycleStage>(m_config.daemon.fault_stage - 1)),
                m_config.daemon.faultKind() == InjectedFault::kHang ? "hang" : "fail",
                m_config.daemon.fault_from_cycle);
  char status[96];
  std::snprintf(status, sizeof(status), "running, mode %s", nav::toString(m_pipeline.mode()));
  m_notifier.ready(status);
  const exec::StopReason reason = m_executive.run(m_options.max_cycles);
  m_notifier.stopping();
  if (m_telemetry_on) {  // the queue written, the last samples acknowledged, before the participant goes
    m_writer.waitForAcks(kFinalAckWaitNs);
    m_writer.stop();  // joins the publisher thread: the stop line's counts are final
  }
  logStopSummary(reason);
  return kExitOk;
}

void Daemon::logStopSummary(exec::StopReason reason) {
  const exec::ExecutiveCounters& c = m_executive.counters();
  const camera::CameraCounters& cam = m_camera.source->counters();
  const telemetry::WriterCounters w = m_writer.counters();
  std::array<char, 160> misses{};  // "acquire:0,process:0,publish:0,health:0": cycles each stage did not beat
  std::size_t used = 0;
  for (int i = 0; i < kCycleStageCount && used < misses.size(); ++i) {
    const auto stage = static_cast<CycleStage>(i);
    const int n = std::snprintf(misses.data() + used, misses.size() - used, "%s%s:%" PRIu64, i > 0 ? "," : "",
                                stageName(stage), m_heartbeat.stage(stage).missed);
    if (n < 0) break;
    used += static_cast<std::size_t>(n);
  }
  m_log.event(
      LogLevel::kNotice, "stop",
      "reason=%s cycles=%" PRIu64 " frames=%" PRIu64 " cycles_without_frame=%" PRIu64
      " camera_dropped=%" PRIu64 " camera_timeouts=%" PRIu64 " camera_errors=%" PRIu64
      " first_sequence=%" PRIu64 " last_sequence=%" PRIu64 " slips=%" PRIu64 " releases_skipped=%" PRIu64
      " worst_overrun_ms=%.3f task_failures=%" PRIu64 " mode=%s transitions=%" PRIu64 " commands=%" PRIu64
      " commands_accepted=%" PRIu64 " fault_onsets=%" PRIu64 " samples_queued=%" PRIu64
      " samples_dropped=%" PRIu64 " samples_written=%" PRIu64 " write_failures=%" PRIu64
      " sample_pool_misses=%" PRIu64 " watchdog_notifications=%" PRIu64 " watchdog_withheld=%" PRIu64
      " heartbeat_misses=%s faults_injected=%" PRIu64 " log_suppressed=%" PRIu64 " log_dropped=%" PRIu64
      " signal=%s elapsed_s=%.3f",
      stopReasonName(reason, m_counters.end_of_stream), c.cycles, m_counters.frames,
      m_counters.cycles_without_frame, cam.frames_dropped, cam.timeouts, cam.errors,
      m_counters.first_sequence, m_counters.last_sequence, c.slips, c.releases_skipped,
      static_cast<double>(c.worst_overrun_ns) * 1e-6, c.task_failures, nav::toString(m_pipeline.mode()),
      m_pipeline.modes().transitionCount(), m_counters.commands, m_counters.commands_accepted,
      m_counters.fault_onsets, w.samples_queued, w.samples_dropped, w.samples_written, w.write_failures,
      m_writer.samplePoolMisses(), m_notifier.sent(), m_counters.watchdog_withheld, misses.data(),
      m_counters.faults_injected, m_counters.log_suppressed + c.events_suppressed, m_log.droppedLines(),
      signalName(), m_log.elapsedS());
  const exec::DurationStats& jitter = m_executive.releaseJitter();
  const exec::DurationStats& busy = m_executive.cycleBusy();
  const exec::DurationStats& acquire = m_executive.taskStats(taskId(CycleStage::kAcquire)).exec;
  const exec::DurationStats& process = m_executive.taskStats(taskId(CycleStage::kProcess)).exec;
  const exec::DurationStats& publish = m_executive.taskStats(taskId(CycleStage::kPublish)).exec;
  const exec::DurationStats& health = m_executive.taskStats(taskId(CycleStage::kHealth)).exec;
  m_log.event(LogLevel::kNotice, "stop_timing",
              "clock=%s jitter_p50_us=%.1f jitter_p99_us=%.1f jitter_max_us=%.1f busy_p50_us=%.1f "
              "busy_p99_us=%.1f busy_max_us=%.1f acquire_p50_us=%.1f acquire_p99_us=%.1f process_p50_us=%.1f "
              "process_p99_us=%.1f process_max_us=%.1f publish_p50_us=%.1f publish_p99_us=%.1f "
              "health_p50_us=%.1f health_p99_us=%.1f",
              m_options.simulated_clock ? "simulated" : "monotonic", us(jitter.quantileNs(0.5)),
              us(jitter.quantileNs(0.99)), us(jitter.maxNs()), us(busy.quantileNs(0.5)),
              us(busy.quantileNs(0.99)), us(busy.maxNs()), us(acquire.quantileNs(0.5)),
              us(acquire.quantileNs(0.99)), us(process.quantileNs(0.5)), us(process.quantileNs(0.99)),
              us(process.maxNs()), us(publish.quantileNs(0.5)), us(publish.quantileNs(0.99)),
              us(health.quantileNs(0.5)), us(health.quantileNs(0.99)));
}

const char* Daemon::signalName() const {
  const int signal_number = m_stop_signal.load(std::memory_order_relaxed);
  if (signal_number == 0) return "none";
  const char* name = sigabbrev_np(signal_number);  // "TERM", "HUP", ...
  return name != nullptr ? name : "unknown";
}

void Daemon::logStatus() {
  // SIGUSR1: where the daemon stands, without stopping it.
  const exec::ExecutiveCounters& c = m_executive.counters();
  const camera::CameraCounters& cam = m_camera.source->counters();
  const telemetry::WriterCounters w = m_writer.counters();  // a snapshot: the publisher thread counts too
  m_log.event(LogLevel::kNotice, "status",
              "cycles=%" PRIu64 " frames=%" PRIu64 " cycles_without_frame=%" PRIu64 " camera_dropped=%" PRIu64
              " camera_errors=%" PRIu64 " slips=%" PRIu64 " mode=%s faults=0x%x transitions=%" PRIu64
              " samples_queued=%" PRIu64 " samples_dropped=%" PRIu64 " samples_written=%" PRIu64
              " write_failures=%" PRIu64 " log_dropped=%" PRIu64,
              c.cycles, m_counters.frames, m_counters.cycles_without_frame, cam.frames_dropped, cam.errors,
              c.slips, nav::toString(m_pipeline.mode()), m_health.fault_bits,
              m_pipeline.modes().transitionCount(), w.samples_queued, w.samples_dropped, w.samples_written,
              w.write_failures, m_log.droppedLines());
}

void Daemon::onSlip(const exec::SlipEvent& event) {
  m_log.event(LogLevel::kWarning, "cycle_slip",
              "minor_frame=%" PRIu64 " overrun_ms=%.3f releases_skipped=%" PRIu64, event.minor_frame,
              static_cast<double>(event.overrun_ns) * 1e-6, event.releases_skipped);
}

void Daemon::onTaskFailure(const exec::TaskFailureEvent& event) {
  // The acquire task logs its camera problems itself, with the driver's text.
  if (event.task == taskId(CycleStage::kAcquire)) return;
  m_log.event(LogLevel::kWarning, "task_failure", "task=%s status=%s minor_frame=%" PRIu64, event.name,
              toString(event.status), event.minor_frame);
}

}  // namespace visnav::app
