// Every tunable of acquisition (tracker initialisation), with units, ranges and defaults. The
// generated reference is config/PARAMETERS.md; a run takes its values from the [acquisition] table.
#pragma once

#include "visnav/core/param_visitor.hpp"

namespace visnav::acq {

struct AcquisitionParams {
  // Search space (memory and the hypothesis count are fixed at init from these).
  int view_directions = 120;
  int roll_steps = 18;
  double max_obliquity_deg = 50.0;
  int range_steps = 5;
  double range_span_rel = 0.35;
  double direction_margin_deg = 2.0;
  // Working image and scoring.
  int working_radius_px = 48;
  int max_working_side_px = 256;
  int max_strong_pixels = 2048;
  int fine_spread_px = 2;
  int coarse_spread_px = 8;
  int shift_steps = 1;
  int samples_per_hypothesis = 64;
  double internal_edge_weight = 0.5;
  double evidence_cap = 4.0;
  double min_edge_snr = 5.0;
  double outline_cue_min_edge_snr = 5.0;
  int edge_snr_radius_px = 12;
  int far_cue_edge_snr_radius_px = 0;
  // Budget per cycle.
  int hypotheses_per_cycle = 4000;
  int search_candidates = 48;
  int candidates = 16;
  int refine_levels = 6;
  // Verification with the near-range tracker and hand-over.
  int verify_scanline_half_length_px = 16;
  int tracker_iterations = 4;
  double max_rms_px = 0.6;
  double rms_weight = 0.3;
  double min_quality = 0.4;
  int confirm_frames = 2;
  bool accept_degraded = true;
  // Never deliver a wrong pose: what confirmation demands.
  double min_confirm_agreement = 0.7;
  double rival_margin = 0.05;
  double near_twin_max_rel = 0.25;
  int near_twin_checks = 3;
  bool mirror_twin_checks = false;
  double near_twin_min_separation_px = 2.0;
  int max_confirm_frames = 8;
  double confirm_max_motion_rel = 0.05;
  double confirm_max_rotation_deg = 5.0;
  bool confirm_follows_motion = true;
  double window_margin = 1.15;

