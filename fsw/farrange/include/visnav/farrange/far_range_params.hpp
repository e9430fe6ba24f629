// Every tunable of the far-range direction/distance estimator (paper sec. III), with units, ranges and
// defaults. Table 1 values are the defaults of beta, lambda_1/2, gamma, t_in and t_out. The generated
// reference is config/PARAMETERS.md; the values used by a run come from the [farrange] table of its config.
#pragma once

#include <cmath>

#include "visnav/core/param_visitor.hpp"

namespace visnav::far {

/// paper: exactly as published (normalise by the single maximum, raw cluster size, most circular cluster).
/// robust: percentile normalisation, filled clusters, size/shape checks, gating by the last estimate, ROI.
enum class FarRangeMethod : int { kPaper = 0, kRobust = 1 };
/// sobel: the usual Sobel kernel (centre weight 2); prewitt: eq. 9's kernels as printed.
enum class EdgeKernel : int { kSobel = 0, kPrewitt = 1 };

struct FarRangeParams {
  int method = static_cast<int>(FarRangeMethod::kRobust);
  int edge_kernel = static_cast<int>(EdgeKernel::kSobel);
  // Table 1.
  double beta = 100.0;
  double edge_weight = 0.5;
  double histogram_weight = 0.5;
  double gamma = 3000.0;
  double t_in = 0.9;
  double t_out = 0.5;
  // Robust method (ignored by method = paper).
  double edge_percentile = 50.0;
  double edge_percentile_factor = 3.0;
  double edge_ref_floor = 0.02;
  int min_cluster_px = 6;
  double max_axis_ratio = 9.0;
  bool fill_holes = true;
  double outline_discount = 1.0;
  double gate_radius_px = 30.0;
  double gate_extent_factor = 1.0;
  double max_size_ratio = 2.0;
  int max_coast_frames = 5;
  bool use_roi = true;
  bool background_fallback_only = true;
  bool printed_search_wins = false;  ///< with it, a target the printed search finds ends a flattened track
  int background_block_px = 128;     ///< eq. 11 over the deviation from the smooth background (0: off)
  double roi_extent_factor = 2.0;
  int roi_min_half_px = 48;
  double extended_min_half_px = 12.0;
  double extended_spawn = 0.99;
  double extended_grow = 0.6;
  double extended_max_growth = 64.0;
  double extended_enclose_ratio = 4.0;
  double untracked_outline_fill_ratio = 2.0;  ///< without a track, a closed outline this solid (0: off)
  double outline_min_coverage = 0.8;       ///< an outline with gaps: its hull, when it runs along this share
  double outline_min_concentration = 0.4;  ///< ... and this share of its pixels lies along the hull
  bool outline_fix_refutable = false;      ///< refuteLastFix() also refutes a fix found by its outline
  double extent_distance_min_px = 4.0;
  int refuted_fix_frames = 60;
  bool refuted_follow = true;           ///< refuted regions follow their cluster; refuted again: longer
  int recheck_frames = 10;              ///< every this many fixes a track is checked against the whole frame
  double recheck_switch_ratio = 4.0;    ///< a rival that many times the tracked n (and near enough) wins
  double recheck_static_growth = 1.25;  ///< a track whose n grew more since the last check is kept
  double min_outline_sharpness = 0.5;   ///< a cluster whose outline is a ramp is never the target (0: off)
  double silhouette_min_half_px = 0.0;  ///< the block-mean silhouette's smallest window (0: off; 48 tried)
  double silhouette_max_half_px = 512.0;  ///< ... and its largest (the window doubles until one is taken)
  int silhouette_block_px = 4;            ///< ... its smallest block side
  double silhouette_k_sigma = 4.0;        ///< ... a block departs beyond this many of the ring's 1-sigma
  double silhouette_level_ratio = 0.25;   ///< ... and grows the region beyond this share of the fix's level
  // Capacities (memory is sized from these and the image size at init).
  int max_clusters = 256;
  int max_cluster_pixels = 262144;

