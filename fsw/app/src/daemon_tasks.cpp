// The four cycle tasks of visnavd, their heartbeats and the event lines they write. Nothing here allocates:
// the frame, the solution, the health record and the command batch are members sized at init, log lines are
// formatted on the stack (event_log.hpp). When a stage beats (its work of the cycle done): fsw/app/README.md,
// "Watchdog".
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <ctime>

#include "visnav/app/daemon.hpp"

namespace visnav::app {
namespace {

/// What a stage failed by fault injection returns (the executive counts and logs it as a task failure).
constexpr Status kInjectedFailure = Status::kInvalidArgument;

}  // namespace

bool Daemon::allowLog(std::uint64_t& reported) {
  if (reported < static_cast<std::uint64_t>(m_config.daemon.log_throttle)) {
    ++reported;
    return true;
  }
  ++m_counters.log_suppressed;
  return false;
}

Status Daemon::acquireTask(const exec::CycleInfo& cycle) {
  m_skip_cycle = false;
  const std::int64_t start_ns = m_clock->nowNs();
  // Bounded wait: never past the cycle's deadline (a late camera must not block the cycle;
  // fsw/app/README.md).
  const std::int64_t left_ns = std::max<std::int64_t>(0, cycle.deadline_ns - start_ns);
  const std::int64_t timeout_ns = std::min(m_config.camera.acquireTimeoutNs(), left_ns);
  const camera::AcquireResult result = m_camera.source->acquire(timeout_ns, m_frame);
  m_have_frame = result == camera::AcquireResult::kFrame;
  noteCameraResult(result);
  logCameraEvents();
  m_acquire_us = static_cast<double>(m_clock->nowNs() - start_ns) * 1e-3;
  // Heartbeat: a frame, or the end of a playback (a source that is done, not failing), or a gap of at most
  // camera_stall_cycles cycles (a slow camera, a recovering driver). A longer gap is a failed stage.
  if (result == camera::AcquireResult::kFrame || result == camera::AcquireResult::kEndOfStream)
    m_cycles_since_frame = 0;
  else
    ++m_cycles_since_frame;
  const bool injected = injectFault(CycleStage::kAcquire, cycle);
  if (!injected && m_cycles_since_frame <= static_cast<std::uint64_t>(m_config.daemon.camera_stall_cycles))
    m_heartbeat.beat(CycleStage::kAcquire);
  const bool failed = result == camera::AcquireResult::kError || result == camera::AcquireResult::kDeviceLost;
  if (injected) return kInjectedFailure;
  return failed ? Status::kNotEnoughData : Status::kOk;
}

void Daemon::noteCameraResult(camera::AcquireResult result) {
  camera::CameraSource& source = *m_camera.source;
  switch (result) {
    case camera::AcquireResult::kFrame:
      // The sequence span says whether the driver's gap count is whole: last - first + 1 = frames + dropped
      // while the device is not reopened (the kernel-camera test checks it across the 32-bit wrap).
      if (m_counters.frames == 0) m_counters.first_sequence = m_frame.sequence;
      m_counters.last_sequence = m_frame.sequence;
      ++m_counters.frames;
      if (m_camera_lost) {
        m_camera_lost = false;
        m_log.event(LogLevel::kNotice, "camera_recovered", "driver=%s", source.name());
      }
      return;
    case camera::AcquireResult::kTimeout: ++m_counters.cycles_without_frame; return;
    case camera::AcquireResult::kEndOfStream:
      if (!m_counters.end_of_stream)
        m_log.event(LogLevel::kNotice, "end_of_stream", "driver=%s frames=%" PRIu64 " action=%s",
                    source.name(), source.counters().frames_delivered,
                    m_config.daemon.stop_at_end_of_stream ? "stop" : "continue");
      m_counters.end_of_stream = true;
      if (m_config.daemon.stop_at_end_of_stream) {
        m_skip_cycle = true;  // nothing to publish for a frame that does not exist
        m_executive.requestStop();
      } else {
        ++m_counters.cycles_without_frame;
      }
      return;
    case camera::AcquireResult::kDeviceLost:
      ++m_counters.cycles_without_frame;
      if (!m_camera_lost) {
        m_camera_lost = true;
        std::array<char, 160> text{};
        m_log.event(LogLevel::kError, "camera_lost", "driver=%s error=\"%s\"", source.name(),
                    quotable(source.lastError(), text));
      }
      if (source.recover()) {  // bounded; the driver spaces its attempts (quick ones, then a back-off)
        m_camera_lost = false;
        m_log.event(LogLevel::kNotice, "camera_recovered", "driver=%s recoveries=%" PRIu64, source.name(),
                    source.counters().recoveries);
      }
      return;
    case camera::AcquireResult::kError: {
      ++m_counters.cycles_without_frame;
      ++m_counters.camera_errors;
      std::array<char, 160> text{};
      if (allowLog(m_camera_logs))
        m_log.event(LogLevel::kWarning, "camera_error", "driver=%s error=\"%s\"", source.name(),
                    quotable(source.lastError(), text));
      return;
    }
  }
}

void Daemon::logCameraEvents() {
  // The driver's own account of its state changes (streaming, lost, retrying) and refused buffers; bounded
  // by its queue. State changes are always logged; buffer trouble within [daemon] log_throttle.
  camera::CameraEvent event;
  for (int i = 0; i < camera::CameraEventQueue::kCapacity && m_camera.source->nextEvent(event); ++i) {
    const bool state_change = event.kind == camera::CameraEventKind::kStateChange;
    if (!state_change && !allowLog(m_camera_logs)) continue;
    char fields[camera::CameraEvent::kTextCapacity + 160];
    m_log.event(state_change ? LogLevel::kNotice : LogLevel::kWarning, camera::eventName(event.kind),
                "driver=%s %s", m_camera.source->name(), camera::formatEvent(event, fields, sizeof(fields)));
  }
}

Status Daemon::processTask(const exec::CycleInfo& cycle) {
  if (m_skip_cycle) return Status::kOk;
  const Status status = m_pipeline.process(m_have_frame ? &m_frame : nullptr, m_clock->nowNs(), m_solution);
  m_solution.timing.acquire_us = m_acquire_us;
  if (m_have_frame) {  // the solution holds no reference into the frame: the driver gets its buffer back now
    m_camera.source->release(m_frame);
    m_have_frame = false;
  }
  logTransitions();
  logFaultOnsets(m_solution.fault_bits, m_solution.frame_number);
  if (injectFault(CycleStage::kProcess, cycle)) return kInjectedFailure;
  if (status == Status::kOk) m_heartbeat.beat(CycleStage::kProcess);  // a missing frame is not its failure
  return status;
}

Status Daemon::publishTask(const exec::CycleInfo& cycle) {
  if (m_skip_cycle) return Status::kOk;
  // A failed write (counted by the writer) is a task failure: the executive counts and reports it.
  const bool ok = !m_telemetry_on || m_writer.publishNav(m_solution);
  if (injectFault(CycleStage::kPublish, cycle)) return kInjectedFailure;
  if (ok) m_heartbeat.beat(CycleStage::kPublish);  // telemetry off: nothing to publish is done work
  return ok ? Status::kOk : Status::kCapacityExceeded;
}

Status Daemon::healthTask(const exec::CycleInfo& cycle) {
  if (m_skip_cycle) return Status::kOk;  // the end of a playback: stopping, no heartbeat verdict
  handleCommands();
  m_pipeline.fillHealth(m_health);
  if (m_any_command) m_health.last_command = m_last_ack;  // includes rejections the pipeline never saw
  const exec::ExecutiveCounters& counters = m_executive.counters();
  m_health.frames_dropped = m_camera.source->counters().frames_dropped + m_counters.cycles_without_frame;
  m_health.cycle_slips = counters.slips;
  // kFaultCycleSlip is the executive's, not FDIR's: the daemon sets and counts it.
  constexpr auto kSlipBit = static_cast<std::size_t>(bitIndex(kFaultCycleSlip));
  if (counters.slips > m_slips_seen) m_health.fault_bits |= kFaultCycleSlip;  // the previous cycle slipped
  m_slips_seen = counters.slips;
  m_health.fault_counts[kSlipBit] =
      static_cast<std::uint32_t>(std::min<std::uint64_t>(counters.slips, UINT32_MAX));
  static_assert(nav::kTaskCount == kCycleStageCount, "Health task_timing is indexed by CycleStage");
  for (int i = 0; i < kCycleStageCount; ++i)
    exec::fillTimingSummary(m_executive.taskStats(m_task_ids[static_cast<std::size_t>(i)]).exec,
                            m_health.task_timing[static_cast<std::size_t>(i)]);
  const bool ok = !m_telemetry_on || m_writer.publishHealth(m_health);
  if (m_status_requested.exchange(false, std::memory_order_relaxed)) logStatus();
  const bool injected = injectFault(CycleStage::kHealth, cycle);
  if (ok && !injected) m_heartbeat.beat(CycleStage::kHealth);
  endHeartbeatCycle(cycle.minor_frame);
  if (injected) return kInjectedFailure;
  return ok ? Status::kOk : Status::kCapacityExceeded;
}

bool Daemon::injectFault(CycleStage stage, const exec::CycleInfo& cycle) {
  // Fault injection ([daemon] fault_stage, off by default; fsw/app/README.md, "Watchdog"): the stage's work
  // is done, then it reports a failure without its heartbeat, or it hangs.
  const DaemonParams& d = m_config.daemon;
  if (d.fault_stage != stageIndex(stage) + 1 || cycle.cycle < static_cast<std::uint64_t>(d.fault_from_cycle))
    return false;
  ++m_counters.faults_injected;
  const bool hang = d.faultKind() == InjectedFault::kHang;
  if (!m_fault_injected_logged) {
    m_fault_injected_logged = true;
    m_log.event(LogLevel::kWarning, "fault_injected",
                "stage=%s kind=%s minor_frame=%" PRIu64 " cycle=%" PRIu64, stageName(stage),
                hang ? "hang" : "fail", cycle.minor_frame, cycle.cycle);
    char status[96];
    std::snprintf(status, sizeof(status), "fault injection: %s stage %s", stageName(stage),
                  hang ? "hangs" : "fails every cycle");
    m_notifier.status(status);
  }
  if (hang) {
    // Deliberately unbounded, like the deadlock it stands for: only a stop request (SIGTERM) ends it.
    const timespec step{0, 10'000'000};
    while (!m_executive.stopRequested()) nanosleep(&step, nullptr);
  }
  return true;
}

void Daemon::endHeartbeatCycle(std::uint64_t minor_frame) {
  const bool all_beat = m_heartbeat.endCycle();
  for (int i = 0; i < kCycleStageCount; ++i) {
    const auto stage = static_cast<CycleStage>(i);
    const StageHeartbeat& h = m_heartbeat.stage(stage);
    bool& logged = m_heartbeat_onset_logged[static_cast<std::size_t>(i)];
    if (h.missed_run == 1U) {
      logged = allowLog(m_heartbeat_logs[static_cast<std::size_t>(i)]);
      if (logged)
        m_log.event(LogLevel::kWarning, "heartbeat_missed",
                    "stage=%s minor_frame=%" PRIu64 " missed=%" PRIu64, stageName(stage), minor_frame,
                    h.missed);
    } else if (h.ended_run > 0U && logged) {  // the recovery of a logged onset (throttled with it)
      logged = false;
      m_log.event(LogLevel::kNotice, "heartbeat_restored",
                  "stage=%s minor_frame=%" PRIu64 " missed_in_a_row=%" PRIu64 " missed=%" PRIu64,
                  stageName(stage), minor_frame, h.ended_run, h.missed);
    }
  }
  if (!all_beat) {  // no WATCHDOG=1: a stage that keeps failing lets systemd's WatchdogSec expire
    ++m_counters.watchdog_withheld;
    return;
  }
  ++m_counters.watchdog_strokes;
  m_notifier.watchdog();
}

void Daemon::handleCommands() {
  if (!m_telemetry_on) return;
  const int count = m_commands.poll(m_received.data(), static_cast<int>(m_received.size()));
  for (int i = 0; i < count; ++i) {
    const telemetry::ReceivedCommand& command = m_received[static_cast<std::size_t>(i)];
    nav::CommandAck ack;
    const bool accepted =
        command.valid && m_pipeline.command(command.kind, command.command_id, m_solution.frame_number, ack);
    if (!command.valid) ack = command.rejection();
    m_last_ack = ack;
    m_any_command = true;
    ++m_counters.commands;
    m_counters.commands_accepted += accepted ? 1U : 0U;
    std::array<char, 80> reason{};
    m_log.event(accepted ? LogLevel::kNotice : LogLevel::kWarning, "command",
                "id=%" PRIu32 " kind=%s raw_kind=%u accepted=%s reason=\"%s\" mode=%s", command.command_id,
                command.valid ? nav::toString(command.kind) : "unknown",
                static_cast<unsigned>(command.raw_kind), accepted ? "yes" : "no",
                quotable(ack.reason.data(), reason), nav::toString(m_pipeline.mode()));
    logTransitions();
  }
}

void Daemon::logTransitions() {
  const std::uint64_t count = m_pipeline.modes().transitionCount();
  if (count == m_transitions_logged) return;
  const nav::ModeTransition& t = m_pipeline.modes().lastTransition();
  std::array<char, 80> reason{};
  m_log.event(LogLevel::kNotice, "mode_transition",
              "frame=%" PRIu64 " from=%s to=%s reason=\"%s\" transitions=%" PRIu64 " unlogged=%" PRIu64,
              t.frame_number, nav::toString(t.from), nav::toString(t.to), quotable(t.reason.data(), reason),
              count, count - m_transitions_logged - 1U);
  m_transitions_logged = count;
  char status[96];
  std::snprintf(status, sizeof(status), "mode %s since frame %" PRIu64, nav::toString(t.to), t.frame_number);
  m_notifier.status(status);
}

void Daemon::logFaultOnsets(std::uint32_t faults, std::uint64_t frame) {
  const std::uint32_t onsets = faults & ~m_previous_faults;
  m_previous_faults = faults;
  for (int bit = 0; bit < nav::kFaultBitCount; ++bit) {
    if ((onsets & (1U << bit)) == 0U) continue;
    ++m_counters.fault_onsets;
    if (allowLog(m_fault_logs[static_cast<std::size_t>(bit)]))
      m_log.event(LogLevel::kWarning, "fault_onset", "fault=%s frame=%" PRIu64 " mode=%s", faultName(bit),
                  frame, nav::toString(m_pipeline.mode()));
  }
}

}  // namespace visnav::app
