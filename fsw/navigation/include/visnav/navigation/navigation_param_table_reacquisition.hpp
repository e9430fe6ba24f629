// The [navigation] table, part 2 of 2: the close-range reacquisition and the far-range hand-over checks.
// Names, units, ranges and texts of NavigationParams' fields (navigation_params.hpp, whose visit() walks
// both parts); apart from the struct so that each file stays readable. Reference: config/PARAMETERS.md.
#pragma once

namespace visnav::nav {

/// Compile-time capacities of the close-range reacquisition.
struct LocalSearchLimits {
  static constexpr int kMaxCueStarts = 8;
};

namespace detail {

template <typename Visitor, typename Params>
void visitReacquisitionParams(Visitor& v, Params& p) {
  v.real({"navigation", "break_nis_chi2", "-", 0.0, 1e6,
          "below the far-range hand-over, a near-range fit whose image evidence is not good and that the "
          "filter rejects with an NIS (6 dof) above this ends the track on its frame: close-range "
          "reacquisition searches from the prediction at once instead of coasting on such fits until "
          "the tracker loses the target (campaign smallsat/36: after an 8.3 deg slew four fits on 4-7 of "
          "17 lines, NIS 144-1784, were coasted on before the search began: found 2 frames after the slew "
          "instead of 10). On campaign seeds 1-40 / 5001-5040 / 7001-7040 (stop 79): tracked frames 15 586 / "
          "15 511 / 15 585 -> 15 595 / 15 517 / 15 593, 7 scenes gained, none lost a frame, none wrong; "
          "slews tracked again within 5 frames 36 / 31 / 28 -> 37 / 32 / 28. 0: off"},
         p.break_nis_chi2);
  v.real({"navigation", "break_max_line_fraction", "-", 0.0, 1.0,
          "break_nis_chi2 ends the track only on a fit that used fewer than this share of its selected "
          "lines: a plate fit that lost one of its four lines reads NIS 336-1121 for a frame and is "
          "accepted by the filter on the next (campaign plate/28, plate/37, and box/23 at 5 of 6 lines: "
          "with any share those three lost 26 tracked frames on seeds 1-40, 1 frame fewer net), while "
          "a slew leaves 3-7 of 8-17 lines on clutter"},
         p.break_max_line_fraction);
  v.integer({"navigation", "reacquire_hypotheses_per_frame", "count", 1, 1000,
             "close-range reacquisition: tracker starts tried per frame (bounds the frame's cost)"},
            p.reacquire_hypotheses_per_frame);
  v.integer({"navigation", "reacquire_scanline_half_length_px", "px", 2, 64,
             "close-range reacquisition: scanline half length of its wide tracker (its capture range)"},
            p.reacquire_scanline_half_length_px);
  v.real({"navigation", "reacquire_step_rel", "-", 0.1, 2.0,
          "close-range reacquisition: spacing of the lateral search grid as a share of the capture range"},
         p.reacquire_step_rel);
  v.real({"navigation", "reacquire_growth_px_per_frame", "px", 1.0, 10000.0,
          "close-range reacquisition: the searched radius around the prediction grows this much per frame. "
          "Stop 58 measured 120 with find_prediction_look_deg: tracked frames 14 703 -> 14 819 on seeds "
          "1-40 against that rule alone, 14 861 -> 14 852 and 15 315 -> 15 320 on seeds 5001-5040 and "
          "7001-7040 against stop 57 (rule included), slews recovered within 5 frames 29 -> 31 of 38 on "
          "the first set only, confidently wrong unchanged; but the wider disc coarsens the outline cue (its "
          "window is "
          "160 working px a side), and octagon/167's 7.8 deg slew (96 px) with the confirmation through "
          "ambiguity was then found 60 frames late (0.669 -> 0.561 tracked). Kept at 40"},
         p.reacquire_growth_px_per_frame);
  v.integer({"navigation", "reacquire_confirm_frames", "count", 1, 100,
             "close-range reacquisition: frames a found pose must keep tracking before it is delivered"},
            p.reacquire_confirm_frames);
  v.boolean({"navigation", "reacquire_confirm_through_ambiguity", "-", 0, 1,
             "close-range reacquisition (experimental, off): a confirming fit flagged ambiguous (its "
             "depth-mirrored rival fits as well) confirms the rival-free candidate when its evidence is "
             "otherwise good and it continues it (reacquire_max_motion_rel, reacquire_max_rotation_deg). "
             "Campaign octagon/167: 13 -> 106 of 157 frames tracked. Off because on the full campaign it "
             "took tracked frames 75 407 -> 75 533 and confidently wrong 88 -> 89 (box/95: a find 5.5 deg "
             "off; fsw/navigation/README.md). false: an ambiguous fit ends the confirmation"},
            p.reacquire_confirm_through_ambiguity);
  v.boolean({"navigation", "reacquire_confirm_at_cue", "-", 0, 1,
             "close-range reacquisition: a confirming frame on which the trackers started at the candidate "
             "(carried by its measured motion once known) find no good fit starts the wide tracker once "
             "more where the candidate's outline, slid over a disc of f x reacquire_max_motion_rel "
             "pixels about it, best matches the frame's edges: the first confirmation has no motion to "
             "carry the candidate by, and a target crossing the image faster than the flight tracker's "
             "capture range was found and lost again frame after frame (campaign cao/5: found on frames "
             "1, 4 and 8, 15-18 px a frame, never confirmed). The fit must still be good image evidence, "
             "within reacquire_max_motion_rel and reacquire_max_rotation_deg of the candidate and "
             "consistent with the prediction. false: the confirmation ends"},
            p.reacquire_confirm_at_cue);
  v.real({"navigation", "reacquire_range_tolerance_rel", "-", 0.001, 10.0,
          "close-range reacquisition: a candidate whose range differs from the predicted range by more than "
          "this share is not taken (a few outline lines of a small body also fit a mirrored pose at another "
          "range: campaign box/1 was re-found 25 % off; at 0.1 box/26 was re-found 8.7 % off with two edges "
          "on the wrong image lines and held: on the full campaign 0.05 gives 306 confidently wrong frames "
          "instead of 407 for 0.7 points of tracked mean)"},
         p.reacquire_range_tolerance_rel);
  v.real({"navigation", "reacquire_attitude_tolerance_deg", "deg", 0.1, 180.0,
          "close-range reacquisition: largest attitude difference between a candidate and the prediction, "
          "both seen along their own line of sight (a slew moves the target, not its look), modulo the "
          "model's symmetries"},
         p.reacquire_attitude_tolerance_deg);
  v.real({"navigation", "reacquire_tolerance_growth_deg_per_frame", "deg", 0.0, 180.0,
          "close-range reacquisition: the attitude tolerance grows this much per frame searched (the "
          "prediction ages; 1 deg/frame is the fastest tumble the campaign draws)"},
         p.reacquire_tolerance_growth_deg_per_frame);
  v.real({"navigation", "reacquire_max_motion_rel", "-", 0.001, 1.0,
          "close-range reacquisition: largest position change per frame (share of the range) that counts "
          "as consistent motion while confirming"},
         p.reacquire_max_motion_rel);
  v.real({"navigation", "reacquire_max_rotation_deg", "deg", 0.01, 180.0,
          "close-range reacquisition: largest attitude change per frame while confirming"},
         p.reacquire_max_rotation_deg);
  v.integer({"navigation", "reacquire_timeout_frames", "count", 1, 100000,
             "close-range reacquisition searching longer than this hands over to far range"},
            p.reacquire_timeout_frames);
  v.integer({"navigation", "reacquire_acquisition_after_frames", "count", 0, 100000,
             "close-range reacquisition: after this many frames without a find, acquisition (attitude grid "
             "x range steps) also searches each frame, cued by the filter's prediction with the lateral "
             "search radius as its direction margin: an approaching or tumbling target leaves the "
             "prediction's range and look, which the local search keeps. A find is taken only from a vertex "
             "fit without a mirrored rival and with a look that agrees with the last valid pose "
             "(reacquire_attitude_tolerance_deg widening per frame since it), and is doubted "
             "(doubted_max_attitude_sigma_deg). Full campaign (with 0 -> 5): tracked mean 0.505 -> 0.547, "
             "recoveries that never came 544 -> 451, "
             "confidently wrong frames 165 -> 193; 0: never"},
            p.reacquire_acquisition_after_frames);
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
            p.reacquire_far_cue);
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
            p.reacquire_acquisition_tiles);
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
            p.reacquire_acquisition_outline_cue);
  v.boolean({"navigation", "reacquire_range_ladder", "-", 0, 1,
             "close-range reacquisition (experimental, off): every other attempt of that acquisition "
             "cued by the prediction steps through ranges about the prediction's (the others stay at "
             "it): (1 + [acquisition] range_span_rel)^2 times nearer, farther, twice nearer, ... (each "
             "attempt covers its range / (1 + span) .. x (1 + span): no gaps), within the target's "
             "bounding radius and far_range_above_m, round again after the last. A search keeps the "
             "range the track was lost at, and a target that approaches or recedes meanwhile leaves "
             "every attempt's range (campaign octagon/19: lost at 24.8 m by a slew, the prediction still "
             "at 24 m when the target was at 10 m; with it 0 -> 53 of 108 tracked, box/23 20 -> 66). Off "
             "because the rung attempts take the frames on which an attempt at the prediction's range "
             "would have found a target that stayed there (smallsat/22 43 -> 0, plate/26 113 -> 79); "
             "measured in the top-level README, stop 60. true: used"},
            p.reacquire_range_ladder);
  v.boolean({"navigation", "reacquire_range_rate_rung", "-", 0, 1,
             "close-range reacquisition: where the track left with a range rate significant on its own "
             "(PoseFilter::significantRangeRate) that the search's prediction drops "
             "(reacquire_drop_insignificant_rates: the start-at-rest prior covers it), every other frame of "
             "the local search (kept while its candidate is confirmed) and every other attempt of the "
             "close-range acquisition cued by the prediction start at the range that rate reached since "
             "the search began, within the target's bounding radius and far_range_above_m, once it is "
             "more than reacquire_range_tolerance_rel off the prediction's. The other frames and attempts "
             "stay at the prediction's range. An approach lost by a slew or an eclipse keeps closing "
             "while the prediction stays where it was lost (campaign octagon/19: lost at 24.8 m closing "
             "at 1.0 m/s, the prediction 56 % too far 42 frames later, 0 of 108 tracked); a target the "
             "track saw still has no rate, and its search is as without this. Measured in the top-level "
             "README, stop 76. true: used"},
            p.reacquire_range_rate_rung);
  v.boolean({"navigation", "reacquire_rate_rung_valid_track_only", "-", 0, 1,
             "the rate rung (reacquire_range_rate_rung) takes the track's range rate only where the track "
             "was delivered valid: its last valid pose closed a run of branch_range_reference_min_frames "
             "valid poses and the filter was not restarted after it. A rate measured by fits never "
             "delivered, or restarted from fits that were not, carries their error into every other "
             "search frame (campaign box/5030: never valid before its loss, the track 24.7 deg off and its "
             "rate closing while the prediction was already short; box/25: restarted at 3.2 m/s from "
             "biased strip fits). Measured in the top-level README, stop 77. true: used"},
            p.reacquire_rate_rung_valid_track_only);
  v.boolean(
      {"navigation", "reacquire_motion_hedge", "-", 0, 1,
       "close-range reacquisition: on the local search's frames the rate rung leaves to the "
       "prediction (no rung, or none this frame), start at the filter's position when the search "
       "began instead, with the prediction's attitude, once the prediction has moved more than "
       "reacquire_range_tolerance_rel of the range from it. The filter carries the velocity it "
       "left with in a straight line, and a target swinging sideways turns back (campaign "
       "plate/5004: 2 m/s when a 6.2 s eclipse began, the prediction 13 m off at reappearance, "
       "the last trusted pose 3.4 m). A find there is judged against the held start. Off: on "
       "campaign seeds 1-40 / 5001-5040 / 7001-7040 tracked frames 15 586 / 15 511 / 15 585 -> 15 578 / "
       "15 508 / 15 580, no scene gained, none wrong either way (half the searching frames leave the "
       "prediction, where a target that kept its motion is); top-level README, stop 78. true: used"},
      p.reacquire_motion_hedge);
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
            p.find_confirms_only_from_reference);
  v.real({"navigation", "branch_reference_max_look_deg", "deg", 1.0, 180.0,
          "find_confirms_only_from_reference: the last valid pose confirms a find's branch only while "
          "its look tolerance (reacquire_attitude_tolerance_deg + reacquire_tolerance_growth_deg_per_frame "
          "per frame since it) is at most this. At 45 deg, half the quarter turn that is a near-square "
          "target's nearest twin (a wider tolerance keeps both twins), a find past it is still taken but "
          "earns its branch with branch_confirm_frames rival-free frames. 45 since stop 57, with "
          "[farrange] min_outline_sharpness: far range no longer holds blobs, and the changed searches "
          "found campaign box/7's flat-shaded box 107 frames after its last valid pose, 32 deg off with a "
          "0.95 deg 1-sigma, valid on its own frame (4 confidently wrong frames); at 45 it is withheld. "
          "Cost, seeds 1-40 / 5001-5040 / 7001-7040 with the sharpness rule: tracked frames 14 756 -> "
          "14 675 / 14 924 -> 14 861 / 15 381 -> 15 315 (finds wait their rival-free frames), confidently "
          "wrong 6 -> 2 / 2 -> 2 / 7 -> 7. Stop 52, without the sharpness rule: it removed no confidently "
          "wrong frame on seeds 1-40 and cost 76 tracked frames. 180: the reference never expires"},
         p.branch_reference_max_look_deg);
  v.real({"navigation", "find_prediction_look_deg", "deg", 0.0, 45.0,
          "find_confirms_only_from_reference: a find also confirms the branch when the filter still "
          "carries the last valid pose (or the start pose) by its motion model alone (no measurement or "
          "restart since: a track that ended valid and coasted) and the find's look is within this of "
          "that prediction, however old the reference. A fixed tolerance, well inside the nearest twins "
          "(a quarter turn, twice a plate's tilt). 0: off"},
         p.find_prediction_look_deg);
  v.boolean(
      {"navigation", "reacquire_carry_angular_rate", "-", 0, 1,
       "a find that lies on the last valid pose as the filter carried it (find_prediction_look_deg) "
       "restarts the filter with the angular rate it carried, instead of at rest: a tumbling "
       "target's next fits otherwise disagree with a static prediction and are rejected (campaign "
       "smallsat/5035: re-found after an 8.6 deg slew, then 5 rejected frames, lost for 38; with it "
       "148 of 151 tracked). Stop 58, seeds 1-40 / 5001-5040 / 7001-7040 with the growth at 120: "
       "tracked frames 14 819 -> 14 841 / 14 852 -> 14 890 / 15 320 -> 15 324, confidently wrong unchanged; "
       "at the shipped 40, with find_prediction_look_deg, against stop 57: 14 675 -> 14 710 / 14 861 -> "
       "14 865 / 15 315 -> 15 319 (octagon/32 133 -> 103 with the rate, smallsat/14 7 -> 34)"},
      p.reacquire_carry_angular_rate);
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
            p.follow_near_twin);
  v.boolean({"navigation", "reacquire_twin_continuity", "-", 0, 1,
             "close-range reacquisition: that acquisition does not refuse a candidate whose near twin "
             "the image cannot resolve ([acquisition] near_twin_min_separation_px) when the last valid "
             "pose's look (reacquire_attitude_tolerance_deg widening per frame) keeps the candidate "
             "and not the twin; the find is flagged (campaign --trace). Campaign box/44 (quarter-turn "
             "twin 1.2 px apart at 14 m): tracked 0.05 -> 0.81; false: the twin always refuses"},
            p.reacquire_twin_continuity);
  v.boolean(
      {"navigation", "reacquire_drop_insignificant_rates", "-", 0, 1,
       "when close-range reacquisition starts, the filter's velocity and angular velocity are each "
       "set to zero unless significant ([filter] restart_rate_chi2 against their own covariance, "
       "the velocity also against the start-at-rest prior; PoseFilter::dropInsignificantRates): "
       "the search is predicted from the filter, and a rate read from the last noisy fits carried "
       "the prediction away from a target that did not move (campaign box/129: 19 m and 82 deg "
       "off 100 frames into the search, never found). false: the search carries the filter's rates as they "
       "are"},
      p.reacquire_drop_insignificant_rates);
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
         p.reacquire_motion_decay_s);
  v.boolean({"navigation", "refute_unconfirmed_cue", "-", 0, 1,
             "an acquisition that failed at far range's cue with edges there (no_candidate, not_confirmed, "
             "ambiguous) refutes that fix as one that found no edges (no_target) does: far range passes "
             "over the region until it has grown 4x in n or [farrange] refuted_fix_frames passed. Off: "
             "acquire_retry_growth handles that failure instead, and far range keeps reporting the target. "
             "Measured on seeds 1-40 of plate, octagon and box (100 scenes, restart and growth off): "
             "tracked 0.621 -> 0.619, wrong frames 36 -> 32; it passed over a satellite acquisition could "
             "not yet confirm at 80 m and handed over clutter instead (campaign smallsat/6: 1.0 -> 0)"},
            p.refute_unconfirmed_cue);
  v.boolean({"navigation", "check_cue_before_handover", "-", 0, 1,
             "before far range hands its fix to acquisition, the acquisition's first test runs on this "
             "frame: a cue whose window's edge SNR is under [acquisition] min_edge_snr "
             "(outline_cue_min_edge_snr for a fix far range found by its outline; what fails an acquisition "
             "no_target on its first frame) is refuted as that failure would refute it and the hand-over "
             "counts as a failed one for the back-off, without leaving far range. On the campaign's "
             "approaches 185 of 341 failed acquisitions ended on their first frame, two mode changes each "
             "(stop 49); false: handed over, and failed there"},
            p.check_cue_before_handover);
  v.boolean(
      {"navigation", "acquire_beside_far_range", "-", 0, 1,
       "a hand-over starts the acquisition beside far range: far range keeps its mode and its fixes while "
       "acquisition searches and confirms, and the mode changes once, to near range, when a pose is "
       "confirmed. A failed acquisition then changes no mode (off: far range -> acquisition -> far range, "
       "two mode changes per failure). Campaign seeds 1-40 / 41-80 / 81-120: mode changes 101 -> 36, "
       "146 -> 42, 159 -> 35 (the most on an approach 7, 12, 12 -> 1, 1, 3), tracked +14, +19, +42, 0 "
       "wrong"},
      p.acquire_beside_far_range);
  v.boolean({"navigation", "far_track_survives_unconfirmed", "-", 0, 1,
             "after an acquisition that failed at far range's cue with edges there (no_candidate, "
             "not_confirmed, ambiguous; not refuted), far range goes on tracking the cluster it handed "
             "over, its gate widened by the frames the acquisition took ([farrange] max_coast_frames "
             "still ends it). false: far range starts afresh and takes the largest plausible cluster, "
             "which may be clutter (campaign octagon/164: a glow of 10 000 px 21-25 deg off, taken after "
             "an attempt at 32 m and held for the rest of the approach; full run: 3 scenes up, no wrong "
             "frame, but 3 more approaches with more than 4 mode changes)"},
            p.far_track_survives_unconfirmed);
  v.integer({"navigation", "reacquire_cue_starts", "count", 0, LocalSearchLimits::kMaxCueStarts,
             "close-range reacquisition: of the starts of a frame, this many go where the predicted outline, "
             "slid across the searched disc, best matches the frame's edges (polarity-free, either "
             "contrast), before the grid's outer rings: a target that moved while lost is found in one "
             "frame instead of when the grid walk reaches it; 0: grid only"},
            p.reacquire_cue_starts);
  v.real({"navigation", "reacquire_cue_min_radius_deg", "deg", 0.0, 45.0,
          "close-range reacquisition: the outline cue (reacquire_cue_starts) slides over a disc of at least "
          "this angular radius about the prediction (f tan of it in pixels) from the first searched frame, "
          "while the grid's disc grows by reacquire_growth_px_per_frame: a slew moves the target by its "
          "angle at once (3-10 deg in the campaign, 30-250 px), which the grown disc reaches only on "
          "frame 1-6; 0: the cue's disc is the grid's"},
         p.reacquire_cue_min_radius_deg);
}

}  // namespace detail
}  // namespace visnav::nav
