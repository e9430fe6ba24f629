#!/usr/bin/env python3
"""Replays visnav's output gates over a campaign's frames.csv (visnav-campaign --frames).

Whether a pose is delivered as valid does not feed back into the tracking: the same frames are tracked, the
same filter updated, whatever the gates decide (two exceptions: the close-range reacquisition checks its
finds' look against the last valid pose, and the tracker refits near twins only while the branch is
unconfirmed and, since stop 51, hands a withheld track that lost lines to its near twin (follow_near_twin) and
lets a find confirm the branch only against the last valid pose, so a withheld pose can change a later
search, fit or verdict; tools/campaign/README.md).
frames.csv records each frame's candidate pose (delivered or
withheld) with its errors, its own sigmas and the tracker's flags, so a gate can be judged offline over a
whole 1000-scene run in seconds instead of a 30-minute rerun. The gates replayed, with the shipped defaults:

  certainty   candidate with attitude 1-sigma <= --attitude-sigma-deg and position 1-sigma / range
              <= --position-sigma-rel ([navigation] max_valid_attitude_sigma_deg / _position_sigma_rel)
  doubt       a near-range candidate the filter's innovation gate rejected (fault bit 0x10), that used
              fewer than --doubt-min-line-fraction of its selected lines or left out any of at most
              --doubt-every-line-up-to ([navigation] doubt_every_line_up_to), beside a face the tracker
              saw as a narrow strip (near_flags 0x1000; [navigation] doubt_narrow_face, --no-narrow-face-doubt
              ignores it), that the filter accepted with a NIS above --doubt-nis-chi2 ([navigation]
              doubt_nis_chi2, frames.csv column nis), one of the first --start-pose-doubt-fits fits after the
              operator's start pose ([navigation] start_pose_doubt_fits: 2 since stop 61, 1 before) whose
              NIS exceeds --start-pose-doubt-nis ([navigation] start_pose_doubt_nis_chi2, stop 54), of the
              first --start-pose-doubt-frames frames of a
              scene that starts in near range from the operator's pose (not shipped: built and measured in
              stop 53, README), whose track began with a reacquisition's find and has not yet had a pose
              within the doubted limit, or that follows a candidate the filter rejected and the pipeline
              still delivered, i.e. restarted the filter from ([navigation] doubt_after_filter_restart,
              stop 59; replayed since stop 61, --no-doubt-after-restart ignores it)
              needs attitude 1-sigma <=
              --doubted-attitude-sigma-deg ([navigation] doubted_max_attitude_sigma_deg /
              doubt_min_line_fraction; 0 switches it off)
  branch      track_branch.hpp ([navigation] branch_confirm_frames): after --break-after frames in a row
              without a certain pose, nothing is valid until --branch-confirm-frames consecutive certain
              frames whose tracker flags have none of --rival-flags (plus kFlagNarrowFace for a fit on at
              most --narrow-confirm-max-lines lines, 7, 0 off, whose attitude 1-sigma is above
              --narrow-confirm-max-attitude-sigma-deg, 0.3; stop 74; less kFlagAmbiguous where the pipeline
              resolved the mirror by the prediction, column mirror_resolved, stop 61; --no-mirror-resolved
              ignores it), without a near-twin rival the
              pipeline counted (frames.csv column near_twin_rival) and not rejected by the filter (fault bit
              0x10; [navigation] branch_confirm_needs_filter, stop 54; --no-branch-confirm-needs-filter
              counts them), after a break in which a candidate beside a narrow strip (near_flags 0x1000)
              was withheld only with its own fit's attitude 1-sigma, before the filter, at most
              --narrow-break-max-fit-attitude-sigma-deg (1.0, 0 off; [navigation]
              narrow_break_max_fit_attitude_sigma_deg, stop 75; column fit_attitude_sigma_deg, written since
              stop 75: a run without it replays a filtered frame at the filter's sigma), or an acquisition /
              reacquisition
              confirmation (unless --no-confirmed-sources), or a certain near-range frame the pipeline
              judged to have kept the branch by continuity (frames.csv column kept_branch: a clean fit,
              accepted by the filter, within the doubted sigma limit, whose look stayed with the last valid
              pose's after a break of at most [navigation] branch_continuity_frames; as the pipeline judged
              it, so exact only with the shipped gates; --no-branch-continuity ignores it;
              --narrow-break-reconfirms: not across a break in which a near-range candidate flagged as
              beside a narrow strip, near_flags 0x1000, was withheld; shipped since stop 74, where
              kept_branch already carries it: the option models it on runs made without it)
  awaited     an acquisition's pose is not valid on its own frame; the next frame confirms the branch if it is
              a near-range frame with a certain, rival-free pose ([navigation] acquisition_awaits_near_range;
              --no-acquisition-await: valid on its own frame and confirming, as before) that is not an
              outline-only fit missing a line ([navigation] handover_needs_whole_outline, stop 72;
              --no-handover-whole-outline: any such fit confirms)
  view        a candidate that showed no face of the model within [navigation] max_valid_view_angle_deg
              (frames.csv column shows_face, as the pipeline judged it; --no-view-gate ignores it)
  jump        a near-range candidate the pipeline withheld as a disputed jump (frames.csv column jumped:
              the filter rejected it and its look turned more than [navigation] disputed_max_look_change_deg
              from the frame before's pose; as the pipeline judged it; --no-jump-gate ignores it)
  minimal     a near-range candidate on at most 4 lines whose pose selected more than
              --minimal-fit-max-missing lines it did not find ([navigation] minimal_fit_max_missing_lines,
              stop 53; -1 ignores it)
  --max-nis   (not shipped) withhold frames whose filter NIS exceeds this
  evidence    (not shipped; frames.csv columns scanlines, inlier_points, evidence_good, written since
              2026-12-01) --min-line-fraction F: a near-range candidate that used fewer than F of its selected
              lines is not certain; --min-edge-support F: nor one with fewer inlier points than F per
              scanline cast; --weak-evidence-doubt / --weak-evidence-invalid: a candidate whose image
              evidence is not good (nav::imageEvidenceGood, as the pipeline judged it) is doubted / not
              certain

Prints tracked mean and confidently wrong frames (scenes) per family, as visnav-campaign defines them.
--check SCENES_CSV: with the gates as given, every scene's tracked and confidently wrong counts must equal
the campaign's own (exit 1 otherwise): the replay's self-check, run by ctest campaign_gate_replay.
--line-end-bias-px B / --interior-edge-bias-px B / --narrow-face-edge-bias-px B: first rescale every
near-range candidate's sigmas as [nearrange] line_end_bias_px / interior_edge_bias_px /
narrow_face_edge_bias_px = B would, the others at their defaults (frames.csv cov_* columns; the gain the
run applied, column systematic_gain, is divided out, so a run of any defaults replays any values), so that a systematic covariance term is judged over a whole run offline.
"""
import argparse
import collections
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sigma_consistency import biases_asked, sigma_scale  # noqa: E402  (systematic_gain, one definition)

