// Tunables of the mode manager and the FDIR monitor (issue 3), with units, ranges and defaults. The
// generated reference is config/PARAMETERS.md; a run takes its values from the [navigation] table.
#pragma once

#include "visnav/core/param_visitor.hpp"

namespace visnav::nav {

/// Compile-time capacities of the close-range reacquisition.
struct LocalSearchLimits {
  static constexpr int kMaxCueStarts = 8;
};

struct NavigationParams {
  // Mode hysteresis (distances along the boresight, counts of consecutive frames).
  int start_mode = 1;                ///< NavMode index the pipeline starts in (1 = far range)
  double acquire_below_m = 0.0;      ///< far range -> acquisition below this distance (0: derived, see below)
  double far_range_above_m = 0.0;    ///< near range -> far range above this distance (0: derived)
  double handover_radius_px = 35.0;  ///< derived hand-over: where the target's bounding radius spans this
  double near_range_min_radius_px = 26.25;  ///< derived give-up: where the bounding radius spans this
  int enter_frames = 3;                     ///< consecutive frames a distance condition must hold
  int acquisition_timeout_frames = 25;   ///< acquisition gives up (back to far range) after this many frames
  int acquire_retry_holdoff_frames = 5;  ///< far range waits this long after a failed acquisition...
  int acquire_retry_holdoff_max_frames = 80;  ///< ... doubling per consecutive failure up to this
  double acquire_retry_growth = 2.0;  ///< after an unconfirmed acquisition: retry that many times nearer
  int fault_persistence_frames = 5;   ///< a near-range fault held this long falls back to far range
  int coast_frames = 3;               ///< frames the filter may propagate without a usable measurement
  // FDIR thresholds (near range).
  double min_inlier_ratio = 0.5;  ///< edge-point inliers / points over the used lines, below: fault
  int min_usable_lines = 3;       ///< fewer used lines: fault
  double max_rms_px = 1.0;        ///< LM residual above: fault
  double min_depth_m = 0.0;       ///< plausible depth band (t_c_m.z); 0: derived from the model and camera
  double max_depth_m = 0.0;
  double max_frame_latency_ms = 100.0;  ///< frame older than one camera period plus this: fault
  // Image evidence that makes a near-range measurement win over the filter's prediction.
  double evidence_min_line_fraction = 0.6;    ///< used lines / measured lines
  double evidence_min_inlier_ratio = 0.7;     ///< inlier points / edge points of the used lines
  double evidence_max_rms_px = 0.8;           ///< pose-fit residual
  double evidence_min_edge_support = 0.5;     ///< inlier points / scanlines cast
  double max_valid_attitude_sigma_deg = 2.5;  ///< a pose less certain than this is not delivered as valid
  double max_valid_position_sigma_rel = 0.0167;
  double doubted_max_attitude_sigma_deg = 1.0;  ///< the same for a near-range pose that is doubted (below)
  double doubt_min_line_fraction = 0.75;        ///< fewer used lines / selected lines: the pose is doubted
  double doubt_nis_chi2 = 16.81;   ///< a filter NIS above this (gate passed): the pose is doubted
  int doubt_every_line_up_to = 6;  ///< with at most this many selected lines, any unused one
  bool doubt_narrow_face = true;   ///< a fit beside a face seen nearly edge-on (kFlagNarrowFace) is doubted
  int doubt_clear_frames = 1;      ///< consecutive poses within the doubted limit that end a find's doubt
  double disputed_max_look_change_deg = 5.0;    ///< a disputed pose turned more than this is not valid
  double disputed_max_range_change_rel = 0.03;  ///< or its range this far (relative) from the prediction's
  double max_valid_view_angle_deg = 80.0;  ///< a pose showing no surface nearer facing than this is not valid
  double start_pose_sigma_deg = 2.5;    ///< 1-sigma (sqrt of trace) of a given start pose's attitude; 0: none
  double start_pose_sigma_rel = 0.025;  ///< and of its position, over the range
  int branch_confirm_frames = 3;  ///< after a break, this many rival-free valid frames before any is valid
  bool acquisition_awaits_near_range = true;  ///< an acquisition's pose is valid once near range agrees
  int branch_continuity_frames = 3;  ///< after a break this short, a clean fit that kept the look confirms
  double branch_continuity_look_deg = 3.0;  ///< that look's tolerance, widening per frame since (below)
  int filter_diverged_rejections = 2;       ///< consecutive rejections of a clean track: restart the filter
  int far_filter_reset_rejections = 3;      ///< consecutive far-range rejections: restart the filter
  // Close-range reacquisition (local_reacquisition.hpp).
  int reacquire_hypotheses_per_frame = 12;
  int reacquire_scanline_half_length_px = 24;
  double reacquire_step_rel = 0.8;              ///< lateral grid step / the wide tracker's capture range
  double reacquire_growth_px_per_frame = 40.0;  ///< the searched radius widens this much per frame
  int reacquire_confirm_frames = 2;
  bool reacquire_confirm_through_ambiguity = false;  ///< a confirming fit continues the rival-free candidate
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
  bool reacquire_twin_continuity = true;  ///< the last valid pose tells an unresolvable near twin apart
  bool reacquire_drop_insignificant_rates = true;  ///< a search carries only the motion the filter knows
  double reacquire_motion_decay_s = 0.0;  ///< a search's rates fade with this time constant (0: kept)
  bool refute_unconfirmed_cue = false;    ///< an acquisition that confirmed nothing at its cue refutes it too
  bool check_cue_before_handover = true;  ///< a cue without edges is refused in far range, not handed over
  bool far_track_survives_unconfirmed = true;  ///< far range goes on past an unconfirmed cue
  int reacquire_cue_starts = 3;  ///< starts per frame at the best shifts of the predicted outline (0: none)
  bool find_confirms_only_from_reference = true;  ///< a find confirms the branch only if a valid pose kept it
  double branch_reference_max_look_deg = 180.0;   ///< ... while its look tolerance is within this
  bool follow_near_twin = true;  ///< an unconfirmed track that lost lines moves to its near twin that fits