  template <typename Visitor>
  void visit(Visitor& v) {
    v.integer(
        {"acquisition", "view_directions", "count", 1, 20000,
         "viewing directions of the attitude grid (Fibonacci sphere, before dropping views that show no "
         "surface within max_obliquity_deg)"},
        view_directions);
    v.integer({"acquisition", "roll_steps", "count", 1, 720, "in-plane roll steps per viewing direction"},
              roll_steps);
    v.real({"acquisition", "max_obliquity_deg", "deg", 1.0, 89.0,
            "views where every surface is more oblique than this are not searched (the tracker starts below "
            "45)"},
           max_obliquity_deg);
    v.integer({"acquisition", "range_steps", "count", 1, 64,
               "distances tried per attitude, geometric over the cue distance / (1 + span) .. * (1 + span)"},
              range_steps);
    v.real({"acquisition", "range_span_rel", "-", 0.0, 3.0,
            "relative distance error of the far-range cue covered"},
           range_span_rel);
    v.real({"acquisition", "direction_margin_deg", "deg", 0.0, 30.0,
            "far-range direction error covered: the search window grows by this angle"},
           direction_margin_deg);
    v.integer({"acquisition", "working_radius_px", "px", 8, 512,
               "the window is box-averaged so that the expected target radius is about this many pixels"},
              working_radius_px);
    v.integer({"acquisition", "max_working_side_px", "px", 32, 2048,
               "capacity: side of the working window (a larger window is averaged more)"},
              max_working_side_px);
    v.integer({"acquisition", "max_strong_pixels", "count", 16, 1000000,
               "capacity: strong-edge pixels kept for the image-to-model agreement (evenly thinned beyond)"},
              max_strong_pixels);
    v.integer({"acquisition", "fine_spread_px", "px", 0, 32,
               "spread radius (tent-weighted max filter) of the orientation channels in the middle "
               "refinement levels"},
              fine_spread_px);
    v.integer({"acquisition", "coarse_spread_px", "px", 0, 64,
               "spread radius for the coarse search: tolerance to grid steps, distance steps and the "
               "centring error of a hypothesis"},
              coarse_spread_px);
    v.integer(
        {"acquisition", "shift_steps", "count", 0, 8,
         "lateral shifts tried per hypothesis: (2 n + 1)^2, coarse_spread_px apart, around the window's "
         "edge centroid"},
        shift_steps);
    v.integer({"acquisition", "samples_per_hypothesis", "count", 4, 4096,
               "edge samples scored per hypothesis (cost per hypothesis)"},
              samples_per_hypothesis);
    v.real({"acquisition", "internal_edge_weight", "-", 0.0, 1.0,
            "weight of edges between two front faces relative to outline edges (their contrast depends on "
            "light)"},
           internal_edge_weight);
    v.real({"acquisition", "evidence_cap", "-", 0.1, 1000.0,
            "edge evidence of a sample saturates at this multiple of the presence threshold (3 x median "
            "gradient): every supported sample counts, the few strongest edges do not dominate"},
           evidence_cap);
    v.real({"acquisition", "min_edge_snr", "-", 1.0, 1000.0,
            "99.9th-percentile / median gradient in the window below this (noise alone: ~3): no target, "
            "acquisition fails"},
           min_edge_snr);
    v.real(
        {"acquisition", "outline_cue_min_edge_snr", "-", 1.0, 1000.0,
         "min_edge_snr for a cue far range found by its outline (edge structure already shown): a large "
         "dim target's window is mostly its own face and the noise, its outline a small share. At 3.5 "
         "(campaign seeds 1-40, 5001-5040, 7001-7040, 600 scenes): "
         "tracked frames +84 (box/13 0 -> 17, cao/5025 0 -> 71), approaches acquired +1, confidently wrong "
         "unchanged, but approach mode changes 299 -> 347 (failed acquisitions of small cues); kept at "
         "min_edge_snr's 5 until acquisition fails less on them"},
        outline_cue_min_edge_snr);
    v.integer(
        {"acquisition", "edge_snr_radius_px", "px", 0, 512,
         "an acquisition the near-range prediction cued also reads the edge SNR of its window "
         "box-averaged to this target radius, and its no-target test takes the better of the two (0: "
         "the working scale alone): noise's gradient drops by the factor, a dim outline's does not. "
         "Far range's cues keep the working scale (a limb's soft edge passes averaged: plate/6 2 -> 10 "
         "mode changes). 12 on campaign seeds 1-120: tracked 45 476 -> 45 541, 0 wrong, no mode change"},
        edge_snr_radius_px);
    v.integer({"acquisition", "far_cue_edge_snr_radius_px", "px", 0, 512,
               "edge_snr_radius_px for a cue far range gave (0: the working scale alone). A dim target under "
               "noise fails the working-scale test where the averaged one passes, and is then never handed "
               "over; a limb's soft edge passes it too. 12, beside far range, on campaign seeds 1-40 / "
               "41-80: tracked +17 (box/13 0 -> 17) / -24 (box/73 41 -> 11: a cue passed early fails "
               "unconfirmed and the retry waits until the target is twice as near), 0 wrong"},
              far_cue_edge_snr_radius_px);
    v.integer({"acquisition", "hypotheses_per_cycle", "count", 1, 10000000,
               "budget: hypotheses scored per frame; the search spans several frames"},
              hypotheses_per_cycle);
    v.integer({"acquisition", "search_candidates", "count", 1, 1024,
               "best distinct coarse hypotheses kept by the search and refined"},
              search_candidates);
    v.integer({"acquisition", "candidates", "count", 1, 64,
               "best distinct refined hypotheses verified with the near-range tracker"},
              candidates);
    v.integer({"acquisition", "refine_levels", "count", 1, 16,
               "pattern-search levels per candidate (step halves per level)"},
              refine_levels);
    v.integer(
        {"acquisition", "verify_scanline_half_length_px", "px", 0, 64,
         "scanline half-length of the verifying tracker (0: as [nearrange]); longer widens its capture"},
        verify_scanline_half_length_px);
    v.integer({"acquisition", "tracker_iterations", "count", 1, 20,
               "tracker passes on the same frame per candidate (each starts from the last result)"},
              tracker_iterations);
    v.real({"acquisition", "max_rms_px", "px", 0.01, 100.0,
            "a candidate's tracker residual must stay below this"},
           max_rms_px);
    v.real({"acquisition", "rms_weight", "1/px", 0.0, 100.0,
            "verified candidates are ranked by edge agreement (F1) minus this times the tracker residual"},
           rms_weight);
    v.real({"acquisition", "min_quality", "-", 0.0, 1.0, "a candidate's tracker quality must reach this"},
           min_quality);
    v.integer({"acquisition", "confirm_frames", "count", 0, 100,
               "consecutive further frames the chosen candidate must track before hand-over"},
              confirm_frames);
    v.boolean({"acquisition", "accept_degraded", "-", 0, 1,
               "accept tracker status degraded (not only tracking) during verification and confirmation"},
              accept_degraded);
    v.real({"acquisition", "min_confirm_agreement", "-", 0.0, 1.0,
            "two-way edge agreement (F1) the confirmed pose must keep on every confirmation frame (0.7: the "
            "200-scenes-per-family campaign gave 788 confidently wrong frames against 938 at 0.5, the same "
            "tracked fraction)"},
           min_confirm_agreement);
    v.real(
        {"acquisition", "rival_margin", "-", 0.0, 1.0,
         "a distinct verified pose (not a symmetric twin) scoring within this of the best is a rival: both "
         "are tracked, and the best is confirmed only once the rival falls this far behind or loses track"},
        rival_margin);
    v.real({"acquisition", "near_twin_max_rel", "-", 0.0, 1.0,
            "a turn of the model (cube group, regular polygons) that maps it onto itself within this share "
            "of its bounding radius is a near twin: the best candidate's near twins are tracked and one "
            "scoring within rival_margin is a rival (0: none; a box within 7 % of a cube was confirmed 118 "
            "deg off without this). 0.25, not 0.15: a rectangle's quarter turn about its normal moves its "
            "corners 24 % of the radius on campaign cao/69, and far out its outline fits at another tilt "
            "and range (13 confidently wrong frames at 0.15, 0 at 0.25)"},
           near_twin_max_rel);
    v.integer({"acquisition", "near_twin_checks", "count", 0, 16,
               "near twins tracked per candidate: those whose two-way edge agreement is highest before "
               "tracking"},
              near_twin_checks);
    v.boolean(
        {"acquisition", "mirror_twin_checks", "-", 0, 1,
         "experimental, off: the candidate's depth-reversed twin (ModelSymmetries::mirrorTwin: the model "
         "mirrored across the line of sight through its centroid, the same outline) competes beside the "
         "rival, re-made and refitted on every confirmation frame; scoring within rival_margin (its "
         "agreement as it stands less its refit's residual) it must fall behind before the candidate is "
         "confirmed. Campaign box/120 (flat-lit box at 49 m) was confirmed 88-90 deg off with the truth "
         "0.02-0.12 deg from its twin: 28 wrong frames -> 0. On the 257 approaches of seeds 1-200 with "
         "[farrange] background_block_px 128 on every frame: tracked 0.316 -> 0.297, wrong frames 44 -> 16; "
         "with far range as printed, which leaves no wrong frame there to remove: tracked 0.286 -> 0.254 "
         "and 0 -> 1 wrong frame. Off: the defaults since stop 40 (the flattened search as a fallback, "
         "near_twin_max_rel 0.25) leave no wrong frame on the approaches either; true: the twin is "
         "challenged"},
        mirror_twin_checks);
    v.real({"acquisition", "near_twin_min_separation_px", "px", 0.0, 1000.0,
            "a near twin that moves the model's vertices less than this in the image is a rival whatever "
            "the tracker makes of it: no edge tells the two poses apart (blur, shading and a step's polarity "
            "move an edge by about a pixel), so the acquisition fails `ambiguous` and is retried closer (a "
            "box within 7 % of a cube was confirmed 89 deg off at 26 m, box/187, once far range read its "
            "distance right); 0: off"},
           near_twin_min_separation_px);
    v.integer({"acquisition", "max_confirm_frames", "count", 1, 1000,
               "confirmation with a rival alive ends here: still ambiguous means failed (status lost)"},
              max_confirm_frames);
    v.real({"acquisition", "confirm_max_motion_rel", "-", 0.001, 1.0,
            "consistency with the predicted motion: largest position change per confirmation frame, as a "
            "share of the depth"},
           confirm_max_motion_rel);
    v.real({"acquisition", "confirm_max_rotation_deg", "deg", 0.01, 180.0,
            "consistency with the predicted motion: largest attitude change per confirmation frame"},
           confirm_max_rotation_deg);
    v.boolean(
        {"acquisition", "confirm_follows_motion", "-", 0, 1,
         "a candidate under confirmation that moved across the line of sight between its last two fits "
         "(significant against their covariance, the two in range within confirm_max_motion_rel) starts the "
         "next frame moved on by that step, and the motion test is taken against that prediction; one the "
         "flight tracker loses from its start is tracked again on that frame from the best shift of its "
         "outline over the window's coarse evidence, within confirm_max_motion_rel; where the last step was "
         "such motion, the confirmed pose's frame before starts the filter with it (a target crossing the "
         "image 19 px a frame left the 10 px scanlines on every confirmation frame, campaign cao/1). false: "
         "each frame starts where the last one ended, and the filter at rest"},
        confirm_follows_motion);
    v.real({"acquisition", "window_margin", "-", 1.0, 4.0,
            "search window half size = window_margin x the target's radius at the nearest distance covered "
            "(+ the direction margin): room for the centroid bias of partly visible edges"},
           window_margin);
  }

  /// Cross-field checks the per-field ranges cannot express. Returns nullptr when valid.
  const char* crossCheck() const {
    if (2 * working_radius_px > max_working_side_px)
      return "max_working_side_px must be >= 2 * working_radius_px";
    if (candidates > search_candidates) return "candidates must be <= search_candidates";
    if (max_confirm_frames < confirm_frames) return "max_confirm_frames must be >= confirm_frames";
    return nullptr;
  }
};

}  // namespace visnav::acq
