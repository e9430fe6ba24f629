// The [navigation] table, part 1 of 2: mode hysteresis, fdir thresholds and the output gates.
// Names, units, ranges and texts of NavigationParams' fields (navigation_params.hpp, whose visit() walks
// both parts); apart from the struct so that each file stays readable. Reference: config/PARAMETERS.md.
#pragma once

namespace visnav::nav::detail {

template <typename Visitor, typename Params>
void visitModeAndGateParams(Visitor& v, Params& p) {
  v.enumeration(
      {"navigation", "start_mode", "-", 0, 3, "mode after start (standby waits for a resume command)"},
      "standby|far_range|acquisition|near_range", p.start_mode);
  v.real({"navigation", "handover_radius_px", "px", 5.0, 10000.0,
          "where acquire_below_m is 0 it is derived as f x bounding radius / this: the hand-over happens "
          "at the same apparent size for every target and camera (plate 2.3 x 1.8 m, f 1000 px: 42 m; 35 "
          "against 50 on two 100-scene campaign subsets: tracked 0.497 -> 0.521 and 0.615 -> 0.638, "
          "confidently wrong frames 27 -> 23 and 20 -> 23)"},
         p.handover_radius_px);
  v.real({"navigation", "near_range_min_radius_px", "px", 1.0, 10000.0,
          "where far_range_above_m is 0 it is derived as f x bounding radius / this: near range gives "
          "the target up to far range when it shrinks below this apparent radius (must be below "
          "handover_radius_px: the gap is the hysteresis; 26.25 = 35 x 3/4, the 4/3 distance ratio it "
          "was derived with before it became its own parameter)"},
         p.near_range_min_radius_px);
  v.real({"navigation", "acquire_below_m", "m", 0.0, 10000.0,
          "far range hands over to acquisition when its distance stays below this for enter_frames"},
         p.acquire_below_m);
  v.real({"navigation", "far_range_above_m", "m", 0.0, 10000.0,
          "near range falls back to far range when the distance stays above this for enter_frames "
          "(must exceed acquire_below_m: the gap is the hysteresis)"},
         p.far_range_above_m);
  v.integer({"navigation", "enter_frames", "count", 1, 1000,
             "consecutive frames a distance condition must hold before the mode changes"},
            p.enter_frames);
  v.boolean({"navigation", "close_count_survives_gaps", "-", 0, 1,
             "in far range, a frame without a fix neither counts towards enter_frames nor restarts the "
             "count (only a fix beyond acquire_below_m does); the hand-over itself needs a fix. Off: on "
             "campaign seeds 1-40, with [acquisition] outline_cue_min_edge_snr 3.5, it handed intermittent "
             "small cues over sooner: approach mode changes 121 -> 124, tracked frames 14 680 -> 14 671"},
            p.close_count_survives_gaps);
  v.integer({"navigation", "acquire_retry_holdoff_frames", "frames", 0, 100000,
             "after a failed or timed-out acquisition, far range does not hand over again for this many "
             "frames; the wait doubles with every consecutive failure (exponential back-off: a far-range "
             "cue that keeps fooling acquisition must not flip the mode every few frames)"},
            p.acquire_retry_holdoff_frames);
  v.integer({"navigation", "acquire_retry_holdoff_max_frames", "frames", 0, 100000,
             "upper bound of that back-off (40 frames: 8 s at 5 Hz), and the wait of acquire_retry_growth "
             "for a target that holds its range. 80 before stop 81; 40 alone on the 257 campaign "
             "approaches: tracked 4 403 -> 4 501 frames, 0 wrong, more than 4 mode changes 25 (README)"},
            p.acquire_retry_holdoff_max_frames);
  v.real({"navigation", "acquire_retry_growth", "-", 0.0, 1000.0,
          "after an acquisition that found edges at far range's cue but confirmed no pose there "
          "(no_candidate, not_confirmed, ambiguous), far range hands over again only once its distance "
          "is this many times below the one it handed over at (the target then spans as many times more "
          "pixels), or after acquire_retry_holdoff_max_frames: the same target at the same size fails the "
          "same way (case approach_smallsat: no_candidate at 157 m, ambiguous at 122 m, confirmed at "
          "69 m). <= 1: the back-off alone"},
         p.acquire_retry_growth);
  v.boolean({"navigation", "refused_handover_escalates_backoff", "-", 0, 1,
             "a hand-over refused for lacking edges at the cue (check_cue_before_handover) counts as a "
             "failed acquisition in the back-off: it waits, and doubles the wait of the next. Off: it waits "
             "the back-off of the acquisitions that failed so far and does not double it: a refusal changes "
             "no mode, and a dim target refused as it comes nearer is tried again at its next size, not "
             "held off ever longer (campaign cao/58: refused at 31, 27 and 21 m, waits of 5, 10 and 20 "
             "frames). Off alone, on the 257 campaign approaches "
             "(seeds 1-200, --kind approach): tracked 4 403 -> 4 470 frames, approaches acquired 114 -> "
             "117, 0 confidently wrong, more than 4 mode changes 25 -> 26. With "
             "acquire_retry_holdoff_max_frames 40 (the defaults since stop 81): 4 534 frames, acquired "
             "118, 0 wrong, more than 4 mode changes 28 (mean 2.18 -> 2.37, max 8 -> 12); seeds 1-40 "
             "(near scenes too): 15 595 -> 15 599, no near scene changed"},
            p.refused_handover_escalates_backoff);
  v.integer({"navigation", "acquisition_timeout_frames", "count", 1, 10000,
             "acquisition returns to far range when it has not succeeded within this many frames"},
            p.acquisition_timeout_frames);
  v.integer({"navigation", "fault_persistence_frames", "count", 1, 1000,
             "a near-range fault held for this many consecutive frames falls back to far range"},
            p.fault_persistence_frames);
  v.integer({"navigation", "coast_frames", "count", 0, 1000,
             "frames the Kalman prediction stands in for a failed near-range measurement (sec. II-H)"},
            p.coast_frames);
  v.real({"navigation", "min_inlier_ratio", "-", 0.0, 1.0,
          "FDIR: edge-point inlier ratio over the used lines below this is a fault"},
         p.min_inlier_ratio);
  v.integer({"navigation", "min_usable_lines", "count", 0, 1000, "FDIR: fewer used lines is a fault"},
            p.min_usable_lines);
  v.real({"navigation", "max_rms_px", "px", 0.001, 100.0, "FDIR: pose-fit residual above this is a fault"},
         p.max_rms_px);
  v.real({"navigation", "min_depth_m", "m", 0.0, 100000.0,
          "FDIR: plausible depth band, lower end; 0 derives the limit from the model: the camera cannot be "
          "inside the model's bounding box (model frame). Not its bounding sphere: the panels of case "
          "approach_smallsat make that 5.8 m in radius, and the approach ends at 5 m"},
         p.min_depth_m);
  v.real({"navigation", "max_depth_m", "m", 0.0, 100000.0,
          "FDIR: plausible depth band, upper end; 0 derives it from the model and camera: the depth at "
          "which the target spans 4 px (no 6-DOF fit is possible beyond)"},
         p.max_depth_m);
  v.real({"navigation", "max_frame_latency_ms", "ms", 0.0, 100000.0,
          "FDIR: a frame older than one camera frame period plus this when processed is a fault (the "
          "camera and the cycle free-run, so the newest frame is up to one period old by phase alone; the "
          "period is the interval between the last two exposures; 0 disables the check)"},
         p.max_frame_latency_ms);
  v.real({"navigation", "evidence_min_line_fraction", "-", 0.0, 1.0,
          "good image evidence: at least this share of the measured lines used (with the three below, "
          "the measurement wins over a filter that rejects it, and the filter restarts from it)"},
         p.evidence_min_line_fraction);
  v.real({"navigation", "evidence_min_inlier_ratio", "-", 0.0, 1.0,
          "good image evidence: edge-point inlier ratio over the used lines at least this. Under noise "
          "0.1 and blur a right fit keeps 0.6-0.7 of its points within the RANSAC band (campaign cao/5: a "
          "start on the target at 0.63-0.67, refused). 0.6 against 0.7 (stop 68, seeds 1-40 / 5001-5040 / "
          "7001-7040, 200 scenes each): tracked frames +64 / +55 / +26, confidently wrong frames "
          "unchanged (1 / 1 / 3)"},
         p.evidence_min_inlier_ratio);
  v.real({"navigation", "evidence_max_rms_px", "px", 0.001, 100.0,
          "good image evidence: pose-fit residual at most this"},
         p.evidence_max_rms_px);
  v.real({"navigation", "evidence_min_edge_support", "-", 0.0, 1.0,
          "good image evidence: inlier edge points per scanline cast at least this (the model's edges are "
          "where the image has them)"},
         p.evidence_min_edge_support);
  v.real({"navigation", "max_valid_attitude_sigma_deg", "deg", 0.0, 180.0,
          "a 6-DOF pose whose own 1-sigma attitude uncertainty (square root of the trace of its attitude "
          "covariance: the rms of the total rotation error) exceeds this is computed and tracked but not "
          "delivered as valid: 2.5 puts the 5 deg of a confidently wrong pose 2 sigma out (campaign "
          "plate/12: a 1.8 m plate at 21 m, 12 deg off from its true start; the paper's plate at 26 m on "
          "VGA: 2.2 deg); 0 switches the check off"},
         p.max_valid_attitude_sigma_deg);
  v.real({"navigation", "max_valid_position_sigma_rel", "-", 0.0, 1.0,
          "the same for the position: 1-sigma (square root of the trace) over the range. 0.0167 puts 5 % "
          "of the range 3 sigma out: the position's 1-sigma rarely comes near it, so the stricter bound "
          "costs little (campaign seeds 1-40, 200 scenes: 0.025 -> 0.0167 took tracked frames 14 721 -> "
          "14 698 and confidently wrong frames 7 -> 4, octagon/15 and octagon/29 at 5.1-6.8 % of the "
          "range with 1-sigma 1.8-2.3 %); 0 switches the check off"},
         p.max_valid_position_sigma_rel);
  v.boolean({"navigation", "deliver_filtered_pose", "-", 0, 1,
             "a near-range fit the filter accepted is delivered as the filter's estimate after it (pose and "
             "covariance, times the fit's systematic gain): it carries the frames before, so its 1-sigma is "
             "judged, by max_valid_* and the doubted limit, with what the track knows, not one frame alone. "
             "Only for a complete fit (every selected line found, no face seen as a narrow strip: "
             "nav::fitIsComplete) that is certain on its own (max_valid_*), whose error is mostly its own "
             "noise; a partial or uncertain fit's error repeats from frame to frame and averaging it only "
             "hides it (campaign box/25, box/37: with every accepted fit filtered, 5-14 deg off at 0.6-1.5 "
             "deg 1-sigma; plate/5023: uncertain complete fits filtered to 1.8 deg 1-sigma, 5.3 deg off), "
             "so it is delivered, and judged, as measured. Measured in the top-level README, stop 69; "
             "false: every pose is the fit's own"},
            p.deliver_filtered_pose);
  v.boolean({"navigation", "deliver_filtered_partial_fit", "-", 0, 1,
             "deliver_filtered_pose also for a partial fit: one that misses selected lines, but not so "
             "many that they doubt it (doubt_min_line_fraction, doubt_every_line_up_to: "
             "nav::fitDoubtedByItsLines), without a face seen as a narrow strip, certain on its own, on a "
             "track whose reacquisition find is no longer doubted (nav::fitMayBeFiltered). On since stop 71: "
             "+41 / +73 / +64 tracked frames on campaign seeds 1 / 5001 / 7001 (40 scenes a family), no "
             "confidently wrong frame more (top-level README, stops 70-71). Without the line test +246 / "
             "+200 / +123 frames, but 19 confidently wrong frames more on seed 5001 (box/5030: 5 of 8 lines, "
             "22-25 deg off at 1.4-2.6 deg 1-sigma, filtered to 0.7-0.9 deg); false: only complete fits"},
            p.deliver_filtered_partial_fit);
  v.real({"navigation", "doubted_max_attitude_sigma_deg", "deg", 0.0, 180.0,
          "a near-range pose that is doubted (the filter's innovation gate rejects it, fewer than "
          "doubt_min_line_fraction of its selected lines were used, or its track began with a "
          "reacquisition's find and none of its poses met this limit yet) is valid only with an attitude "
          "1-sigma of at most this: the track goes on with it either way, but a wrong fit has weak "
          "geometry and a doubt (campaign smallsat/83: 5 of 8 lines, 1.5 deg 1-sigma, 12 deg off for 37 "
          "frames). Full campaign: confidently wrong frames 396 -> 165, tracked mean 0.516 -> 0.505; on "
          "200 other scenes 63 -> 26, 0.545 -> 0.535; 0 switches the check off"},
         p.doubted_max_attitude_sigma_deg);
  v.real({"navigation", "doubt_min_line_fraction", "-", 0.0, 1.0,
          "a near-range pose is doubted when fewer than this share of its selected lines were used (the "
          "others were not found or rejected): it rests on part of the outline. 0.85 (2 of 8 doubted) "
          "fails case low_contrast_octagon: 1.00 -> 0.81 tracked (README, stop 47)"},
         p.doubt_min_line_fraction);
  v.real({"navigation", "doubt_nis_chi2", "-", 0.0, 1000.0,
          "a near-range pose the filter accepts with a NIS (6 dof) above this is doubted: the innovation "
          "gate ([filter] pose_gate_chi2, 99.9 %) lets through a fit one frame surprising enough that it "
          "is more often a spike than the target's motion; the filter still takes it, only its validity "
          "needs doubted_max_attitude_sigma_deg. 12.59 is the 95 % point (16.81, the 99 % point, until stop "
          "54). Single-frame spikes 5.2-5.9 deg off at 1.5-1.9 deg 1-sigma and NIS 17.5-20.5 (campaign "
          "octagon/2, smallsat/5017, smallsat/5026, octagon/5009; stop 52), and 5.3-6.6 deg off (plate/5009: "
          "7.3 % of the range) at 1.2-2.5 deg and NIS 12.7-16.8 (box/5034, plate/5009, octagon/7001, "
          "plate/7020; stop 54); "
          "measured in the top-level README; 0 switches it off"},
         p.doubt_nis_chi2);
  v.boolean(
      {"navigation", "doubt_after_filter_restart", "-", 0, 1,
       "the near-range fit on the frame after one whose image evidence overruled the filter's "
       "innovation gate (the filter restarted from it) is doubted: the filter it agrees with holds that "
       "one disputed fit only (campaign box/7 frame 142: 5.6 deg off at a 2.2 deg 1-sigma and NIS 5.4, "
       "the frame after a restart at NIS 57). Such frames on seeds 1-40, 5001-5040 and 7001-7040 (stop "
       "58-59 trees): 404 right within 1 deg 1-sigma (unchanged), 24 right above it, 1 wrong"},
      p.doubt_after_filter_restart);
  v.integer({"navigation", "doubt_every_line_up_to", "lines", 0, 1000,
             "a near-range pose with at most this many selected lines is doubted when any of them was not "
             "used: a small outline has no line to spare (campaign box/191: 4 of 5 lines, 5.0-5.5 deg off "
             "at 1.7-2.3 deg 1-sigma). Full campaign: confidently wrong frames 33 -> 28 (box/191 4 -> 0, "
             "cao/197 1 -> 0), tracked mean 0.622 -> 0.620; replayed on 200 other scenes and on the named "
             "cases, no change (5 instead of 6 the same); 0 switches it off"},
            p.doubt_every_line_up_to);
  v.integer({"navigation", "minimal_fit_max_missing_lines", "lines", -1, 1000,
             "a near-range pose fitted on 4 lines or fewer (4 vertices for 6 unknowns: a line fitted on "
             "the wrong edge is absorbed by the attitude instead of showing in the residual) is not valid "
             "when more than this many of its selected lines were not found: the pose predicts an outline "
             "the image does not show (campaign box/5030 at 21 m: 4 of 7 lines, 10-13 deg off at 0.6-0.9 "
             "deg 1-sigma). Tracked on; measured in the top-level README (stop 53); -1 switches it off"},
            p.minimal_fit_max_missing_lines);
  v.boolean({"navigation", "doubt_narrow_face", "-", 0, 1,
             "a near-range pose is doubted when a tracked face is seen nearly edge-on, as a strip "
             "narrower than [nearrange] confusable_edge_separation_px (the tracker's narrow-face flag): "
             "the lines beside it may be biased by up to the strip's width with a tight scatter, and "
             "a pose on them looks certain (campaign box/25: 5 of 6 lines at 0.02-0.08 px rms, 1.0-1.5 "
             "deg 1-sigma, 4.7-5.9 deg off)"},
            p.doubt_narrow_face);
  v.integer({"navigation", "doubt_clear_frames", "count", 1, 1000,
             "a track that began with a reacquisition's find stays doubted, and none of its poses is "
             "valid, until this many consecutive poses met doubted_max_attitude_sigma_deg (1: the first "
             "such pose ends the doubt and is valid). A find the image does not pin down alternates "
             "between certain and uncertain fits as its lines come and go (campaign box/191: found 1.6 m "
             "and 12 deg off, 1-sigma 0.30, 1.99, 0.36, 1.84, 1.95, 0.98, 0.39, 2.10 deg on consecutive "
             "frames; 13 confidently wrong frames with 1 or 2, none with 3). Measured, off: with 3 on seeds "
             "1-40, tracked 0.6500 -> 0.6358 and confidently wrong frames 18 -> 18 (a right find waits two "
             "frames more)"},
            p.doubt_clear_frames);
  v.real({"navigation", "disputed_max_look_change_deg", "deg", 0.0, 180.0,
          "a near-range pose the innovation gate rejects but the image supports (the measurement wins "
          "and the filter restarts from it) is not valid on that frame when its look (attitude along its "
          "line of sight, modulo symmetries: a slew does not change it) is more than this from the "
          "prediction's: no target tumbles that fast between two frames, a fit jumping to the wrong "
          "faces of a box does (campaign box/58: 10.7 deg in one frame, NIS 777, 0.4 deg 1-sigma). The "
          "track goes on from it; 0 switches the check off"},
         p.disputed_max_look_change_deg);
  v.real({"navigation", "disputed_max_range_change_rel", "-", 0.0, 10.0,
          "the same for the range: a disputed pose whose range differs from the prediction's by more "
          "than this share of it is not valid on that frame. The prediction carries the approach's speed, "
          "and a slew does not change the range; the image constrains depth least, and a fit that locks "
          "on another pair of edges jumps in it (campaign box/44: 8.6 % in one frame, NIS 2097, valid "
          "and wrong on that frame and the next). Full campaign: confidently wrong frames 96 -> 88, "
          "tracked 0.6237 -> 0.6228. The track goes on from it; 0 switches the check off"},
         p.disputed_max_range_change_rel);
  v.real({"navigation", "disputed_max_nis", "-", 0.0, 1e6,
          "or its NIS (6 dof) exceeds this, however little it turned or moved: the image supports it and "
          "the filter restarts from it, but on this frame it is as likely a lock on the wrong edges as the "
          "target's motion (campaign box/5018: 5.3 deg off at NIS 85 and 0.44 deg 1-sigma, its look 4.4 deg "
          "from the frame before's). Chi-square with 6 dof exceeds 80 with probability below 1e-14. "
          "Measured in the top-level README (stop 61); 0 switches it off"},
         p.disputed_max_nis);
  v.real({"navigation", "max_valid_view_angle_deg", "deg", 0.0, 90.0,
          "a 6-DOF pose on which no surface of the model faces the camera within this angle (between its "
          "outward normal and the line of sight to its centre) is tracked but not valid: seen edge-on, a "
          "plate's outline is a sliver whose opposite edges lie a few pixels apart, and its fit locks "
          "biased with a small covariance (stop 32's full run: 47 of its 139 confidently wrong frames, "
          "plates turning edge-on, 5-19 % of the range off with a 0.5-2.3 % 1-sigma; with the check on "
          "that run's plates, octagons and cao models: 71 -> 23 wrong frames for 22 of 64 239 expected "
          "frames). A box always shows a face within 55 deg (the cube's worst view, along a diagonal), so "
          "boxes and the satellite are not affected, flat models are; 0 switches the check off"},
         p.max_valid_view_angle_deg);
  v.real({"navigation", "start_pose_sigma_deg", "deg", 0.0, 180.0,
          "a start pose given by the operator (startNearRange, visnav-replay --initial-pose) starts the "
          "filter with this 1-sigma attitude uncertainty (square root of the trace), so the first "
          "measurements are checked against it instead of starting a track on their own: an ambiguous "
          "first fit no longer leaves the filter empty and the prediction frozen at the start pose "
          "(campaign box/26: lost on frame 3 of a 0.5 m/frame approach, then 180 frames of search at "
          "the start range); a measurement it rejects still wins with good image evidence; 0: the first "
          "measurement starts the filter, as before"},
         p.start_pose_sigma_deg);
  v.real({"navigation", "start_pose_sigma_rel", "-", 0.0, 1.0,
          "the same for the start pose's position: 1-sigma (square root of the trace) over the range"},
         p.start_pose_sigma_rel);
  v.real({"navigation", "start_pose_doubt_nis_chi2", "-", 0.0, 1000.0,
          "the first near-range fit after a start pose given by the operator is doubted (valid only "
          "within doubted_max_attitude_sigma_deg) when its NIS (6 dof) against that pose exceeds this: a "
          "start pose is a prior, not a track, and a first fit that disagrees with it more than half of "
          "consistent fits would has no motion to agree with, like a find. 5.35 is the chi-square median. "
          "Wrong first fits in the campaign (octagon/7, octagon/7028, plate/7032: 5.5-7.1 deg off at "
          "1.6-2.5 deg 1-sigma) had NIS 9.0-9.7; right ones 0.0-1.1 (90 %); the paper's plate 0.08. "
          "Measured in the top-level README (stop 54); 0 switches it off"},
         p.start_pose_doubt_nis_chi2);
  v.integer({"navigation", "start_pose_doubt_fits", "count", 0, 100,
             "how many near-range fits after a start pose are judged by start_pose_doubt_nis_chi2: the "
             "second fit's prediction still rests on the start pose and one fit, with no motion measured "
             "(campaign octagon/29: its second fit 6.2 deg off at 1.9 deg 1-sigma, NIS 11.9, below "
             "doubt_nis_chi2). Measured in the top-level README (stop 61); 1: the first fit only (stop 54); "
             "0 switches the check off"},
            p.start_pose_doubt_fits);
  v.integer({"navigation", "branch_confirm_frames", "count", 0, 1000,
             "a track's branch (which of two mirror poses, e.g. a plate's two tilts) is known from the given "
             "start pose, an acquisition or reacquisition confirmation, or this many consecutive valid "
             "frames whose fit had corners and no mirrored rival; any frame without a valid pose loses it. "
             "While it is unknown no pose is valid: a track carried through withheld frames can come out "
             "on the mirror branch, fitting the image as well with a tight covariance (campaign "
             "octagon/174: 26 withheld frames, then 66 valid ones 34-140 deg off); 0 switches the check "
             "off"},
            p.branch_confirm_frames);
  v.integer({"navigation", "narrow_confirm_max_lines", "count", 0, 1000,
             "a near-range fit beside a face seen as a narrow strip ([nearrange] kFlagNarrowFace) that used "
             "at most this many lines counts as rival-free toward branch_confirm_frames (and confirms an "
             "acquisition's hand-over) only when its attitude 1-sigma is at most "
             "narrow_confirm_max_attitude_sigma_deg: the strip's two lines are a large share of so few, and "
             "their bias, up to the strip's width, is not in the 1-sigma. Campaign box/7035: a find, then "
             "three strip fits of 5 lines at 0.85 deg 1-sigma confirmed the branch and four frames were "
             "delivered 5.0-5.4 deg off. On against off (7 lines, 0.3 deg; stop 74): see "
             "narrow_confirm_max_attitude_sigma_deg; 0 switches the rule off"},
            p.narrow_confirm_max_lines);
  v.real({"navigation", "narrow_confirm_max_attitude_sigma_deg", "deg", 0.0, 180.0,
          "see narrow_confirm_max_lines. Replayed (tools/campaign/gate_replay.py) on campaign seeds "
          "1 / 5001 / 7001 and on stop 72's full run: "
          "confidently wrong frames 10 / 2 / 0 / 4 -> 5 / 1 / 0 / 0 (full run / seeds 1 / 5001 / 7001, with "
          "narrow_break_reconfirms) for 349 / 72 / 59 / 187 of 77 243 / 15 591 / 15 564 / 15 800 tracked "
          "frames (boxes and smallsats; box/7025 -101: a box whose strip lasts, its right track reconfirmed "
          "later). At 0.5 deg one wrong frame more on the full run, at 0.0-0.4 the same 5; on at most 5 "
          "lines the wrong frames stay. 0 deg: no strip fit on so few lines confirms"},
         p.narrow_confirm_max_attitude_sigma_deg);
  v.real({"navigation", "narrow_break_max_fit_attitude_sigma_deg", "deg", 0.0, 180.0,
          "after a break in which a near-range fit beside a narrow strip (kFlagNarrowFace) was withheld, "
          "a fit counts toward branch_confirm_frames only when its own attitude 1-sigma (the fit's "
          "covariance with its systematic gain, before the filter of deliver_filtered_pose) is at most "
          "this: the strip's bias outlasts the flag (a pose turned by it hides the face), and the "
          "filter's estimate averages the fits as if their errors were independent while a biased fit "
          "repeats its error (campaign box/25: strip fits withheld on frames 0-4, then fits at 1.04-1.24 "
          "deg 1-sigma, filtered to 0.72-0.84, confirmed 5.5 deg off). After any break (the rule for "
          "every confirmation, replayed at 1 deg on seeds 1-40): tracked mean 0.686 -> 0.673, the far "
          "plates' right fits at 2 deg never confirmed. Measured in the top-level README (stop 75); 0 "
          "switches it off"},
         p.narrow_break_max_fit_attitude_sigma_deg);
  v.boolean({"navigation", "branch_confirm_needs_filter", "-", 0, 1,
             "a near-range fit the filter's innovation gate rejected (fault bit 0x10) counts toward none of "
             "the branch_confirm_frames: a confirmation needs consistency with the predicted motion, as an "
             "acquisition's does. Campaign box/5001: the tracker jumped at frame 173, the filter restarted "
             "from the fits it had rejected, and three rival-free frames confirmed that track 13.6 % off in "
             "range, the third of them rejected at NIS 56. Measured in the top-level README (stop 54); "
             "false: rejected fits count"},
            p.branch_confirm_needs_filter);
  v.boolean({"navigation", "mirror_resolved_by_prediction", "-", 0, 1,
             "a near-range fit whose depth-mirrored rival explains its lines as well (the tracker's "
             "kFlagAmbiguous: a plate's other tilt, a box's Necker reversal) still counts as rival-free "
             "toward branch_confirm_frames when the track continues the last valid pose (or the "
             "operator's start pose) without a filter restart since, the filter accepted the fit, and "
             "its prediction rejects the rival ([filter] pose_gate_chi2): the image cannot tell the two "
             "apart, the motion can. Without it such fits break every count: on campaign seeds 1-40, 211 "
             "frames of right poses were withheld for the branch alone with the flag set (octagon/11, /15 "
             "and /20 the most). Measured in the top-level README, stop 60; false: an ambiguous fit is "
             "never rival-free"},
            p.mirror_resolved_by_prediction);
  v.boolean({"navigation", "branch_range_after_jump", "-", 0, 1,
             "after a disputed jump breaks the branch, a near-range fit counts toward none of the "
             "branch_confirm_frames unless its range stays within disputed_max_range_change_rel (widened "
             "by branch_range_growth_rel_per_frame per frame since and by three 1-sigma of the reference "
             "carried on) of the span from the last valid pose's range, standing still, to that range "
             "carried on at its rate: the filter restarted on the jumped track has lost that reference. "
             "The reference is the filter's range, rate and their covariance on the last valid frame, "
             "and only when that frame ended branch_range_reference_min_frames valid poses in a row. "
             "Campaign smallsat/7023: the tracker jumped 13 % in range at frame 95, the filter restarted "
             "there and accepted the frames after, and three of them were confirmed 16-17 % off. Stop 54 "
             "built it with the fit's range carried on at the filter's rate after any valid pose and left "
             "it off: box/7036's right track after a jump was withheld for the rest of the scene (a "
             "reference one frame after a find, its range rate 0.00 m/s at 0.05 m/s 1-sigma while the target "
             "closed at 2 m/s). On since stop 67: on seeds "
             "1-40 / 5001-5040 / 7001-7040 it removes smallsat/7023's 3 wrong frames and changes no other "
             "delivered pose. Top-level README, stops 54 and 67; false: no range check"},
            p.branch_range_after_jump);
  v.real({"navigation", "branch_range_growth_rel_per_frame", "-", 0.0, 1.0,
          "the widening of branch_range_after_jump's range tolerance per frame since the last valid pose"},
         p.branch_range_growth_rel_per_frame);
  v.integer({"navigation", "branch_range_reference_min_frames", "count", 1, 1000,
             "branch_range_after_jump's reference is the last valid pose only when it ends at least this "
             "many valid poses in a row: the filter's range rate, which carries the reference on, is "
             "measured by a run of fits (three give a rate, as [filter] restart_rate_chi2's restart from "
             "three fits); after one or two following a start or a find it is about the prior's zero with a "
             "confidence the motion has not earned. Campaign smallsat/14: valid once at 42 m after an "
             "acquisition, closing at 3.9 m/s, the filter's range rate -0.15 m/s at 0.47 m/s 1-sigma; "
             "with stop 54's form of the rule (any valid pose a "
             "reference) the right track after a jump three frames later was withheld for the rest of the "
             "approach (38 -> 0 tracked expected frames). 1: every valid pose"},
            p.branch_range_reference_min_frames);
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
      p.acquisition_awaits_near_range);
  v.boolean(
      {"navigation", "handover_needs_whole_outline", "-", 0, 1,
       "the first near-range fit after an acquisition (acquisition_awaits_near_range) confirms its branch "
       "only if it measured interior edges or every selected outline line: an outline-only fit that "
       "missed a line (tracker flags 0x200 and 0x4) is what a wrong pose with a matching outline leaves "
       "(campaign octagon/62 on the full run of seeds 1-200, stop 71: an acquisition 120 deg off whose "
       "depth-reversed twin was 3 deg from the truth, confirmed by a 5-of-7-line outline fit at 0.5 deg "
       "1-sigma). Such a fit counts as one of branch_confirm_frames instead. Measured in the top-level "
       "README, stop 72; false: any valid rival-free fit confirms"},
      p.handover_needs_whole_outline);
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
            p.branch_continuity_frames);
  v.real({"navigation", "branch_continuity_look_deg", "deg", 0.0, 180.0,
          "see branch_continuity_frames: the look tolerance on the frame right after the last valid "
          "pose"},
         p.branch_continuity_look_deg);
  v.integer({"navigation", "branch_continuity_missing_lines", "count", 0, 64,
             "see branch_continuity_frames: a fit may also keep the branch with up to this many of its "
             "selected lines not found, when that is its only degradation (no residual above "
             "[nearrange] degraded_rms_px, no point-to-line fallback, no mirrored or near-twin rival, no "
             "face seen as a narrow strip); the other conditions hold as for a clean fit. On campaign "
             "seeds 1-40, 51 of the 372 right poses withheld for the branch alone after a break of 1-3 "
             "frames were such fits with one line missing, and none of the 2 wrong ones. 1 against 0 on "
             "seeds 1 / 5001 / 7001: tracked frames 15 176 / 15 103 / 15 486 -> 15 242 / 15 163 / "
             "15 527, every scene that changed gained, confidently wrong frames 1 / 1 / 6 unchanged "
             "(top-level README, stop 65). 0: status tracking only"},
            p.branch_continuity_missing_lines);
  v.integer({"navigation", "branch_continuity_spotless_frames", "count", 0, 1000,
             "see branch_continuity_frames: after a longer break, of at most this many frames, a fit "
             "keeps the branch only when it is spotless: status tracking with no tracker flag but the "
             "informational texture fallback (no face seen as a narrow strip, no line rejected), and the "
             "other conditions as for a clean fit. 10 against 0 on campaign seeds 1 / 5001 / 7001 (stop "
             "66): tracked frames 15 242 / 15 163 / 15 527 -> 15 258 / 15 190 / 15 557, every scene that "
             "changed gained, confidently wrong frames 1 / 1 / 6 unchanged; at or below "
             "branch_continuity_frames: off"},
            p.branch_continuity_spotless_frames);
  v.boolean(
      {"navigation", "narrow_break_reconfirms", "-", 0, 1,
       "no fit keeps the branch by continuity (branch_continuity_frames) across a break in which a "
       "near-range fit beside a face seen as a narrow strip ([nearrange] kFlagNarrowFace) was "
       "withheld: such a strip's lines may be biased by its width, and a clean-looking fit after it "
       "can carry the bias; the branch then waits for branch_confirm_frames rival-free frames. "
       "Campaign box/129: fits withheld on frames 114-115 (a mirrored rival, then the strip), and "
       "frame 116 kept the branch 6.3 deg off. On against off, campaign seeds 1 / 5001 / 7001 (stops "
       "73-74): tracked frames 15 602 / 15 572 / 15 809 -> 15 591 / 15 564 / 15 800, confidently "
       "wrong 2 / 0 / 4 unchanged; with narrow_confirm_max_lines on the full run 13 -> 5 wrong frames for "
       "411 of 77 292 tracked frames (top-level README, stop 74)"},
      p.narrow_break_reconfirms);
  v.integer({"navigation", "filter_diverged_rejections", "count", 1, 1000,
             "a clean (tracking) measurement the filter rejects this many times in a row restarts the "
             "filter from it"},
            p.filter_diverged_rejections);
  v.integer({"navigation", "far_filter_reset_rejections", "count", 1, 1000,
             "far range: the filter restarts from the next fix after this many rejected fixes in a row"},
            p.far_filter_reset_rejections);
}

}  // namespace visnav::nav::detail