  template <typename Visitor>
  void visit(Visitor& v) {
    v.enumeration(
        {"navigation", "start_mode", "-", 0, 3, "mode after start (standby waits for a resume command)"},
        "standby|far_range|acquisition|near_range", start_mode);
    v.real({"navigation", "handover_radius_px", "px", 5.0, 10000.0,
            "where acquire_below_m is 0 it is derived as f x bounding radius / this: the hand-over happens "
            "at the same apparent size for every target and camera (plate 2.3 x 1.8 m, f 1000 px: 42 m; 35 "
            "against 50 on two 100-scene campaign subsets: tracked 0.497 -> 0.521 and 0.615 -> 0.638, "
            "confidently wrong frames 27 -> 23 and 20 -> 23)"},
           handover_radius_px);
    v.real({"navigation", "near_range_min_radius_px", "px", 1.0, 10000.0,
            "where far_range_above_m is 0 it is derived as f x bounding radius / this: near range gives "
            "the target up to far range when it shrinks below this apparent radius (must be below "
            "handover_radius_px: the gap is the hysteresis; 26.25 = 35 x 3/4, the 4/3 distance ratio it "
            "was derived with before it became its own parameter)"},
           near_range_min_radius_px);
    v.real({"navigation", "acquire_below_m", "m", 0.0, 10000.0,
            "far range hands over to acquisition when its distance stays below this for enter_frames"},
           acquire_below_m);
    v.real({"navigation", "far_range_above_m", "m", 0.0, 10000.0,
            "near range falls back to far range when the distance stays above this for enter_frames "
            "(must exceed acquire_below_m: the gap is the hysteresis)"},
           far_range_above_m);
    v.integer({"navigation", "enter_frames", "count", 1, 1000,
               "consecutive frames a distance condition must hold before the mode changes"},
              enter_frames);
    v.integer({"navigation", "acquire_retry_holdoff_frames", "frames", 0, 100000,
               "after a failed or timed-out acquisition, far range does not hand over again for this many "
               "frames; the wait doubles with every consecutive failure (exponential back-off: a far-range "
               "cue that keeps fooling acquisition must not flip the mode every few frames)"},
              acquire_retry_holdoff_frames);
    v.integer({"navigation", "acquire_retry_holdoff_max_frames", "frames", 0, 100000,
               "upper bound of that back-off (80 frames: 16 s at 5 Hz)"},
              acquire_retry_holdoff_max_frames);
    v.real({"navigation", "acquire_retry_growth", "-", 0.0, 1000.0,
            "after an acquisition that found edges at far range's cue but confirmed no pose there "
            "(no_candidate, not_confirmed, ambiguous), far range hands over again only once its distance "
            "is this many times below the one it handed over at (the target then spans as many times more "
            "pixels), or after acquire_retry_holdoff_max_frames: the same target at the same size fails the "
            "same way (case approach_smallsat: no_candidate at 157 m, ambiguous at 122 m, confirmed at "
            "69 m). <= 1: the back-off alone"},
           acquire_retry_growth);
    v.integer({"navigation", "acquisition_timeout_frames", "count", 1, 10000,
               "acquisition returns to far range when it has not succeeded within this many frames"},
              acquisition_timeout_frames);
    v.integer({"navigation", "fault_persistence_frames", "count", 1, 1000,
               "a near-range fault held for this many consecutive frames falls back to far range"},
              fault_persistence_frames);
    v.integer({"navigation", "coast_frames", "count", 0, 1000,
               "frames the Kalman prediction stands in for a failed near-range measurement (sec. II-H)"},
              coast_frames);
    v.real({"navigation", "min_inlier_ratio", "-", 0.0, 1.0,
            "FDIR: edge-point inlier ratio over the used lines below this is a fault"},
           min_inlier_ratio);
    v.integer({"navigation", "min_usable_lines", "count", 0, 1000, "FDIR: fewer used lines is a fault"},
              min_usable_lines);
    v.real({"navigation", "max_rms_px", "px", 0.001, 100.0, "FDIR: pose-fit residual above this is a fault"},
           max_rms_px);
    v.real({"navigation", "min_depth_m", "m", 0.0, 100000.0,
            "FDIR: plausible depth band, lower end; 0 derives the limit from the model: the camera cannot be "
            "inside the model's bounding box (model frame). Not its bounding sphere: the panels of case "
            "approach_smallsat make that 5.8 m in radius, and the approach ends at 5 m"},
           min_depth_m);
    v.real({"navigation", "max_depth_m", "m", 0.0, 100000.0,
            "FDIR: plausible depth band, upper end; 0 derives it from the model and camera: the depth at "
            "which the target spans 4 px (no 6-DOF fit is possible beyond)"},
           max_depth_m);
    v.real({"navigation", "max_frame_latency_ms", "ms", 0.0, 100000.0,
            "FDIR: a frame older than one camera frame period plus this when processed is a fault (the "
            "camera and the cycle free-run, so the newest frame is up to one period old by phase alone; the "
            "period is the interval between the last two exposures; 0 disables the check)"},
           max_frame_latency_ms);
    v.real({"navigation", "evidence_min_line_fraction", "-", 0.0, 1.0,
            "good image evidence: at least this share of the measured lines used (with the three below, "
            "the measurement wins over a filter that rejects it, and the filter restarts from it)"},
           evidence_min_line_fraction);
    v.real({"navigation", "evidence_min_inlier_ratio", "-", 0.0, 1.0,
            "good image evidence: edge-point inlier ratio over the used lines at least this"},
           evidence_min_inlier_ratio);
    v.real({"navigation", "evidence_max_rms_px", "px", 0.001, 100.0,
            "good image evidence: pose-fit residual at most this"},
           evidence_max_rms_px);
    v.real({"navigation", "evidence_min_edge_support", "-", 0.0, 1.0,
            "good image evidence: inlier edge points per scanline cast at least this (the model's edges are "
            "where the image has them)"},
           evidence_min_edge_support);
    v.real({"navigation", "max_valid_attitude_sigma_deg", "deg", 0.0, 180.0,
            "a 6-DOF pose whose own 1-sigma attitude uncertainty (square root of the trace of its attitude "
            "covariance: the rms of the total rotation error) exceeds this is computed and tracked but not "
            "delivered as valid: 2.5 puts the 5 deg of a confidently wrong pose 2 sigma out (campaign "
            "plate/12: a 1.8 m plate at 21 m, 12 deg off from its true start; the paper's plate at 26 m on "
            "VGA: 2.2 deg); 0 switches the check off"},
           max_valid_attitude_sigma_deg);
    v.real({"navigation", "max_valid_position_sigma_rel", "-", 0.0, 1.0,
            "the same for the position: 1-sigma (square root of the trace) over the range. 0.0167 puts 5 % "
            "of the range 3 sigma out: the position's 1-sigma rarely comes near it, so the stricter bound "
            "costs little (campaign seeds 1-40, 200 scenes: 0.025 -> 0.0167 took tracked frames 14 721 -> "
            "14 698 and confidently wrong frames 7 -> 4, octagon/15 and octagon/29 at 5.1-6.8 % of the "
            "range with 1-sigma 1.8-2.3 %); 0 switches the check off"},
           max_valid_position_sigma_rel);
    v.real({"navigation", "doubted_max_attitude_sigma_deg", "deg", 0.0, 180.0,
            "a near-range pose that is doubted (the filter's innovation gate rejects it, fewer than "
            "doubt_min_line_fraction of its selected lines were used, or its track began with a "
            "reacquisition's find and none of its poses met this limit yet) is valid only with an attitude "
            "1-sigma of at most this: the track goes on with it either way, but a wrong fit has weak "
            "geometry and a doubt (campaign smallsat/83: 5 of 8 lines, 1.5 deg 1-sigma, 12 deg off for 37 "
            "frames). Full campaign: confidently wrong frames 396 -> 165, tracked mean 0.516 -> 0.505; on "
            "200 other scenes 63 -> 26, 0.545 -> 0.535; 0 switches the check off"},
           doubted_max_attitude_sigma_deg);
    v.real({"navigation", "doubt_min_line_fraction", "-", 0.0, 1.0,
            "a near-range pose is doubted when fewer than this share of its selected lines were used (the "
            "others were not found or rejected): it rests on part of the outline. 0.85 (2 of 8 doubted) "
            "fails case low_contrast_octagon: 1.00 -> 0.81 tracked (README, stop 47)"},
           doubt_min_line_fraction);
    v.real({"navigation", "doubt_nis_chi2", "-", 0.0, 1000.0,
            "a near-range pose the filter accepts with a NIS (6 dof) above this is doubted: the innovation "
            "gate ([filter] pose_gate_chi2, 99.9 %) lets through a fit one frame surprising enough that it "
            "is more often a spike than the target's motion; the filter still takes it, only its validity "
            "needs doubted_max_attitude_sigma_deg. 16.81 is the 99 % point. Single-frame spikes 5.2-5.9 deg "
            "off at 1.5-1.9 deg 1-sigma and NIS 17.5-20.5 (campaign octagon/2, smallsat/5017, smallsat/5026, "
            "octagon/5009); measured in the top-level README (stop 52); 0 switches it off"},
           doubt_nis_chi2);
    v.integer({"navigation", "doubt_every_line_up_to", "lines", 0, 1000,
               "a near-range pose with at most this many selected lines is doubted when any of them was not "
               "used: a small outline has no line to spare (campaign box/191: 4 of 5 lines, 5.0-5.5 deg off "
               "at 1.7-2.3 deg 1-sigma). Full campaign: confidently wrong frames 33 -> 28 (box/191 4 -> 0, "
               "cao/197 1 -> 0), tracked mean 0.622 -> 0.620; replayed on 200 other scenes and on the named "
               "cases, no change (5 instead of 6 the same); 0 switches it off"},
              doubt_every_line_up_to);
    v.boolean({"navigation", "doubt_narrow_face", "-", 0, 1,
               "a near-range pose is doubted when a tracked face is seen nearly edge-on, as a strip "
               "narrower than [nearrange] confusable_edge_separation_px (the tracker's narrow-face flag): "
               "the lines beside it may be biased by up to the strip's width with a tight scatter, and "
               "a pose on them looks certain (campaign box/25: 5 of 6 lines at 0.02-0.08 px rms, 1.0-1.5 "
               "deg 1-sigma, 4.7-5.9 deg off)"},
              doubt_narrow_face);
    v.integer(
        {"navigation", "doubt_clear_frames", "count", 1, 1000,
         "a track that began with a reacquisition's find stays doubted, and none of its poses is "
         "valid, until this many consecutive poses met doubted_max_attitude_sigma_deg (1: the first "
         "such pose ends the doubt and is valid). A find the image does not pin down alternates "
         "between certain and uncertain fits as its lines come and go (campaign box/191: found 1.6 m "
         "and 12 deg off, 1-sigma 0.30, 1.99, 0.36, 1.84, 1.95, 0.98, 0.39, 2.10 deg on consecutive "
         "frames; 13 confidently wrong frames with 1 or 2, none with 3). Measured, off: with 3 on seeds "
         "1-40, tracked 0.6500 -> 0.6358 and confidently wrong frames 18 -> 18 (a right find waits two "
         "frames more)"},
        doubt_clear_frames);
    v.real({"navigation", "disputed_max_look_change_deg", "deg", 0.0, 180.0,
            "a near-range pose the innovation gate rejects but the image supports (the measurement wins "
            "and the filter restarts from it) is not valid on that frame when its look (attitude along its "
            "line of sight, modulo symmetries: a slew does not change it) is more than this from the "
            "prediction's: no target tumbles that fast between two frames, a fit jumping to the wrong "
            "faces of a box does (campaign box/58: 10.7 deg in one frame, NIS 777, 0.4 deg 1-sigma). The "
            "track goes on from it; 0 switches the check off"},
           disputed_max_look_change_deg);
    v.real({"navigation", "disputed_max_range_change_rel", "-", 0.0, 10.0,
            "the same for the range: a disputed pose whose range differs from the prediction's by more "
            "than this share of it is not valid on that frame. The prediction carries the approach's speed, "
            "and a slew does not change the range; the image constrains depth least, and a fit that locks "
            "on another pair of edges jumps in it (campaign box/44: 8.6 % in one frame, NIS 2097, valid "
            "and wrong on that frame and the next). Full campaign: confidently wrong frames 96 -> 88, "
            "tracked 0.6237 -> 0.6228. The track goes on from it; 0 switches the check off"},
           disputed_max_range_change_rel);
    v.real({"navigation", "max_valid_view_angle_deg", "deg", 0.0, 90.0,
            "a 6-DOF pose on which no surface of the model faces the camera within this angle (between its "
            "outward normal and the line of sight to its centre) is tracked but not valid: seen edge-on, a "
            "plate's outline is a sliver whose opposite edges lie a few pixels apart, and its fit locks "
            "biased with a small covariance (stop 32's full run: 47 of its 139 confidently wrong frames, "
            "plates turning edge-on, 5-19 % of the range off with a 0.5-2.3 % 1-sigma; with the check on "
            "that run's plates, octagons and cao models: 71 -> 23 wrong frames for 22 of 64 239 expected "
            "frames). A box always shows a face within 55 deg (the cube's worst view, along a diagonal), so "
            "boxes and the satellite are not affected, flat models are; 0 switches the check off"},
           max_valid_view_angle_deg);
    v.real({"navigation", "start_pose_sigma_deg", "deg", 0.0, 180.0,
            "a start pose given by the operator (startNearRange, visnav-replay --initial-pose) starts the "
            "filter with this 1-sigma attitude uncertainty (square root of the trace), so the first "
            "measurements are checked against it instead of starting a track on their own: an ambiguous "
            "first fit no longer leaves the filter empty and the prediction frozen at the start pose "
            "(campaign box/26: lost on frame 3 of a 0.5 m/frame approach, then 180 frames of search at "
            "the start range); a measurement it rejects still wins with good image evidence; 0: the first "
            "measurement starts the filter, as before"},
           start_pose_sigma_deg);
    v.real({"navigation", "start_pose_sigma_rel", "-", 0.0, 1.0,
            "the same for the start pose's position: 1-sigma (square root of the trace) over the range"},
           start_pose_sigma_rel);
    v.integer(
        {"navigation", "branch_confirm_frames", "count", 0, 1000,
         "a track's branch (which of two mirror poses, e.g. a plate's two tilts) is known from the given "
         "start pose, an acquisition or reacquisition confirmation, or this many consecutive valid "
         "frames whose fit had corners and no mirrored rival; any frame without a valid pose loses it. "
         "While it is unknown no pose is valid: a track carried through withheld frames can come out "
         "on the mirror branch, fitting the image as well with a tight covariance (campaign "
         "octagon/174: 26 withheld frames, then 66 valid ones 34-140 deg off); 0 switches the check "
         "off"},
        branch_confirm_frames);
    v.boolean(
        {"navigation", "acquisition_awaits_near_range", "-", 0, 1,
         "the pose an acquisition confirms is delivered tracked but not valid on its own frame, and the "
         "track's branch becomes known only when the first near-range frame after it delivers a valid, "
         "rival-free fit the filter (started from the acquisition) does not reject as a jump; otherwise "
         "branch_confirm_frames rival-free frames are needed as after any break. The acquisition's "
         "confirmation frames all look at one small target: on stop 33's full campaign all 5 of its wrong "
         "frames (5.6-159 deg off) were on the acquisition's own frame; in the three traced (box/89, /40, "
         "/16) the near-range fits after it disagreed (NIS 38-146) and were withheld. Costs one frame per "
         "acquisition; false: valid on its own frame"},
        acquisition_awaits_near_range);
    v.integer({"navigation", "branch_continuity_frames", "count", 0, 1000,
               "after a break of at most this many frames without a valid pose, a near-range fit confirms "
               "the track's branch at once when it is as good as a fit gets: status tracking (every "
               "selected line, no mirrored rival), accepted by the filter's prediction, attitude 1-sigma "
               "within doubted_max_attitude_sigma_deg, and its look (attitude seen along its own line of "
               "sight, modulo the model's symmetries) within branch_continuity_look_deg of the last valid "
               "pose's, widened by reacquire_tolerance_growth_deg_per_frame per frame since. On seeds "
               "1-40: 84 frames more tracked (14 720 -> 14 804), none wrong; on the full campaign 406 "
               "more and 4 more confidently wrong, each continuing a track already 2.7-6.7 deg off; with "
               "ambiguous and degraded fits allowed, seeds 1-40 gave 547 more and 13 more confidently "
               "wrong. 0: only branch_confirm_frames rival-free frames confirm"},
              branch_continuity_frames);
    v.real({"navigation", "branch_continuity_look_deg", "deg", 0.0, 180.0,
            "see branch_continuity_frames: the look tolerance on the frame right after the last valid "
            "pose"},
           branch_continuity_look_deg);
    v.integer({"navigation", "filter_diverged_rejections", "count", 1, 1000,
               "a clean (tracking) measurement the filter rejects this many times in a row restarts the "
               "filter from it"},
              filter_diverged_rejections);
    v.integer({"navigation", "far_filter_reset_rejections", "count", 1, 1000,
               "far range: the filter restarts from the next fix after this many rejected fixes in a row"},
              far_filter_reset_rejections);
    v.integer({"navigation", "reacquire_hypotheses_per_frame", "count", 1, 1000,
               "close-range reacquisition: tracker starts tried per frame (bounds the frame's cost)"},
              reacquire_hypotheses_per_frame);
    v.integer({"navigation", "reacquire_scanline_half_length_px", "px", 2, 64,
               "close-range reacquisition: scanline half length of its wide tracker (its capture range)"},
              reacquire_scanline_half_length_px);
    v.real({"navigation", "reacquire_step_rel", "-", 0.1, 2.0,
            "close-range reacquisition: spacing of the lateral search grid as a share of the capture range"},
           reacquire_step_rel);
    v.real({"navigation", "reacquire_growth_px_per_frame", "px", 1.0, 10000.0,
            "close-range reacquisition: the searched radius around the prediction grows this much per frame"},
           reacquire_growth_px_per_frame);
    v.integer({"navigation", "reacquire_confirm_frames", "count", 1, 100,
               "close-range reacquisition: frames a found pose must keep tracking before it is delivered"},
              reacquire_confirm_frames);
    v.boolean({"navigation", "reacquire_confirm_through_ambiguity", "-", 0, 1,
               "close-range reacquisition (experimental, off): a confirming fit flagged ambiguous (its "
               "depth-mirrored rival fits as well) confirms the rival-free candidate when its evidence is "
               "otherwise good and it continues it (reacquire_max_motion_rel, reacquire_max_rotation_deg). "
               "Campaign octagon/167: 13 -> 106 of 157 frames tracked. Off because on the full campaign it "
               "took tracked frames 75 407 -> 75 533 and confidently wrong 88 -> 89 (box/95: a find 5.5 deg "
               "off; fsw/navigation/README.md). false: an ambiguous fit ends the confirmation"},
              reacquire_confirm_through_ambiguity);
    v.real(
        {"navigation", "reacquire_range_tolerance_rel", "-", 0.001, 10.0,
         "close-range reacquisition: a candidate whose range differs from the predicted range by more than "
         "this share is not taken (a few outline lines of a small body also fit a mirrored pose at another "
         "range: campaign box/1 was re-found 25 % off; at 0.1 box/26 was re-found 8.7 % off with two edges "
         "on the wrong image lines and held: on the full campaign 0.05 gives 306 confidently wrong frames "
         "instead of 407 for 0.7 points of tracked mean)"},
        reacquire_range_tolerance_rel);
    v.real({"navigation", "reacquire_attitude_tolerance_deg", "deg", 0.1, 180.0,
            "close-range reacquisition: largest attitude difference between a candidate and the prediction, "
            "both seen along their own line of sight (a slew moves the target, not its look), modulo the "
            "model's symmetries"},
           reacquire_attitude_tolerance_deg);
    v.real({"navigation", "reacquire_tolerance_growth_deg_per_frame", "deg", 0.0, 180.0,
            "close-range reacquisition: the attitude tolerance grows this much per frame searched (the "
            "prediction ages; 1 deg/frame is the fastest tumble the campaign draws)"},
           reacquire_tolerance_growth_deg_per_frame);
    v.real({"navigation", "reacquire_max_motion_rel", "-", 0.001, 1.0,
            "close-range reacquisition: largest position change per frame (share of the range) that counts "
            "as consistent motion while confirming"},
           reacquire_max_motion_rel);
    v.real({"navigation", "reacquire_max_rotation_deg", "deg", 0.01, 180.0,
            "close-range reacquisition: largest attitude change per frame while confirming"},
           reacquire_max_rotation_deg);
    v.integer({"navigation", "reacquire_timeout_frames", "count", 1, 100000,
               "close-range reacquisition searching longer than this hands over to far range"},
              reacquire_timeout_frames);
    v.integer(
        {"navigation", "reacquire_acquisition_after_frames", "count", 0, 100000,
         "close-range reacquisition: after this many frames without a find, acquisition (attitude grid "
         "x range steps) also searches each frame, cued by the filter's prediction with the lateral "
         "search radius as its direction margin: an approaching or tumbling target leaves the "
         "prediction's range and look, which the local search keeps. A find is taken only from a vertex "
         "fit without a mirrored rival and with a look that agrees with the last valid pose "
         "(reacquire_attitude_tolerance_deg widening per frame since it), and is doubted "
         "(doubted_max_attitude_sigma_deg). Full campaign (with 0 -> 5): tracked mean 0.505 -> 0.547, "
         "recoveries that never came 544 -> 451, "
         "confidently wrong frames 165 -> 193; 0: never"},
        reacquire_acquisition_after_frames);
    v.boolean({"navigation", "reacquire_far_cue", "-", 0, 1,
               "close-range reacquisition: every other attempt of the acquisition that searches alongside "
               "(reacquire_acquisition_after_frames) first runs far range on the frame (its outline search "
               "finds an extended target) and, when it finds one outside the window the prediction's "
               "attempt covers, searches around that line of sight at the prediction's range: the "
               "prediction's line of sight drifts while nothing is measured (campaign box/23: after a "
               "46-frame eclipse 10 to 120 deg off). The other attempts, and a fix the prediction's window "
               "holds, keep the prediction (far range locks on clutter, box/37; cued by far range while the "
               "prediction was 1.9 deg off the line of sight and right in range, an attempt confirmed a pose "
               "5.6 % off in range, box/191). The find is judged as before; "
               "false: the prediction only"},
              reacquire_far_cue);
    v.boolean({"navigation", "reacquire_acquisition_tiles", "-", 0, 1,
               "close-range reacquisition (experimental, off): every other attempt of that acquisition "
               "cued by the prediction looks at the next cell of a square spiral over the disc the local "
               "search has grown to (cells 2 (h - r) apart, h the window's half-size and r the target's "
               "radius; centres on the image), the others at the prediction: a target lost for long drifts "
               "from the prediction's line of sight by more than one window (campaign cao/5: 22 deg off "
               "after 60 frames, every attempt failed with no target in its window). A window without the "
               "target fails on its own frame (min_edge_snr); the find is judged as before. Off because on "
               "the full campaign (with disputed_max_range_change_rel) it took tracked 0.6228 -> 0.6238 "
               "and confidently wrong frames 88 -> 119: more attempts confirm more wrong box poses "
               "(box/172 +20, box/132 +9); true: every other attempt on a tile"},
              reacquire_acquisition_tiles);
    v.boolean({"navigation", "reacquire_acquisition_outline_cue", "-", 0, 1,
               "close-range reacquisition (experimental, off): on far range's turn (every other attempt of "
               "that acquisition), when far range gives no cue, the attempt looks where this frame's outline "
               "cue (reacquire_cue_starts: the outline at the prediction's look and range slid over the "
               "searched disc) matched best, if the prediction's window would not hold the whole target "
               "there. Far range sees nothing on a gradient or a limb, and the prediction drifts while "
               "nothing is measured (campaign octagon/19, gradient: 7.4 deg off the line of sight, never "
               "re-found; with it 0 -> 50 of 108 tracked). The other turn stays at the prediction (with the "
               "cue on every attempt box/36 lost 34 frames: a cue on clutter held the attempt while the "
               "target reappeared in the prediction's window). Off because on the full campaign it took "
               "tracked 0.6248 -> 0.6268 and confidently wrong frames 88 -> 99: box/132, never found "
               "without it, was found and its track then drifted to 12 deg (1 -> 10 wrong frames); seeds "
               "1-40 alone had shown 0.6435 -> 0.6483 and 18 -> 18. true: used"},
              reacquire_acquisition_outline_cue);
    v.boolean({"navigation", "find_confirms_only_from_reference", "-", 0, 1,
               "a close-range reacquisition's find confirms the track's branch only when the branch was "
               "known before the loss: a last valid pose (or the operator's start pose) exists and the "
               "find's look is consistent with it (reacquire_attitude_tolerance_deg widening per frame). "
               "Otherwise the find and the track after it need branch_confirm_frames rival-free frames, "
               "near twins refitted, like any track whose branch is unknown. The local search is judged "
               "against its prediction, and a prediction from a track never delivered carries that "
               "track's twin (campaign octagon/172 with reacquire_motion_decay_s: acquired at 30 m on the "
               "quarter turn, withheld, lost, then re-found on the same quarter turn at 14 m and delivered "
               "88 deg off for 10 frames). false: every find confirms"},
              find_confirms_only_from_reference);
    v.real(
        {"navigation", "branch_reference_max_look_deg", "deg", 1.0, 180.0,
         "find_confirms_only_from_reference: the last valid pose confirms a find's branch only while "
         "its look tolerance (reacquire_attitude_tolerance_deg + reacquire_tolerance_growth_deg_per_frame "
         "per frame since it) is at most this. At 45 deg, half the quarter turn that is a near-square "
         "target's nearest twin (a wider tolerance keeps both twins), a find past it is still taken but "
         "earns its branch with branch_confirm_frames rival-free frames. Measured (stop 52) and left at "
         "180: with the search's fading rates (reacquire_motion_decay_s 5 s) 45 deg kept campaign cao/157's "
         "find, 72 frames after its last valid pose and 5.6 deg off at 23 m, from being delivered on its "
         "own frame, but not smallsat/183's (43 deg off on a stale prediction: it passed its rival-free "
         "frames); with the shipped defaults it removed no confidently wrong frame on seeds 1-40 (200 "
         "scenes) and cost 76 tracked frames over 24 of them, 1-7 each (box/44 0.812 -> 0.796). 180: the "
         "reference never "
         "expires"},
        branch_reference_max_look_deg);
    v.boolean({"navigation", "follow_near_twin", "-", 0, 1,
               "while a track's branch is unknown, a near-range fit that left some of its selected lines "
               "unfound (kFlagLineRejected) and whose near twin fits the lines it found as well "
               "(kFlagNearTwinRival, not refused by the last valid pose's look) looks again: a second "
               "tracker, from the twin, on the same image. When that fit is clean (status tracking, no "
               "rival of either kind), finds more lines and has no higher rms, the filter restarts from it. "
               "The frame is withheld either way; the twin's track earns its branch like any other "
               "(branch_confirm_frames rival-free frames). Campaign octagon/172 with far range as before "
               "stop 49: the quarter turn acquired at 30 m found 6 of its 8 lines on every frame, the true "
               "pose all 8; tracked 0.24 -> 0.52. false: the track stays on its pose"},
              follow_near_twin);
    v.boolean({"navigation", "reacquire_twin_continuity", "-", 0, 1,
               "close-range reacquisition: that acquisition does not refuse a candidate whose near twin "
               "the image cannot resolve ([acquisition] near_twin_min_separation_px) when the last valid "
               "pose's look (reacquire_attitude_tolerance_deg widening per frame) keeps the candidate "
               "and not the twin; the find is flagged (campaign --trace). Campaign box/44 (quarter-turn "
               "twin 1.2 px apart at 14 m): tracked 0.05 -> 0.81; false: the twin always refuses"},
              reacquire_twin_continuity);
    v.boolean(
        {"navigation", "reacquire_drop_insignificant_rates", "-", 0, 1,
         "when close-range reacquisition starts, the filter's velocity and angular velocity are each "
         "set to zero unless significant ([filter] restart_rate_chi2 against their own covariance, "
         "the velocity also against the start-at-rest prior; PoseFilter::dropInsignificantRates): "
         "the search is predicted from the filter, and a rate read from the last noisy fits carried "
         "the prediction away from a target that did not move (campaign box/129: 19 m and 82 deg "
         "off 100 frames into the search, never found). false: the search carries the filter's rates as they "
         "are"},
        reacquire_drop_insignificant_rates);
    v.real({"navigation", "reacquire_motion_decay_s", "s", 0.0, 1000.0,
            "close-range reacquisition: after every searched frame the filter's velocity and angular "
            "velocity are multiplied by exp(-dt / this), so the search's prediction moves at most rate x "
            "this from where the track was lost instead of along a straight line for the whole search "
            "(campaign octagon/37: 8 m off 60 frames into the search where the last pose was 4 m off). "
            "Measured at 5 s: seeds 1-40 (200 scenes) tracked frames 14 721 -> 14 793 and seeds 5001-5040 "
            "15 022 -> 15 074, confidently wrong 7 and 13 unchanged; the 10 wrong frames it exposed on "
            "campaign octagon/172 (a find continuing a track never delivered) are refused by "
            "find_confirms_only_from_reference since stop 51. Still off: on stop 51's full run (1000 "
            "scenes, with follow_near_twin) tracked frames 74 351 -> 74 506 but confidently wrong 28 -> 34 "
            "(cao/157: a find 5.6 deg off at 23 m; smallsat/183: a find continuing a track withheld for "
            "30 frames, 43 deg off, within the last valid pose's look tolerance grown 1 deg a frame). "
            "0: the rates are kept"},
           reacquire_motion_decay_s);
    v.boolean({"navigation", "refute_unconfirmed_cue", "-", 0, 1,
               "an acquisition that failed at far range's cue with edges there (no_candidate, not_confirmed, "
               "ambiguous) refutes that fix as one that found no edges (no_target) does: far range passes "
               "over the region until it has grown 4x in n or [farrange] refuted_fix_frames passed. Off: "
               "acquire_retry_growth handles that failure instead, and far range keeps reporting the target. "
               "Measured on seeds 1-40 of plate, octagon and box (100 scenes, restart and growth off): "
               "tracked 0.621 -> 0.619, wrong frames 36 -> 32; it passed over a satellite acquisition could "
               "not yet confirm at 80 m and handed over clutter instead (campaign smallsat/6: 1.0 -> 0)"},
              refute_unconfirmed_cue);
    v.boolean({"navigation", "check_cue_before_handover", "-", 0, 1,
               "before far range hands its fix to acquisition, the acquisition's first test runs on this "
               "frame: a cue whose window's edge SNR is under [acquisition] min_edge_snr (what fails an "
               "acquisition no_target on its first frame) is refuted as that failure would refute it and the "
               "hand-over counts as a failed one for the back-off, without leaving far range. On the "
               "campaign's approaches 185 of 341 failed acquisitions ended on their first frame, two mode "
               "changes each (stop 49); false: handed over, and failed there"},
              check_cue_before_handover);
    v.boolean({"navigation", "far_track_survives_unconfirmed", "-", 0, 1,
               "after an acquisition that failed at far range's cue with edges there (no_candidate, "
               "not_confirmed, ambiguous; not refuted), far range goes on tracking the cluster it handed "
               "over, its gate widened by the frames the acquisition took ([farrange] max_coast_frames "
               "still ends it). false: far range starts afresh and takes the largest plausible cluster, "
               "which may be clutter (campaign octagon/164: a glow of 10 000 px 21-25 deg off, taken after "
               "an attempt at 32 m and held for the rest of the approach; full run: 3 scenes up, no wrong "
               "frame, but 3 more approaches with more than 4 mode changes)"},
              far_track_survives_unconfirmed);
    v.integer(
        {"navigation", "reacquire_cue_starts", "count", 0, LocalSearchLimits::kMaxCueStarts,
         "close-range reacquisition: of the starts of a frame, this many go where the predicted outline, "
         "slid across the searched disc, best matches the frame's edges (polarity-free, either "
         "contrast), before the grid's outer rings: a target that moved while lost is found in one "
         "frame instead of when the grid walk reaches it; 0: grid only"},
        reacquire_cue_starts);
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