  template <typename Visitor>
  void visit(Visitor& v) {
    v.enumeration(
        {"farrange", "method", "-", 0, 1,
         "paper: as published (max normalisation, raw n, most circular cluster); robust: noise-relative "
         "normalisation, filled clusters, size and shape checks, gating by the last estimate, ROI"},
        "paper|robust", method);
    v.enumeration(
        {"farrange", "edge_kernel", "-", 0, 1,
         "3x3 gradient kernels of the edge filter: sobel (centre weight 2) or prewitt (eq. 9 as printed)"},
        "sobel|prewitt", edge_kernel);
    v.real({"farrange", "beta", "-", 0.0, 1.0e6, "Table 1 beta: histogram rarity dampening of eq. 12"}, beta);
    v.real({"farrange", "edge_weight", "-", 0.0, 1.0, "Table 1 lambda_1: weight of the edge filter (eq. 13)"},
           edge_weight);
    v.real({"farrange", "histogram_weight", "-", 0.0, 1.0,
            "Table 1 lambda_2: weight of the histogram filter (eq. 13); the weights must sum to 1 (eq. 14)"},
           histogram_weight);
    v.real({"farrange", "gamma", "m px^0.5", 1.0e-3, 1.0e9,
            "Table 1 gamma of eq. 16, d = gamma / sqrt(n); calibrate with visnav-calibrate-gamma"},
           gamma);
    v.real({"farrange", "t_in", "-", 0.0, 1.0,
            "Table 1 t_in: a cluster is spawned where the response exceeds it"},
           t_in);
    v.real({"farrange", "t_out", "-", 0.0, 1.0, "Table 1 t_out: a cluster grows over responses above it"},
           t_out);
    v.real(
        {"farrange", "edge_percentile", "%", 1.0, 100.0,
         "robust: eq. 10 divides by edge_percentile_factor times this percentile of abs(Jx) + abs(Jy) "
         "instead of the "
         "maximum (100: the maximum), so one bright non-target edge cannot push the target below t_in; the "
         "median is the background's noise level, the same in any region of interest"},
        edge_percentile);
    v.real({"farrange", "edge_percentile_factor", "-", 0.1, 1000.0,
            "robust: the eq. 10 divisor is this times the edge_percentile of abs(Jx) + abs(Jy) (clipped to 1 "
            "above)"},
           edge_percentile_factor);
    v.real({"farrange", "edge_ref_floor", "brightness", 0.0, 1.0,
            "robust: the eq. 10 divisor is at least the response of a step of this contrast (noise-free "
            "frames)"},
           edge_ref_floor);
    v.integer({"farrange", "min_cluster_px", "px", 1, 1000000,
               "robust: smaller clusters are never the target (noise, tiny glints)"},
              min_cluster_px);
    v.real({"farrange", "max_axis_ratio", "-", 1.0, 1000.0,
            "robust: clusters more elongated than this (sqrt of the second-moment eigenvalue ratio) are "
            "rejected when no track exists (line-like clutter)"},
           max_axis_ratio);
    v.boolean({"farrange", "fill_holes", "-", 0, 1,
               "robust: n and centre of mass from the cluster with its holes filled (the histogram filter "
               "drops a near target's interior, so the raw n stops following 1/d^2)"},
              fill_holes);
    v.real({"farrange", "outline_discount", "-", 0.0, 2.0,
            "robust: n = filled size - this * outline pixels; the thresholded cluster reaches about one "
            "pixel beyond the silhouette (blur halo), a term in 1/d that no gamma absorbs"},
           outline_discount);
    v.real({"farrange", "gate_radius_px", "px", 1.0, 10000.0,
            "robust: a tracked target must lie within this radius of the predicted position ..."},
           gate_radius_px);
    v.real({"farrange", "gate_extent_factor", "-", 0.0, 100.0,
            "robust: ... plus this factor times the last target's half extent"},
           gate_extent_factor);
    v.real({"farrange", "max_size_ratio", "-", 1.0, 1000.0,
            "robust: a tracked target's n must lie within [n_pred / r, n_pred * r]"},
           max_size_ratio);
    v.integer({"farrange", "max_coast_frames", "count", 0, 100000,
               "robust: frames without an accepted target before the track is dropped (then full-frame "
               "search without gating)"},
              max_coast_frames);
    v.integer({"farrange", "background_block_px", "px", 0, 4096,
               "robust: the histogram filter (eqs. 11-12) counts each pixel's "
               "deviation from the frame's smooth background (the median of blocks this size, sampled "
               "every 4th row and column, bilinear between their centres) instead of its grey level, so a "
               "target whose grey levels lie inside a gradient's or a planet limb's spread is still rare. "
               "At 128 on the campaign's 257 approaches (seeds 1-200): tracked mean 0.286 -> 0.316, "
               "approaches on a limb 0.207 -> 0.298, but confidently wrong frames 0 -> 44: more hand-overs "
               "on hard scenes, and the acquisition confirmed wrong box and plate poses on two of them "
               "(box/120, cao/69; fsw/farrange/README.md); hence the default searches flattened only as a "
               "fallback (background_fallback_only). Step +240 us at VGA, full frame. 0: the grey level, as "
               "printed"},
              background_block_px);
    v.boolean({"farrange", "background_fallback_only", "-", 0, 1,
               "robust, with background_block_px: eq. 11 as printed first, and over the flattened "
               "background only on a frame where the full-frame search found no target (flag flattened; "
               "the region of interest of a target found so is searched flattened). At 128 on the 257 "
               "approaches of seeds 1-200: tracked mean 0.286 -> 0.315 and confidently wrong frames 0 -> "
               "13 (cao/69 alone, against 44 in 5 scenes always flattened), plate 0.431 -> 0.351 (plate/41, "
               "/114, /125 lost: flattened fixes on clutter where the printed search had a frame without "
               "target). With [acquisition] near_twin_max_rel 0.25 (the defaults), on the full run of seeds "
               "1-200: tracked 0.6248 -> 0.6323, confidently wrong frames 88 -> 88. false: always flattened"},
              background_fallback_only);
    v.boolean({"farrange", "printed_search_wins", "-", 0, 1,
               "robust, with background_fallback_only: while the track is a fix found over the flattened "
               "background, eq. 11 as printed is also run over the whole frame, and a target it finds "
               "(the largest plausible cluster, as without a track) ends that track and is taken: the "
               "flattened search stays the fallback of a frame without target, never a track that holds on "
               "against the printed one (campaign plate/114: a drifting blob found flattened on a frame "
               "without target was held 140 frames, 6-8 deg off the plate). Measured, off: on the 257 "
               "approaches of seeds 1-200 with background_block_px 128, background_fallback_only and "
               "[acquisition] near_twin_max_rel 0.25 it gave back plate/114, /125, /41 and box/29, /40 but "
               "tracked 0.3175 -> 0.2991 and confidently wrong frames 0 -> 10 (box/115: the acquisition, "
               "handed over at another time, confirmed a wrong pose); false: a flattened track keeps its "
               "region"},
              printed_search_wins);
    v.boolean({"farrange", "use_roi", "-", 0, 1,
               "robust: filter only a region around the predicted target (sec. V); full frame when lost or "
               "when the region yields no target"},
              use_roi);
    v.real({"farrange", "roi_extent_factor", "-", 0.5, 100.0,
            "robust: ROI half size = factor * target half extent + roi_min_half_px"},
           roi_extent_factor);
    v.integer({"farrange", "roi_min_half_px", "px", 8, 100000, "robust: smallest ROI half size"},
              roi_min_half_px);
    v.real({"farrange", "extended_min_half_px", "px", 0.0, 100000.0,
            "robust: when eq. 13 finds no tracked target, its outline is searched on the edge response alone "
            "inside the gate (eq. 12's rarity fails once the target's own grey levels fill the histogram); "
            "an outline of at least this half extent is taken (12 was measured on the full campaign); 0 "
            "switches the search off"},
           extended_min_half_px);
    v.real({"farrange", "extended_spawn", "-", 0.0, 1.0,
            "robust: that outline search spawns where the edge response of eq. 10 exceeds this"},
           extended_spawn);
    v.real({"farrange", "extended_grow", "-", 0.0, 1.0,
            "robust: ... and grows over edge responses above this; the filled outline is the silhouette"},
           extended_grow);
    v.real({"farrange", "extended_max_growth", "-", 1.0, 1.0e6,
            "robust: the outline found may be up to this many times the tracked n (a track held on a "
            "fragment of the target: its n is a lower bound)"},
           extended_max_growth);
    v.real({"farrange", "extended_enclose_ratio", "-", 1.0, 1.0e6,
            "robust: an outline enclosing eq. 13's gated candidate replaces it only when at least this many "
            "times its n (a fragment: plate/50 kept 1-3 px of a plate at 50 m); at 2 a satellite's body "
            "(28 px at 745 m, far_range_ci) gave way to the outline with its panels, read 33 % too near"},
           extended_enclose_ratio);
    v.real(
        {"farrange", "untracked_outline_fill_ratio", "-", 0.0, 1.0e6,
         "robust, without a track: the outline search also runs on the whole frame, and a closed outline "
         "(not cut by the image border, at least extended_min_half_px in half extent, filled area at least "
         "this many times its own edge pixels: an open arc, a glow or noise is not) replaces eq. 13's "
         "largest cluster when it is extended_enclose_ratio times its n. On a background of the target's "
         "grey levels eq. 13 keeps noise specks (campaign box/13: read at 1190 m from 750 m to 8 m, never "
         "handed over); 0 switches it off"},
        untracked_outline_fill_ratio);
    v.real({"farrange", "outline_min_coverage", "-", 0.0, 2.0,
            "robust: an outline with gaps (in noise, or where the target's contrast against a gradient "
            "passes near zero, the edge response leaves gaps and the outline fills nothing: campaign box/13 "
            "at 40-10 m) stands for its convex hull, in both outline searches, when the outline's pixels lie "
            "within 2 px of at least this share of the hull's boundary and the hull holds "
            "untracked_outline_fill_ratio times their number; one or two fragments (an outline broken "
            "twice); above 1 switches the hull off"},
           outline_min_coverage);
    v.real({"farrange", "outline_min_concentration", "-", 0.0, 1.0,
            "robust: ... and at least this share of the outline's pixels lies within 3 px of the hull's "
            "boundary (an outline lies along its hull; a line with noise attached covers its hull's boundary "
            "with the noise, but most of its pixels lie inside; a frame around a blob of twice its pixels: "
            "0.28). The noise an outline gathers in noise 0.07 takes a plate's to 0.4-0.6; 0: no test"},
           outline_min_concentration);
    v.boolean({"farrange", "outline_fix_refutable", "-", 0, 1,
               "robust: whether a fix found by an outline search may be refuted (refuted_fix_frames) when "
               "acquisition finds its window's edge SNR too low (no_target): an outline is edge structure, "
               "and a dim target still far off has a low window SNR too (campaign octagon/7022's approach: "
               "never acquired when such fixes are refuted, 9 of 36 frames tracked when not); false: only "
               "the mode manager's back-off applies to it"},
              outline_fix_refutable);
    v.real(
        {"farrange", "extent_distance_min_px", "px", 0.0, 100000.0,
         "a target whose cluster reaches at least this far from its centre of mass is put at the nearer of "
         "eq. 16's gamma / sqrt(n) and f x model bounding radius / that extent: n counts response pixels, "
         "and an extended target's outline has far fewer than its area (a plate at 12 m read 65 m, and far "
         "range never handed it back); both read too far on a fragment of the target, and too far never "
         "hands over. On the 1000-scene campaign (tools/campaign/far_distance.py) the nearer had a median "
         "abs(log error) of 0.09-0.17 against eq. 16's 0.12-0.27 for targets 4 to 64 px in radius; 0: "
         "eq. 16 always (the model's radius is the pipeline's)"},
        extent_distance_min_px);
    v.integer(
        {"farrange", "refuted_fix_frames", "frames", 0, 100000,
         "robust: after a fix was refuted (acquisition looked at its cue and found no edge structure "
         "there, failure no_target), clusters centred within its extent (at least gate_radius_px) "
         "and within 4x of its n are not selected for this many frames, so the next best is; up to "
         "4 such regions are kept. Campaign approaches handed over a stationary clutter region 10-40 deg "
         "off the target again and again (12 mode changes, never acquired); 0: never"},
        refuted_fix_frames);
    v.boolean(
        {"farrange", "refuted_follow", "-", 0, 1,
         "robust: a refuted region follows its cluster (each searched frame it moves to the like-sized "
         "cluster nearest its centre within its radius), and a fix refuted again in a region that was "
         "refuted before, still followed, and that did not grow 1.25x in n since, is passed over twice as "
         "long as the time before (up to 8x refuted_fix_frames). Glints drifting across the image 4 px a "
         "frame left their refuted region "
         "within 10 frames and were handed to acquisition again and again (campaign plate/23: 6 attempts, "
         "12 mode changes, every one failing no_target). An approaching target grows out of its region "
         "(4x in n) and is no longer followed; false: regions stay where they were refuted, for "
         "refuted_fix_frames each time"},
        refuted_follow);
    v.integer(
        {"farrange", "recheck_frames", "frames", 0, 100000,
         "robust: every this many fixes of a track, the whole frame is searched "
         "as without a track; its largest plausible cluster replaces the track when it lies outside the "
         "gate, is at least recheck_switch_ratio times the tracked n and reads nearer than the "
         "acquisition hand-over distance (the pipeline's acquire_below_m), from a track that did not "
         "grow (recheck_static_growth). A track taken on clutter before the target was visible held it "
         "for the whole approach (campaign plate/64: a blob 22 deg off, read 40 m, while the plate came "
         "to 6 m); 0: never"},
        recheck_frames);
    v.real({"farrange", "recheck_switch_ratio", "-", 1.0, 1.0e6,
            "see recheck_frames: how many times the tracked n a cluster found by the recheck must be"},
           recheck_switch_ratio);
    v.real({"farrange", "recheck_static_growth", "-", 1.0, 1.0e6,
            "see recheck_frames: only a track whose n grew less than this factor since the last check "
            "(or its start) may be replaced; an approaching target grows (campaign plate/64 closed 2 % of "
            "its range a frame, 750 -> 631.6 m in 8 frames: n 1.5x in 10 frames), clutter does not. Without "
            "it, on the campaign's approaches true "
            "far targets of a few pixels gave way to nearer-reading clutter"},
           recheck_static_growth);
    v.real(
        {"farrange", "min_outline_sharpness", "-", 0.0, 1.0,
         "robust: a cluster whose outline is a ramp rather than a body's edge is never the target: rays "
         "from its centre compare the 2-px step at the outline with the 8-px step "
         "(measureOutlineSharpness at the cluster's scale: 0.71-0.77 for a body's edge with a 1-px blur, "
         "0.27-0.32 for a Gaussian spot; clusters under 10 px radius, sparse ones, and those with under "
         "half their rays on a clear step are not measured, never passed over). Campaign box/2: a blob "
         "14 deg off tracked from 750 m to 7 m, the box never acquired; with 0.5 acquired, 77 of 77. "
         "Seeds 1-40 / 5001-5040 / 7001-7040 (with [navigation] branch_reference_max_look_deg 45, both "
         "since stop 57), against both off: tracked frames 14 665 -> 14 675 / 14 848 -> 14 861 / 15 364 "
         "-> 15 315, confidently wrong 2 / 2 / 7 unchanged, approaches acquired 27 -> 29 / 15 -> 18 / 15 "
         "-> 16, approach mode changes 105 -> 96 / 101 -> 99 / 93 -> 97; far fixes with the target in view "
         "on something else 33 % -> 24 % / 53 % -> 42 % / 53 % -> 40 %. 0: off"},
        min_outline_sharpness);
    v.real(
        {"farrange", "silhouette_min_half_px", "px", 0.0, 4096.0,
         "robust, with the target's radius known (experimental, off): a fix reaching "
         "extent_distance_min_px from its centre is measured again as the silhouette of block means "
         "(SilhouetteExtent: the window's brightness less a plane fitted to its border ring, grown from "
         "the fix) in a window of this half side, at least 4 x its extent, doubled up to "
         "silhouette_max_half_px until a silhouette is taken; one that holds the fix, reaches beyond it "
         "and has a sharp outline (min_outline_sharpness) gives f x bounding radius / its extent when "
         "nearer (flag silhouette_extent). A dim target's fix is a fragment of it and reads too far (cao/"
         "5029: 51 m at 13 m, with it 17 m). At 48 on seeds 1-40 / 5001-5040 / 7001-7040: on-target far "
         "distances within 60 m, 90th percentile of distance / range 2.37 / 3.73 / 5.07 -> 1.25 / 3.22 / "
         "4.67, but silhouettes were also taken on 355 / 695 / 644 fixes on something else and read under "
         "half the range on 54 / 141 / 142 fixes (a glow as bright as the target joins it: box/6 read 15 m "
         "at 29 m and was never acquired), tracked frames -43 / 0 / -5, approaches acquired 29 -> 28, 19, "
         "16 -> 15, wrong frames unchanged; 0: off"},
        silhouette_min_half_px);
    v.real(
        {"farrange", "silhouette_max_half_px", "px", 8.0, 4096.0,
         "robust: the silhouette's window doubles, up to this half side, until a silhouette is taken (a "
         "window inside a large target fits its background on the target and finds only the fragment); "
         "a region on the window's border ring (a limb, a gradient, a glow the target sits on) gives none"},
        silhouette_max_half_px);
    v.integer({"farrange", "silhouette_block_px", "px", 1, 64,
               "robust: the silhouette's smallest block side (larger where the window is wider than 64 "
               "blocks): the noise of a block's mean is the pixels' over this side"},
              silhouette_block_px);
    v.real({"farrange", "silhouette_k_sigma", "-", 1.0, 100.0,
            "robust: a block belongs to the silhouette when its mean departs from the plane fitted to the "
            "window's border ring (either polarity) by more than this many of the ring's robust 1-sigma "
            "(1.4826 x median absolute residual)"},
           silhouette_k_sigma);
    v.real({"farrange", "silhouette_level_ratio", "-", 0.0, 1.0,
            "robust: the silhouette grows only over blocks departing by this share of the strongest "
            "departure within the fix's extent as well: a faint glow beside a bright target departs from "
            "the plane too, and joined to it read a satellite at 181 m as 48 m (campaign smallsat/5015); 0: "
            "any departing block"},
           silhouette_level_ratio);
    v.integer({"farrange", "max_clusters", "count", 1, 65534, "capacity: clusters per frame"}, max_clusters);
    v.integer({"farrange", "max_cluster_pixels", "px", 16, 10000000,
               "capacity: pixels in all clusters of a frame (growth stops and the frame is flagged beyond)"},
              max_cluster_pixels);
  }

  /// Cross-field checks the per-field ranges cannot express. Returns nullptr when valid.
  const char* crossCheck() const {
    if (std::abs(edge_weight + histogram_weight - 1.0) > 1e-9)
      return "[farrange] edge_weight + histogram_weight must sum to 1 (paper eq. 14)";
    if (!(t_out <= t_in)) return "[farrange] t_out must be <= t_in (clusters grow from spawn pixels)";
    if (!(extended_grow <= extended_spawn))
      return "[farrange] extended_grow must be <= extended_spawn (clusters grow from spawn pixels)";
    if (silhouette_min_half_px > 0.0 && !(silhouette_max_half_px >= silhouette_min_half_px))
      return "[farrange] silhouette_max_half_px must be >= silhouette_min_half_px (the window only grows)";
    return nullptr;
  }
};

}  // namespace visnav::far
