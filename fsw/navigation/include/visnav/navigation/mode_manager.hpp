// Mode management: standby, far range, acquisition, near range. Distance conditions must hold for
// `enter_frames` consecutive frames and the two distance thresholds are apart, so measurement noise around
// one threshold never makes the mode chatter. Every transition is recorded with its reason. Pure logic:
// no allocation, no I/O.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "visnav/core/status.hpp"
#include "visnav/navigation/nav_solution.hpp"
#include "visnav/navigation/navigation_params.hpp"

namespace visnav::nav {

/// What the estimators said this frame, as far as the mode decision needs.
struct ModeInputs {
  bool far_valid = false;  ///< far range found the target (far range mode)
  double far_distance_m = 0.0;
  bool acquisition_succeeded = false;
  bool acquisition_failed = false;  ///< acquisition gave up on its own
  /// ... with edges at the cue but no pose it could confirm (no_candidate, not_confirmed, ambiguous)
  bool acquisition_unconfirmed = false;
  bool near_fault_persisted = false;  ///< FDIR: a near-range fault held fault_persistence_frames
  bool depth_known = false;           ///< a depth estimate exists (filter or near range)
  double depth_m = 0.0;  ///< t_c_m.z (CONVENTIONS.md): what far range's distance and the thresholds measure
  bool reacquisition_timed_out = false;  ///< close-range reacquisition searched too long
  /// far range: the cue a hand-over would take has no edge structure (Acquisition::cueLacksEdges); the
  /// hand-over is refused as a failed acquisition would be, without leaving far range
  bool cue_lacks_edges = false;
};

class ModeManager {
 public:
  LoadError init(const NavigationParams& params);
  /// Back to the start mode, counters and history cleared.
  void reset();

  NavMode mode() const { return m_mode; }
  /// Frames spent in the current mode (1 on the frame of entry).
  std::uint32_t framesInMode() const { return m_frames_in_mode; }
  /// Decides the mode for the next frame from this frame's inputs. True when the mode changed.
  bool step(const ModeInputs& in, std::uint64_t frame_number);
  /// Ground command: validated against the current mode; the acknowledgment says why when rejected.
  bool command(ModeCommandKind kind, std::uint32_t command_id, bool far_fix_available,
               std::uint64_t frame_number, CommandAck& ack);
  /// Forces a transition (e.g. the pipeline's own fault handling); no-op when already in `to`.
  void transition(NavMode to, const char* reason, std::uint64_t frame_number);
  /// After a failed acquisition: the next hand-over waits acquire_retry_holdoff_frames, doubled per
  /// consecutive failure up to acquire_retry_holdoff_max_frames. `escalate` false: the wait of the failures
  /// so far, this one not counted (a refused hand-over, refused_handover_escalates_backoff off).
  void backOff(bool escalate = true);
  /// In far range: whether step() with these inputs hands over to acquisition (before cue_lacks_edges).
  bool handOverDue(const ModeInputs& in) const;
  /// In far range with acquire_beside_far_range: an acquisition runs beside far range (started by the step
  /// that handed over, ended by the step that saw it succeed, fail or time out).
  bool acquiringBesideFarRange() const { return m_acquiring_beside; }
  /// Hand-overs refused because the cue had no edge structure (cue_lacks_edges), since init or reset.
  std::uint64_t refusedHandOvers() const { return m_refused_handovers; }

  const ModeTransition& lastTransition() const { return m_last; }
  std::uint64_t transitionCount() const { return m_transitions; }

 private:
  NavigationParams m_params;
  NavMode m_mode = NavMode::kFarRange;
  std::uint32_t m_frames_in_mode = 0;
  int m_close_count = 0;               ///< consecutive frames below acquire_below_m (far range)
  int m_far_count = 0;                 ///< consecutive frames above far_range_above_m (near range)
  int m_acquisition_failures = 0;      ///< consecutive failed or timed-out acquisitions (reset by success)
  int m_holdoff_frames = 0;            ///< far range may hand over again after this many frames in far range
  double m_handover_distance_m = 0.0;  ///< far range's distance when it last handed over
  /// After an unconfirmed acquisition: far range hands over again below this distance (0: no such limit).
  double m_retry_below_m = 0.0;
  bool m_acquiring_beside = false;       ///< see acquiringBesideFarRange()
  std::uint32_t m_acquiring_frames = 0;  ///< frames that acquisition has run beside far range
  ModeTransition m_last;
  std::uint64_t m_transitions = 0;
  std::uint64_t m_refused_handovers = 0;
  /// The far-range hand-over condition for a frame with `close_count` consecutive close fixes, `frames`
  /// frames into far range.
  bool handOverCondition(const ModeInputs& in, int close_count, std::uint32_t frames) const;
  /// m_close_count after a far-range frame with these inputs (step() and handOverDue() alike).
  int nextCloseCount(const ModeInputs& in) const;
  /// An acquisition (in its mode or beside far range) failed or timed out: back-off and retry distance.
  void acquisitionEnded(const ModeInputs& in);
  /// Far range with an acquisition beside it: its outcome decides (acquire_beside_far_range).
  void stepAcquiringBeside(const ModeInputs& in, std::uint64_t frame_number);
};

}  // namespace visnav::nav
