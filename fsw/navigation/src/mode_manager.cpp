#include "visnav/navigation/mode_manager.hpp"

#include <string>

namespace visnav::nav {

LoadError ModeManager::init(const NavigationParams& params) {
  if (const char* problem = params.crossCheck())
    return LoadError::failure(std::string("navigation: ") + problem);
  if (!(params.acquire_below_m > 0.0 && params.far_range_above_m > params.acquire_below_m))
    return LoadError::failure(
        "navigation: hand-over distances not set (NavigationParams::withDerivedHandover derives them)");
  m_params = params;
  reset();
  return LoadError::success();
}

void ModeManager::reset() {
  m_mode = static_cast<NavMode>(m_params.start_mode);
  m_frames_in_mode = 0;
  m_close_count = 0;
  m_far_count = 0;
  m_acquisition_failures = 0;
  m_holdoff_frames = 0;
  m_handover_distance_m = 0.0;
  m_retry_below_m = 0.0;
  m_refused_handovers = 0;
  m_acquiring_beside = false;
  m_acquiring_frames = 0;
  m_last = ModeTransition{};
  m_last.from = m_mode;
  m_last.to = m_mode;
  copyBounded("start", m_last.reason.data(), m_last.reason.size());
  m_transitions = 0;
}

void ModeManager::transition(NavMode to, const char* reason, std::uint64_t frame_number) {
  if (to == m_mode) return;
  m_last.from = m_mode;
  m_last.to = to;
  m_last.frame_number = frame_number;
  copyBounded(reason, m_last.reason.data(), m_last.reason.size());
  ++m_transitions;
  m_mode = to;
  m_frames_in_mode = 0;
  m_close_count = 0;
  m_far_count = 0;
  m_acquiring_beside = false;
}

void ModeManager::backOff(bool escalate) {
  // 5, 10, 20, 40, 40, ... frames (acquire_retry_holdoff_frames doubled up to its max): bounded shifts.
  m_holdoff_frames = m_params.acquire_retry_holdoff_frames;
  for (int i = 0; i < m_acquisition_failures && m_holdoff_frames < m_params.acquire_retry_holdoff_max_frames;
       ++i)
    m_holdoff_frames *= 2;
  if (m_holdoff_frames > m_params.acquire_retry_holdoff_max_frames)
    m_holdoff_frames = m_params.acquire_retry_holdoff_max_frames;
  if (escalate && m_acquisition_failures < 1000) ++m_acquisition_failures;
}

bool ModeManager::handOverCondition(const ModeInputs& in, int close_count, std::uint32_t frames) const {
  // After an acquisition that saw edges but confirmed nothing, the same target at the same size fails the
  // same way: wait until it has come acquire_retry_growth times nearer, or for the longest back-off (a
  // target that holds its range is tried again).
  const bool grown = m_retry_below_m <= 0.0 || (in.far_valid && in.far_distance_m < m_retry_below_m) ||
                     frames > static_cast<std::uint32_t>(m_params.acquire_retry_holdoff_max_frames);
  return in.far_valid && close_count >= m_params.enter_frames &&
         frames > static_cast<std::uint32_t>(m_holdoff_frames) && grown;
}

int ModeManager::nextCloseCount(const ModeInputs& in) const {
  // A frame without a fix (far range coasting: a dim extended target's outline drops out every few frames,
  // campaign box/13) neither counts nor restarts the count: only a fix beyond the hand-over does.
  if (!in.far_valid) return m_params.close_count_survives_gaps ? m_close_count : 0;
  return in.far_distance_m < m_params.acquire_below_m ? m_close_count + 1 : 0;
}

bool ModeManager::handOverDue(const ModeInputs& in) const {
  if (m_mode != NavMode::kFarRange) return false;
  return handOverCondition(in, nextCloseCount(in), m_frames_in_mode + 1U);
}

void ModeManager::acquisitionEnded(const ModeInputs& in) {
  backOff();
  if (in.acquisition_failed && in.acquisition_unconfirmed && m_params.acquire_retry_growth > 1.0)
    m_retry_below_m = m_handover_distance_m / m_params.acquire_retry_growth;
}

void ModeManager::stepAcquiringBeside(const ModeInputs& in, std::uint64_t frame_number) {
  ++m_acquiring_frames;
  if (in.acquisition_succeeded) {
    m_acquisition_failures = 0;
    m_holdoff_frames = 0;
    transition(NavMode::kNearRange, "acquisition beside far range: first pose confirmed", frame_number);
    return;
  }
  if (!in.acquisition_failed &&
      m_acquiring_frames < static_cast<std::uint32_t>(m_params.acquisition_timeout_frames))
    return;
  // Failed or timed out: far range goes on, as after a refused hand-over (no mode changed), and the
  // back-off counts from here.
  acquisitionEnded(in);
  m_acquiring_beside = false;
  m_frames_in_mode = 0;
  m_close_count = 0;
}

bool ModeManager::step(const ModeInputs& in, std::uint64_t frame_number) {
  const NavMode before = m_mode;
  ++m_frames_in_mode;
  switch (m_mode) {
    case NavMode::kStandby: break;  // only a resume command leaves standby
    case NavMode::kFarRange: {
      if (m_acquiring_beside) {
        stepAcquiringBeside(in, frame_number);
        break;
      }
      m_close_count = nextCloseCount(in);
      if (handOverCondition(in, m_close_count, m_frames_in_mode)) {
        m_retry_below_m = 0.0;
        if (in.cue_lacks_edges) {
          // What the acquisition would fail on its first frame (no_target): backed off without the two mode
          // changes (campaign approaches: 185 of 341 failed acquisitions), and without doubling the wait
          // unless refused_handover_escalates_backoff (a refusal changes no mode).
          backOff(m_params.refused_handover_escalates_backoff);
          ++m_refused_handovers;
          m_frames_in_mode = 0;
          m_close_count = 0;
        } else {
          m_handover_distance_m = in.far_distance_m;
          if (m_params.acquire_beside_far_range) {
            m_acquiring_beside = true;
            m_acquiring_frames = 0;
          } else {
            transition(NavMode::kAcquisition, "far range: target close enough", frame_number);
          }
        }
      }
      break;
    }
    case NavMode::kAcquisition:
      if (in.acquisition_succeeded) {
        m_acquisition_failures = 0;
        m_holdoff_frames = 0;
        transition(NavMode::kNearRange, "acquisition: first pose confirmed", frame_number);
      } else if (in.acquisition_failed) {
        acquisitionEnded(in);
        transition(NavMode::kFarRange, "acquisition: failed", frame_number);
      } else if (m_frames_in_mode >= static_cast<std::uint32_t>(m_params.acquisition_timeout_frames)) {
        acquisitionEnded(in);
        transition(NavMode::kFarRange, "acquisition: timeout", frame_number);
      }
      break;
    case NavMode::kNearRange:
      m_far_count = in.depth_known && in.depth_m > m_params.far_range_above_m ? m_far_count + 1 : 0;
      if (in.near_fault_persisted) {
        transition(NavMode::kFarRange, "near range: persistent fault", frame_number);
      } else if (in.reacquisition_timed_out) {
        transition(NavMode::kFarRange, "near range: reacquisition timed out", frame_number);
      } else if (m_far_count >= m_params.enter_frames) {
        transition(NavMode::kFarRange, "near range: target beyond far_range_above_m", frame_number);
      }
      break;
  }
  return m_mode != before;
}

bool ModeManager::command(ModeCommandKind kind, std::uint32_t command_id, bool far_fix_available,
                          std::uint64_t frame_number, CommandAck& ack) {
  ack = CommandAck{};
  ack.command_id = command_id;
  ack.kind = kind;
  const char* rejection = nullptr;
  switch (kind) {
    case ModeCommandKind::kForceFarRange:
      if (m_mode == NavMode::kStandby)
        rejection = "in standby: send resume first";
      else {
        m_acquiring_beside = false;  // far range alone, as commanded: a hand-over starts a new one
        transition(NavMode::kFarRange, "command: force far range", frame_number);
      }
      break;
    case ModeCommandKind::kReacquire:
      if (m_mode == NavMode::kStandby)
        rejection = "in standby: send resume first";
      else if (!far_fix_available)
        rejection = "no far-range fix to acquire from";
      else
        transition(NavMode::kAcquisition, "command: re-acquire", frame_number);
      break;
    case ModeCommandKind::kStandby: transition(NavMode::kStandby, "command: standby", frame_number); break;
    case ModeCommandKind::kResume:
      if (m_mode != NavMode::kStandby)
        rejection = "not in standby";
      else
        transition(NavMode::kFarRange, "command: resume", frame_number);
      break;
    default: rejection = "unknown command"; break;
  }
  ack.accepted = rejection == nullptr;
  copyBounded(ack.accepted ? "ok" : rejection, ack.reason.data(), ack.reason.size());
  return ack.accepted;
}

}  // namespace visnav::nav