AMBIGUOUS = 0x400          # kFlagAmbiguous
RESIDUAL_FALLBACK = 0x100  # kFlagResidualFallback
FAULT_INNOVATION = 0x10    # kFaultInnovation
NARROW_FACE = 0x1000       # kFlagNarrowFace
OUTLINE_PARTIAL = 0x204    # kFlagSilhouetteOnly | kFlagLineRejected


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('frames_csv')
    p.add_argument('--attitude-sigma-deg', type=float, default=2.5)
    p.add_argument('--position-sigma-rel', type=float, default=0.0167)
    p.add_argument('--doubted-attitude-sigma-deg', type=float, default=1.0)
    p.add_argument('--doubt-min-line-fraction', type=float, default=0.75)
    p.add_argument('--doubt-nis-chi2', type=float, default=12.59)
    p.add_argument('--no-narrow-face-doubt', action='store_true')
    p.add_argument('--branch-confirm-frames', type=int, default=3)
    p.add_argument('--rival-flags', type=lambda s: int(s, 0), default=AMBIGUOUS | RESIDUAL_FALLBACK)
    p.add_argument('--narrow-confirm-max-lines', type=int, default=7)
    p.add_argument('--narrow-confirm-max-attitude-sigma-deg', type=float, default=0.3)
    p.add_argument('--narrow-break-max-fit-attitude-sigma-deg', type=float, default=1.0)
    p.add_argument('--no-confirmed-sources', action='store_true')
    p.add_argument('--break-after', type=int, default=1)
    p.add_argument('--max-nis', type=float, default=0.0)
    p.add_argument('--doubt-every-line-up-to', type=int, default=6)
    p.add_argument('--min-line-fraction', type=float, default=0.0)
    p.add_argument('--minimal-fit-max-missing', type=int, default=2)
    p.add_argument('--start-pose-doubt-frames', type=int, default=0)
    p.add_argument('--start-pose-doubt-nis', type=float, default=5.35)
    p.add_argument('--start-pose-doubt-fits', type=int, default=2)
    p.add_argument('--no-branch-confirm-needs-filter', action='store_true')
    p.add_argument('--no-branch-range-after-jump', action='store_true')
    p.add_argument('--min-edge-support', type=float, default=0.0)
    p.add_argument('--weak-evidence-doubt', action='store_true')
    p.add_argument('--weak-evidence-invalid', action='store_true')
    p.add_argument('--no-view-gate', action='store_true')
    p.add_argument('--no-acquisition-await', action='store_true')
    p.add_argument('--no-handover-whole-outline', action='store_true')
    p.add_argument('--no-branch-continuity', action='store_true')
    p.add_argument('--narrow-break-reconfirms', action='store_true')
    p.add_argument('--no-jump-gate', action='store_true')
    p.add_argument('--no-mirror-resolved', action='store_true')
    p.add_argument('--no-doubt-after-restart', action='store_true')
    p.add_argument('--line-end-bias-px', type=float, default=None)
    p.add_argument('--interior-edge-bias-px', type=float, default=None)
    p.add_argument('--narrow-face-edge-bias-px', type=float, default=None)
    p.add_argument('--check', metavar='SCENES_CSV')
    return p.parse_args(argv)


