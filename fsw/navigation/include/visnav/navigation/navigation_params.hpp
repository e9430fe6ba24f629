// Tunables of the mode manager and the FDIR monitor (issue 3), with units, ranges and defaults. The
// generated reference is config/PARAMETERS.md; a run takes its values from the [navigation] table.
#pragma once

#include "visnav/core/param_visitor.hpp"
#include "visnav/navigation/navigation_param_table_gates.hpp"
#include "visnav/navigation/navigation_param_table_reacquisition.hpp"

namespace visnav::nav {

struct NavigationParams {
  // Mode hysteresis (distances along the boresight, counts of consecutive frames).
  int start_mode = 1;                ///< NavMode index the pipeline starts in (1 = far range)
  double acquire_below_m = 0.0;      ///< far range -> acquisition below this distance (0: derived, see below)
  double far_range_above_m = 0.0;    ///< near range -> far range above this distance (0: derived)
  double handover_radius_px = 35.0;  ///< derived hand-over: where the target's bounding radius spans this
  double near_range_min_radius_px = 26.25;  ///< derived give-up: where the bounding radius spans this
  int enter_frames = 3;                     ///< consecutive frames a distance condition must hold
  bool close_count_survives_gaps = false;   ///< far range: a frame without a fix holds the count
  int acquisition_timeout_frames = 25;   ///< acquisition gives up (back to far range) after this many frames
  bool acquire_beside_far_range = true;  ///< hand-over: acquisition beside far range, which keeps its mode
  int acquire_retry_holdoff_frames = 5;  ///< far range waits this long after a failed acquisition...
  int acquire_retry_holdoff_max_frames = 40;  ///< ... doubling per consecutive failure up to this
  double acquire_retry_growth = 2.0;  ///< after an unconfirmed acquisition: retry that many times nearer
  bool refused_handover_escalates_backoff = false;  ///< a refused hand-over doubles the back-off too
  int fault_persistence_frames = 5;      ///< a near-range fault held this long falls back to far range
  double break_nis_chi2 = 200.0;         ///< a weak fit rejected above this NIS ends the track (0: off)
  double break_max_line_fraction = 0.5;  ///< ... on fewer than this share of its selected lines
  int coast_frames = 3;                  ///< frames the filter may propagate without a usable measurement
  // FDIR thresholds (near range).
  double min_inlier_ratio = 0.5;  ///< edge-point inliers / points over the used lines, below: fault
  int min_usable_lines = 3;       ///< fewer used lines: fault
  double max_rms_px = 1.0;        ///< LM residual above: fault
  double min_depth_m = 0.0;       ///< plausible depth band (t_c_m.z); 0: derived from the model and camera
  double max_depth_m = 0.0;
  double max_frame_latency_ms = 100.0;  ///< frame older than one camera period plus this: fault
  // Image evidence that makes a near-range measurement win over the filter's prediction.
  double evidence_min_line_fraction = 0.6;    ///< used lines / measured lines
  double evidence_min_inlier_ratio = 0.6;     ///< inlier points / edge points of the used lines
  double evidence_max_rms_px = 0.8;           ///< pose-fit residual
  double evidence_min_edge_support = 0.5;     ///< inlier points / scanlines cast
  double max_valid_attitude_sigma_deg = 2.5;  ///< a pose less certain than this is not delivered as valid
  double max_valid_position_sigma_rel = 0.0167;
  double doubted_max_attitude_sigma_deg = 1.0;  ///< the same for a near-range pose that is doubted (below)
  bool deliver_filtered_pose = true;  ///< a complete fit the filter accepted is delivered as its estimate
  bool deliver_filtered_partial_fit = true;  ///< the same for a partial fit its lines do not doubt
  double doubt_min_line_fraction = 0.75;     ///< fewer used lines / selected lines: the pose is doubted
  double doubt_nis_chi2 = 12.59;             ///< a filter NIS above this (gate passed): the pose is doubted
  int doubt_every_line_up_to = 6;            ///< with at most this many selected lines, any unused one
  int minimal_fit_max_missing_lines = 2;     ///< a 4-line fit missing more selected lines is not valid
  bool doubt_narrow_face = true;  ///< a fit beside a face seen nearly edge-on (kFlagNarrowFace) is doubted
  bool doubt_after_filter_restart = true;  ///< the fit after one that overruled the filter is doubted
  int doubt_clear_frames = 1;  ///< consecutive poses within the doubted limit that end a find's doubt
  double disputed_max_look_change_deg = 5.0;    ///< a disputed pose turned more than this is not valid
  double disputed_max_range_change_rel = 0.03;  ///< or its range this far (relative) from the prediction's
  double disputed_max_nis = 80.0;               ///< or its NIS (6 dof) above this
  double max_valid_view_angle_deg = 80.0;  ///< a pose showing no surface nearer facing than this is not valid
  double start_pose_sigma_deg = 2.5;    ///< 1-sigma (sqrt of trace) of a given start pose's attitude; 0: none
  double start_pose_sigma_rel = 0.025;  ///< and of its position, over the range
  double start_pose_doubt_nis_chi2 = 5.35;  ///< the first fit's NIS vs the start pose above this: doubted
  int start_pose_doubt_fits = 2;            ///< that many fits after the start pose are judged so
  int branch_confirm_frames = 3;     ///< after a break, this many rival-free valid frames before any is valid
  int narrow_confirm_max_lines = 7;  ///< a narrow-strip fit on at most this many lines confirms a branch only
  double narrow_confirm_max_attitude_sigma_deg = 0.3;    ///< ... at this 1-sigma or less (stop 74)
  double narrow_break_max_fit_attitude_sigma_deg = 1.0;  ///< after a strip break, a fit counts at its own
  bool branch_confirm_needs_filter = true;    ///< a fit the filter rejected counts toward none of them
  bool mirror_resolved_by_prediction = true;  ///< a mirrored rival the continued track rejects is no rival
  bool branch_range_after_jump = true;  ///< after a disputed jump, nor one off the last valid pose's range
  double branch_range_growth_rel_per_frame = 0.005;  ///< that range's tolerance growth (from 3 %, below)
  int branch_range_reference_min_frames = 3;  ///< that range a reference after this many valid in a row
  bool acquisition_awaits_near_range = true;  ///< an acquisition's pose is valid once near range agrees
  bool handover_needs_whole_outline = true;   ///< that agreement is no outline-only fit that missed a line
  int branch_continuity_frames = 3;  ///< after a break this short, a clean fit that kept the look confirms
  double branch_continuity_look_deg = 3.0;     ///< that look's tolerance, widening per frame since (below)
  int branch_continuity_missing_lines = 1;     ///< selected lines such a fit may miss (its only degradation)
  int branch_continuity_spotless_frames = 10;  ///< a longer break: only a flawless fit keeps the branch
  bool narrow_break_reconfirms = true;  ///< no continuity across a break beside a narrow strip (stop 74)
  int filter_diverged_rejections = 2;   ///< consecutive rejections of a clean track: restart the filter
  int far_filter_reset_rejections = 3;  ///< consecutive far-range rejections: restart the filter
  // Close-range reacquisition (local_reacquisition.hpp).
  int reacquire_hypotheses_per_frame = 12;
  int reacquire_scanline_half_length_px = 24;
  double reacquire_step_rel = 0.8;              ///< lateral grid step / the wide tracker's capture range
  double reacquire_growth_px_per_frame = 40.0;  ///< the searched radius widens this much per frame
  int reacquire_confirm_frames = 2;
  bool reacquire_confirm_through_ambiguity = false;  ///< a confirming fit continues the rival-free candidate
  bool reacquire_confirm_at_cue = true;              ///< a lost candidate is looked for at its outline
  double reacquire_range_tolerance_rel = 0.05;       ///< a candidate's range against the prediction's
  double reacquire_attitude_tolerance_deg = 15.0;    ///< its attitude in the line-of-sight frame
  double reacquire_tolerance_growth_deg_per_frame = 1.0;
  double reacquire_max_motion_rel = 0.05;      ///< confirmation: position change / range per frame
  double reacquire_max_rotation_deg = 5.0;     ///< confirmation: attitude change per frame
  int reacquire_timeout_frames = 300;          ///< searching longer: hand over to far range
  int reacquire_acquisition_after_frames = 5;  ///< then acquisition also searches (0: never)
  bool reacquire_far_cue = true;  ///< that acquisition looks where far range finds the target, if it does
  bool reacquire_acquisition_tiles = false;  ///< its prediction-cued attempts also walk tiles over the disc
  bool reacquire_acquisition_outline_cue = false;  ///< or look where the outline cue matched best
  bool reacquire_range_ladder = false;    ///< its prediction-cued attempts step through ranges about it
  bool reacquire_range_rate_rung = true;  ///< every other search frame at the range the track's rate reached
  bool reacquire_rate_rung_valid_track_only = true;  ///< that rate only from a track delivered valid
  bool reacquire_motion_hedge = false;    ///< without a rung, every other search frame where the search began
  bool reacquire_twin_continuity = true;  ///< the last valid pose tells an unresolvable near twin apart
  bool reacquire_drop_insignificant_rates = true;  ///< a search carries only the motion the filter knows
  double reacquire_motion_decay_s = 0.0;  ///< a search's rates fade with this time constant (0: kept)
  bool refute_unconfirmed_cue = false;    ///< an acquisition that confirmed nothing at its cue refutes it too
  bool check_cue_before_handover = true;  ///< a cue without edges is refused in far range, not handed over
  bool far_track_survives_unconfirmed = true;  ///< far range goes on past an unconfirmed cue
  int reacquire_cue_starts = 3;  ///< starts per frame at the best shifts of the predicted outline (0: none)
  double reacquire_cue_min_radius_deg =
      10.0;  ///< the cue slides over at least this cone from the first frame
  bool find_confirms_only_from_reference = true;  ///< a find confirms the branch only if a valid pose kept it
  double branch_reference_max_look_deg = 45.0;    ///< ... while its look tolerance is within this
  double find_prediction_look_deg = 8.0;     ///< or within this of that pose carried by the filter (0: off)
  bool reacquire_carry_angular_rate = true;  ///< such a find restarts the filter with the carried rate
  bool follow_near_twin = true;  ///< an unconfirmed track that lost lines moves to its near twin that fits