def replay_scene(rows, a):
    """Per-frame (valid, wrong) under the gates, in frame order."""
    known, run, bad = True, 0, 0  # the near scenes start from a given pose: the branch is known
    track_doubted = False  # the track began with a find and none of its poses met the doubted limit yet
    awaiting = False  # an acquisition's pose waits for the next near-range frame
    narrow_break = False  # since the last valid frame a candidate beside a narrow strip was withheld
    out = []
    # A near scene starts from the operator's pose (startNearRange) on its first frame.
    started_near = bool(rows) and rows[0]['mode'] == 'near_range'
    start_fits_pending = a.start_pose_doubt_fits if started_near else 0
    restarted_filter = False  # the frame before's near-range fit overruled the filter (a restart)
    for r in rows:
        # The fit after one that overruled the filter agrees with that one fit only ([navigation]
        # doubt_after_filter_restart, stop 59): a near-range candidate the innovation gate rejected and the
        # pipeline still delivered (its image evidence was good, or the track diverged) restarted the filter.
        follows_restart = restarted_filter and not a.no_doubt_after_restart and r['mode'] == 'near_range'
        restarted_filter = (r['mode'] == 'near_range' and r['candidate'] == '1'
                            and (int(r['fault_bits']) & FAULT_INNOVATION) != 0)
        # The first near-range fits after the start pose (those with a filter update; [navigation]
        # start_pose_doubt_fits, stop 61) are judged against it.
        start_fit = start_fits_pending > 0 and r['mode'] == 'near_range' and r['nis'] != ''
        if start_fit:
            start_fits_pending -= 1
        if r['mode'] != 'near_range':
            start_fits_pending = 0
        awaited = awaiting and r['mode'] == 'near_range'
        if awaited and not a.no_handover_whole_outline:
            awaited = (int(r['near_flags']) & OUTLINE_PARTIAL) != OUTLINE_PARTIAL
        if r['mode'] != 'acquisition':
            awaiting = False
        if r['reacquired'] == '1':
            track_doubted = True
        elif r['mode'] == 'acquisition':
            track_doubted = False
        certain = (r['candidate'] == '1' and float(r['attitude_sigma_deg']) <= a.attitude_sigma_deg
                   and float(r['position_sigma_rel']) <= a.position_sigma_rel)
        if certain and a.doubted_attitude_sigma_deg > 0 and r['mode'] == 'near_range':
            doubted = track_doubted or follows_restart or (int(r['fault_bits']) & FAULT_INNOVATION) != 0 or (
                int(r['lines_used']) < a.doubt_min_line_fraction * int(r['lines_total'])) or (
                not a.no_narrow_face_doubt and (int(r['near_flags']) & NARROW_FACE) != 0) or (
                a.weak_evidence_doubt and r.get('evidence_good', '1') == '0') or (
                a.doubt_nis_chi2 > 0 and r['nis'] != '' and float(r['nis']) > a.doubt_nis_chi2) or (
                int(r['lines_used']) < int(r['lines_total']) <= a.doubt_every_line_up_to) or (
                started_near and int(r['frame']) - int(rows[0]['frame']) < a.start_pose_doubt_frames) or (
                start_fit and a.start_pose_doubt_nis > 0 and float(r['nis']) > a.start_pose_doubt_nis)
            if doubted and float(r['attitude_sigma_deg']) > a.doubted_attitude_sigma_deg:
                certain = False
        if (r['mode'] == 'near_range' and r['candidate'] == '1' and a.doubted_attitude_sigma_deg > 0
                and float(r['attitude_sigma_deg']) <= a.doubted_attitude_sigma_deg):
            track_doubted = False
        if certain and a.max_nis > 0 and r['nis'] and float(r['nis']) > a.max_nis:
            certain = False
        if certain and r['mode'] == 'near_range' and (
                int(r['lines_used']) < a.min_line_fraction * int(r['lines_total'])
                or int(r.get('inlier_points', '0')) < a.min_edge_support * int(r.get('scanlines', '0'))
                or (a.weak_evidence_invalid and r.get('evidence_good', '1') == '0')):
            certain = False
        if (certain and a.minimal_fit_max_missing >= 0 and r['mode'] == 'near_range' and r['reacquired'] != '1'
                and int(r['lines_used']) <= 4
                and int(r['lines_total']) - int(r['lines_used']) > a.minimal_fit_max_missing):
            certain = False
        if certain and not a.no_view_gate and r.get('shows_face', '1') == '0':
            certain = False
        if certain and not a.no_jump_gate and r.get('jumped', '0') == '1':
            certain = False
        acquisition_pose = r['mode'] == 'acquisition' and r['candidate'] == '1'
        if acquisition_pose and not a.no_acquisition_await:
            certain = False
            awaiting = True
        valid = certain
        if a.branch_confirm_frames > 0:
            if not certain:
                bad += 1
                run = 0
                if bad >= a.break_after:
                    known = False
            else:
                bad = 0
                # A find off a known branch (find_on_branch 0; [navigation]
                # find_confirms_only_from_reference) confirms nothing and is not rival-free either.
                find_off_branch = r['reacquired'] == '1' and r.get('find_on_branch', '1') == '0'
                # A mirrored rival the prediction resolved is none (column mirror_resolved, the pipeline's
                # verdict; [navigation] mirror_resolved_by_prediction, stop 60; written since stop 61).
                rivals = a.rival_flags
                if not a.no_mirror_resolved and r.get('mirror_resolved', '0') == '1':
                    rivals &= ~AMBIGUOUS
                # A strip fit on few lines is rival-free only when very certain ([navigation]
                # narrow_confirm_max_lines / narrow_confirm_max_attitude_sigma_deg, stop 74).
                if (r['mode'] == 'near_range' and int(r['near_flags']) & NARROW_FACE
                        and int(r['lines_used'] or 0) <= a.narrow_confirm_max_lines
                        and float(r['attitude_sigma_deg']) > a.narrow_confirm_max_attitude_sigma_deg):
                    rivals |= NARROW_FACE
                rival_free = r['mode'] != 'near_range' or ((int(r['near_flags']) & rivals) == 0
                                                           and r.get('near_twin_rival', '0') != '1'
                                                           and not find_off_branch)
                # A fit the filter rejected counts toward no confirmation run (branch_confirm_needs_filter).
                motion_agrees = (a.no_branch_confirm_needs_filter or r['mode'] != 'near_range'
                                 or (int(r['fault_bits']) & FAULT_INNOVATION) == 0)
                # Nor one that left the last valid pose's range after a jump (branch_range_after_jump; as the
                # pipeline judged it, frames.csv column range_broken, written since stop 54).
                if not a.no_branch_range_after_jump and r.get('range_broken', '0') == '1':
                    motion_agrees = False
                continuous = (not a.no_branch_continuity and r['mode'] == 'near_range'
                              and r.get('kept_branch', '0') == '1'
                              and not (a.narrow_break_reconfirms and narrow_break))
                if not a.no_confirmed_sources and (acquisition_pose
                                                   or (r['reacquired'] == '1' and not find_off_branch)
                                                   or (awaited and rival_free) or continuous):
                    known = True
                # Nor, after a break a strip caused, one whose own fit, before the filter, is uncertain
                # ([navigation] narrow_break_max_fit_attitude_sigma_deg, stop 75; column
                # fit_attitude_sigma_deg, written since stop 75: a run without it replays a filtered frame at
                # the filter's sigma).
                fit_sigma = r.get('fit_attitude_sigma_deg') or r['attitude_sigma_deg']
                # The break as the pipeline judged it where the run wrote it (column narrow_break, since
                # stop 75; it also counts a strip fit the tracker made but the pipeline did not deliver or
                # withhold), else as replayed.
                after_strip = r['narrow_break'] == '1' if 'narrow_break' in r else narrow_break
                fit_uncertain = (r['mode'] == 'near_range' and after_strip
                                 and a.narrow_break_max_fit_attitude_sigma_deg > 0
                                 and float(fit_sigma) > a.narrow_break_max_fit_attitude_sigma_deg)
                if not (rival_free and motion_agrees) or fit_uncertain:
                    run = 0
                elif run < a.branch_confirm_frames:
                    run += 1
                    if run >= a.branch_confirm_frames:
                        known = True
                valid = known
        range_m = float(r['range_m'])
        if valid:
            narrow_break = False
        elif r['mode'] == 'near_range' and r['candidate'] == '1' and int(r['near_flags']) & NARROW_FACE:
            narrow_break = True
        wrong = valid and (float(r['candidate_position_error_m']) > 0.05 * range_m
                           or float(r['candidate_attitude_error_deg']) > 5.0)
        out.append((valid, wrong))
    return out