  template <typename Visitor>
  void visit(Visitor& v) {
    detail::visitModeAndGateParams(v, *this);
    detail::visitReacquisitionParams(v, *this);
  }

  /// The hand-over distances with the derived ones filled in (0 = derive) for a target of
  /// `bounding_radius_m` seen with focal length `focal_px`.
  NavigationParams withDerivedHandover(double bounding_radius_m, double focal_px) const {
    NavigationParams p = *this;
    if (!(p.acquire_below_m > 0.0)) p.acquire_below_m = focal_px * bounding_radius_m / handover_radius_px;
    if (!(p.far_range_above_m > 0.0))
      p.far_range_above_m = focal_px * bounding_radius_m / near_range_min_radius_px;
    return p;
  }

  const char* crossCheck() const {
    if (!(near_range_min_radius_px < handover_radius_px))
      return "near_range_min_radius_px must be below handover_radius_px (hysteresis)";
    if (acquire_below_m > 0.0 && far_range_above_m > 0.0 && !(far_range_above_m > acquire_below_m))
      return "far_range_above_m must exceed acquire_below_m (hysteresis)";
    if (max_depth_m > 0.0 && !(max_depth_m > min_depth_m)) return "max_depth_m must exceed min_depth_m";
    return nullptr;
  }
};

}  // namespace visnav::nav