def rescale_sigmas(r, biases):
    """A near-range candidate's sigmas as [nearrange] line_end_bias_px, interior_edge_bias_px and
    narrow_face_edge_bias_px = `biases` would make them (NearRangeResult::systematic_gain)."""
    if r['mode'] != 'near_range' or r['candidate'] != '1' or r['attitude_sigma_deg'] == '':
        return
    root = sigma_scale(r, biases)
    r['attitude_sigma_deg'] = str(float(r['attitude_sigma_deg']) * root)
    r['position_sigma_rel'] = str(float(r['position_sigma_rel']) * root)


def main(argv):
    a = parse_args(argv)
    scenes = collections.OrderedDict()
    biases = biases_asked(a)
    with open(a.frames_csv, newline='') as f:
        for r in csv.DictReader(f):
            if biases is not None:
                rescale_sigmas(r, biases)
            scenes.setdefault(r['scene'], []).append(r)
    families = collections.OrderedDict()
    per_scene = {}
    for name, rows in scenes.items():
        verdicts = replay_scene(rows, a)
        expected = tracked = wrong = 0
        for r, (valid, is_wrong) in zip(rows, verdicts):
            wrong += is_wrong
            if r['expected'] == '1':
                expected += 1
                tracked += valid and not is_wrong and r['mode'] in ('near_range', 'acquisition')
        per_scene[name] = (tracked, wrong)
        fam = families.setdefault(rows[0]['family'], {'fractions': [], 'wrong': 0, 'wrong_scenes': 0})
        if expected > 0:
            fam['fractions'].append(tracked / expected)
        fam['wrong'] += wrong
        fam['wrong_scenes'] += wrong > 0
    total = {'fractions': [], 'wrong': 0, 'wrong_scenes': 0}
    for fam in families.values():
        for k in total:
            total[k] += fam[k]
    for name, fam in [('overall', total)] + list(families.items()):
        mean = sum(fam['fractions']) / len(fam['fractions']) if fam['fractions'] else float('nan')
        print(f"{name:9s} tracked mean {mean:.3f}  confidently wrong {fam['wrong']} ({fam['wrong_scenes']} scenes)")
    if a.check:
        mismatches = 0
        with open(a.check, newline='') as f:
            for r in csv.DictReader(f):
                got = per_scene.get(r['name'])
                want = (int(r['tracked']), int(r['confidently_wrong']))
                if got != want:
                    mismatches += 1
                    print(f"check: {r['name']}: replay tracked/wrong {got}, campaign {want}", file=sys.stderr)
        print(f"check: {len(per_scene)} scenes, {mismatches} differ from {a.check}")
        return 1 if mismatches else 0
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
