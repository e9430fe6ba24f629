// Every tunable of the near-range tracker (paper sec. II), with units, ranges and defaults. The generated
// reference is config/PARAMETERS.md; the values used by a run come from the [nearrange] table of its config.
#pragma once

#include "visnav/core/param_visitor.hpp"

namespace visnav {

enum class EdgePolarityMode : int { kAny = 0, kLearned = 1 };
enum class PoseResidualMode : int { kVertex = 0, kPointToLine = 1 };

struct NearRangeParams {
  // Scanlines (sec. II-D): density is the paper's accuracy/time knob.
  double scanline_spacing_px = 6.0;
  int scanline_half_length_px = 10;
  double vertex_margin_px = 5.0;
  double min_edge_length_px = 12.0;
  // Edge point on a scanline (eq. 4, eq. 5 / Algorithm 1).
  int min_scanlines_per_edge = 10;
  int scanline_band_half_width_px = 2;
  double contrast_delta = 0.2;
  int step_window_px = 4;
  double step_min_z = 5.0;
  double edge_candidate_min_share = 0.5;
  double confusable_edge_separation_px = 6.0;
  int texture_bins = 32;
  double texture_min_log_gain = 1.0;
  double texture_min_variance_ratio = 10.0;
  bool subpixel = true;
  int polarity_mode = static_cast<int>(EdgePolarityMode::kLearned);
  // RANSAC line fit (sec. II-E).
  double ransac_threshold_px = 0.9;
  int ransac_iterations = 100;
  int ransac_seed = 1;
  int min_points_per_line = 5;
  bool uncut_line_scatter = false;  ///< a line's point sigma undoes the RANSAC threshold's cut
  double min_inlier_ratio = 0.4;
  // Pose update (sec. II-G).
  int pose_residual = static_cast<int>(PoseResidualMode::kVertex);
  int lm_max_iterations = 100;
  double pixel_sigma_px = 0.1;
  double line_end_bias_px = 0.0;          ///< systematic line-end error, not averaged down by points
  double interior_edge_bias_px = 0.0;     ///< the same, added on the lines of interior edges
  double narrow_face_edge_bias_px = 0.0;  ///< the same, added on the two lines of a narrow face's strip
  double max_rms_px = 1.5;
  double degraded_rms_px = 0.6;
  double reject_line_rms_gain = 0.5;
  double reject_line_trigger_rms_px = 0.15;
  int max_rejected_lines = 3;
  bool mirrored_rival_relabel = true;     ///< the rival's fit relabels lines through the model mirror
  double near_twin_rival_max_rel = 0.25;  ///< near twins refitted when asked (setNearTwinChecks)
  // Surface switching (sec. II-H), viewing angle v of CONVENTIONS.md.
  double visibility_enter_low_deg = 45.0;
  double visibility_enter_high_deg = 135.0;
  double visibility_exit_low_deg = 40.0;
  double visibility_exit_high_deg = 140.0;
  bool silhouette_edges = true;
  bool occluded_scanlines = true;  ///< no scanline where the edge is hidden behind a nearer surface
  // Capacities (memory is sized from these at init).
  int max_tracked_surfaces = 16;
  int max_scanlines_per_edge = 256;

  template <typename Visitor>
  void visit(Visitor& v) {
    v.real({"nearrange", "scanline_spacing_px", "px", 1.0, 200.0,
            "distance between neighbouring scanlines along a projected edge (sec. II-D)"},
           scanline_spacing_px);
    v.integer({"nearrange", "scanline_half_length_px", "px", 2, 64,
               "samples on each side of the predicted edge; bounds the tracked inter-frame motion"},
              scanline_half_length_px);
    v.real({"nearrange", "vertex_margin_px", "px", 0.0, 100.0,
            "no scanline closer than this to a projected vertex (it would cross the neighbouring edge)"},
           vertex_margin_px);
    v.real({"nearrange", "min_edge_length_px", "px", 2.0, 1000.0,
            "projected edges shorter than this are not measured"},
           min_edge_length_px);
    v.integer(
        {"nearrange", "min_scanlines_per_edge", "count", 1, 4096,
         "a measured edge gets at least this many scanlines (closer than scanline_spacing_px, never closer "
         "than 1 px), so a short edge of a small target can still reach min_points_per_line"},
        min_scanlines_per_edge);
    v.integer({"nearrange", "scanline_band_half_width_px", "px", 0, 8,
               "each scanline sample averages 2 b + 1 samples 1 px apart along the predicted edge (oriented "
               "mask): noise down by sqrt(2 b + 1) while a straight edge stays sharp"},
              scanline_band_half_width_px);
    v.real({"nearrange", "contrast_delta", "-", 0.0, 1.0,
            "delta of sec. II-D: a significant step at least this large (brightness 0..1) is a strong "
            "(gradient) edge, a weaker one is reported as a weak-contrast step"},
           contrast_delta);
    v.integer({"nearrange", "step_window_px", "px", 1, 16,
               "w: the step between two samples is the difference of the means of w samples on either side "
               "(eq. 4 is w = 1); covers a blurred edge and averages noise"},
              step_window_px);
    v.real({"nearrange", "step_min_z", "sigma", 0.0, 100.0,
            "a step is an edge point when it exceeds this many standard deviations of its noise, measured on "
            "the scanline (5: about 1 false point in 100 noise-only scanlines, campaign edge statistics)"},
           step_min_z);
    v.real(
        {"nearrange", "edge_candidate_min_share", "-", 0.0, 1.0,
         "of the significant steps on a scanline at least this share of the strongest, the one nearest the "
         "predicted edge is taken (1: the strongest, eq. 4's argmax); a scanline across a small target "
         "also crosses its neighbouring edges"},
        edge_candidate_min_share);
    v.real({"nearrange", "confusable_edge_separation_px", "px", 0.0, 64.0,
            "an interior edge whose parallel outline neighbour projects closer than this is not measured: "
            "the step test (two step_window_px windows plus blur) cannot tell the two steps apart, and a "
            "flat-lit interior edge has no step of its own (campaign box/17: strips of 2.5-3.8 px; slew_box "
            "measures both at 8-14 px); 0 measures every edge"},
           confusable_edge_separation_px);
    v.integer({"nearrange", "texture_bins", "count", 2, 256, "brightness classes of Algorithm 1"},
              texture_bins);
    v.real(
        {"nearrange", "texture_min_log_gain", "nats", 0.0, 1000.0,
         "a texture split must explain the scanline better than one texture by this log-likelihood margin, "
         "else the scanline yields no point (a uniform patch has no edge)"},
        texture_min_log_gain);
    v.real({"nearrange", "texture_min_variance_ratio", "-", 1.0, 1e6,
            "a texture split is kept only when one side's variance is this many times the other's: a "
            "histogram ignores order, so noise on a ramp scores like a clean step (both <= 2.65 nats on 21 "
            "samples); a change of spread is what a texture edge without a step has and noise has not"},
           texture_min_variance_ratio);
    v.boolean({"nearrange", "subpixel", "-", 0, 1,
               "refine the eq. 4 maximum to sub-pixel with a Gaussian/parabola fit of w"},
              subpixel);
    v.enumeration({"nearrange", "polarity_mode", "-", 0, 1,
                   "any: argmax |w|; learned: argmax of w signed by the polarity seen at the same place "
                   "of the edge in the last frame (contrast may reverse along an outline)"},
                  "any|learned", polarity_mode);
    v.real({"nearrange", "ransac_threshold_px", "px", 0.05, 20.0, "alpha of sec. II-E: consensus distance"},
           ransac_threshold_px);
    v.integer({"nearrange", "ransac_iterations", "count", 1, 10000, "n of sec. II-E: hypotheses per line"},
              ransac_iterations);
    v.integer({"nearrange", "ransac_seed", "-", 0, 2147483647,
               "seed of the deterministic generator (same seed and input => same output)"},
              ransac_seed);
    v.integer({"nearrange", "min_points_per_line", "count", 2, 1000,
               "fewer consensus points: line not used; an edge too short for this many scanlines (a chamfer "
               "seen from afar) counts neither as a line nor as a missed one, and the lines of its two "
               "neighbours on the face meet across it as a corner of the vertex fit"},
              min_points_per_line);
    v.real(
        {"nearrange", "min_inlier_ratio", "-", 0.0, 1.0,
         "smaller consensus/points ratio: line not used. Under noise blurred with the image a scanline's "
         "5-sigma test also passes noise steps (46 % of scanlines without an edge, edge_study; "
         "fsw/nearrange/README.md), so a true edge can keep under half its points within alpha. 0.5 -> 0.4 "
         "(stop 83), campaign seeds 1-40 / 41-80 / 81-120: tracked frames 15 607 -> 15 642 / 14 870 -> "
         "14 906 / 15 064 -> 15 079 (box 7 013 -> 6 978, smallsat 9 468 -> 9 556), confidently wrong 0 "
         "/ 0 / 0, mode changes 406 unchanged; 0.3 not measured"},
        min_inlier_ratio);
    v.enumeration({"nearrange", "pose_residual", "-", 0, 1,
                   "vertex: eq. 7 over intersected vertices; point_to_line: every inlier edge point"},
                  "vertex|point_to_line", pose_residual);
    v.integer({"nearrange", "lm_max_iterations", "count", 1, 500, "Levenberg-Marquardt iteration bound"},
              lm_max_iterations);
    v.real({"nearrange", "pixel_sigma_px", "px", 0.001, 10.0,
            "1-sigma measurement noise of an edge point, scales the reported covariance"},
           pixel_sigma_px);
    v.real(
        {"nearrange", "line_end_bias_px", "px", 0.0, 10.0,
         "1-sigma systematic error of a fitted line's end (blur, shading, a neighbouring edge), which more "
         "points do not reduce, added to the scatter its points give in the covariance delivered with a "
         "pose and judged by [navigation] max_valid_attitude_sigma_deg and the other validity limits (the "
         "filter keeps the scatter's: NearRangeResult::systematic_gain). On campaign seeds 1-8 (40 scenes, "
         "--trace) the fitted lines' ends lay 0.29 px rms from the true edges where their scatter put them "
         "at 0.14 px; 0.22 px makes the normalised squared error 1 over all families (plate 0.07, box "
         "0.33). Off by default: replayed on seeds 1-40 (gate_replay.py on the columns systematic_gain and "
         "cov_*), 0.1 withheld 115 more frames of right poses for no fewer wrong ones, 0.2 withheld 552 for "
         "2 fewer; run on seeds 1 / 5001 / 7001, 0.1 cost 510 tracked frames and 7 losses never recovered "
         "for 3 fewer wrong frames (top-level README, stop 61); 0 switches it off"},
        line_end_bias_px);
    v.real({"nearrange", "interior_edge_bias_px", "px", 0.0, 10.0,
            "1-sigma systematic error of the ends of an interior edge's line (both its faces front-facing), "
            "added to line_end_bias_px's in the covariance delivered with a pose and its validity, not in "
            "the filter's: such an edge's step is between two shaded faces and beside the outline, and on "
            "campaign boxes (seeds 1-40, --trace, delivered poses) their line ends lay 3.7 px rms from the "
            "true edges (9.6 % beyond 1 px) where outline ends lay 0.73 px rms (1.5 %). Off by default: "
            "replayed on seeds 1 / 5001 / 7001, 0.8 px removed 7 of the 8 wrong frames for 460 of 45 104 "
            "tracked frames, but already 0.3 px lifts 33 of slew_box's doubted poses across the 1 deg "
            "doubted limit (117 -> 84 of 120 tracked, below the case's 97 % gate; top-level README, stop "
            "62); 0 switches it off"},
           interior_edge_bias_px);
    v.real({"nearrange", "narrow_face_edge_bias_px", "px", 0.0, 10.0,
            "1-sigma systematic error of the ends of the two lines that bound a face seen as a strip "
            "narrower than confusable_edge_separation_px (kFlagNarrowFace), added like "
            "interior_edge_bias_px: the step test cannot tell the strip's two steps apart, and a face "
            "that turns away puts its edge on the outline (campaign box/25 frame 60: such a line 4.7 px "
            "off, the pose 6.3 deg off at a 0.78 deg 1-sigma). Off by default: replayed on seeds 1 / 5001 "
            "/ 7001, 0.7 px removed 3 of the 8 wrong frames for 849 tracked frames, and slew_box fell to "
            "84 of 120 (top-level README, stop 62); 0 switches it off"},
           narrow_face_edge_bias_px);
    v.real({"nearrange", "max_rms_px", "px", 0.01, 100.0, "pose residual above this: status lost"},
           max_rms_px);
    v.real({"nearrange", "degraded_rms_px", "px", 0.01, 100.0, "pose residual above this: status degraded"},
           degraded_rms_px);
    v.real({"nearrange", "reject_line_rms_gain", "-", 0.01, 1.0,
            "leave-one-line-out: a refit without one line replaces the fit only when its residual is below "
            "this fraction of the fit's (one wrong line, e.g. locked onto a neighbour, must explain a clear "
            "share of the residual to be dropped)"},
           reject_line_rms_gain);
    v.real(
        {"nearrange", "reject_line_trigger_rms_px", "px", 0.0, 100.0,
         "leave-one-line-out is tried when the fit's residual exceeds this (or the fit failed): a face "
         "entering at a grazing angle locked one edge onto its neighbour at 0.4 px rms where the track ran "
         "at 0.01-0.03 px (slew_box), below degraded_rms_px; 0.2 until 2026-11-29, when an outline line "
         "2.5 px off (slew_box frame 116) fitted at 0.19 px rms and the relabelled rival flagged the frame"},
        reject_line_trigger_rms_px);
    v.integer(
        {"nearrange", "max_rejected_lines", "count", 0, 16,
         "leave-one-line-out is repeated up to this many times while the residual stays above the "
         "trigger: a small target's short scanlines can lock several edges onto neighbours in one frame "
         "(smallsat: 3 of 13 lines 2-7 px off at 1.9 px rms); each pass costs one LM per used line"},
        max_rejected_lines);
    v.real({"nearrange", "visibility_enter_low_deg", "deg", 0.0, 90.0, "sec. II-H: start tracking above"},
           visibility_enter_low_deg);
    v.real({"nearrange", "visibility_enter_high_deg", "deg", 90.0, 180.0, "sec. II-H: start tracking below"},
           visibility_enter_high_deg);
    v.real({"nearrange", "visibility_exit_low_deg", "deg", 0.0, 90.0, "sec. II-H: stop tracking below"},
           visibility_exit_low_deg);
    v.real({"nearrange", "visibility_exit_high_deg", "deg", 90.0, 180.0, "sec. II-H: stop tracking above"},
           visibility_exit_high_deg);
    v.boolean(
        {"nearrange", "mirrored_rival_relabel", "-", 0, 1,
         "ambiguity test: the depth-mirrored rival's fit assigns each measured line and corner to the "
         "model feature the model's mirror symmetry makes of it, as the rival pose projects it (a box's "
         "Necker twin), and the rival must show the outline it explains. Seeds 1-40 with "
         "reject_line_trigger_rms_px 0.15: confidently wrong frames 18 -> 13 (box 13 -> 7), tracked frames "
         "14 913 -> 14 843 (fsw/nearrange/README.md). false: the rival is fitted to the lines as measured "
         "and a box's twin is never flagged"},
        mirrored_rival_relabel);
    v.real(
        {"nearrange", "near_twin_rival_max_rel", "-", 0.0, 1.0,
         "near twins the tracker refits to its measured lines when the caller asks (a track whose branch "
         "is not yet confirmed): turns of the model onto itself within this fraction of its bounding "
         "radius (a near-square plate's quarter turn), the closest NearRangeTracker::kMaxNearTwins of them. "
         "One that fits as well flags kFlagNearTwinRival. 0: none"},
        near_twin_rival_max_rel);
    v.boolean(
        {"nearrange", "uncut_line_scatter", "-", 0, 1,
         "a line's point sigma, which sets how well its ends and the vertices on it are known, is "
         "that of the normal scatter whose part within ransac_threshold_px the inliers show "
         "(uncutScatterVariance), not the inliers' own: at the 0.9 px threshold a 0.6 px scatter "
         "looks like 0.45. Campaign trace, seeds 1-8: where the points scatter 0.4-0.8 px, the line ends' "
         "true offsets spread 1.5-2.7 times their claimed sigma, 1.2-1.4 times with it. Off: on "
         "seeds 1-40 tracked mean 0.637 -> 0.632 and confidently wrong frames 7 -> 8 with it"},
        uncut_line_scatter);
    v.boolean({"nearrange", "silhouette_edges", "-", 0, 1,
               "also measure the outline of the body (edges between a front and a back face, open edges of "
               "front faces) outside the sec. II-H gate: it has contrast against the background when a "
               "multi-face body shows no face inside the gate or faces of equal brightness"},
              silhouette_edges);
    v.boolean({"nearrange", "occluded_scanlines", "-", 0, 1,
               "no scanline is cast where its point of the model edge lies behind another front-facing "
               "surface nearer the camera (a solar panel in front of a body edge, one part of a .cao model "
               "in front of another): the step found there is the occluder's (test OccludedScanlines: a bar "
               "6 px inside split a plate edge's points and it gave no line; campaign seeds 1 / 5001 / 7001: "
               "smallsat 155 / 176 / 80 more tracked frames, no other family changed); an edge left with "
               "fewer visible scanlines than min_points_per_line counts as too short to measure. Back-facing "
               "surfaces do not occlude (single-sided plates, as the renderer draws them)"},
              occluded_scanlines);
    v.integer({"nearrange", "max_tracked_surfaces", "count", 1, 256, "capacity: surfaces tracked at once"},
              max_tracked_surfaces);
    v.integer({"nearrange", "max_scanlines_per_edge", "count", 4, 4096, "capacity: scanlines per edge"},
              max_scanlines_per_edge);
  }

  /// Cross-field checks the per-field ranges cannot express. Returns nullptr when valid.
  const char* crossCheck() const {
    if (!(visibility_exit_low_deg <= visibility_enter_low_deg))
      return "visibility_exit_low_deg must be <= visibility_enter_low_deg (hysteresis)";
    if (!(visibility_enter_high_deg <= visibility_exit_high_deg))
      return "visibility_enter_high_deg must be <= visibility_exit_high_deg (hysteresis)";
    if (!(degraded_rms_px <= max_rms_px)) return "degraded_rms_px must be <= max_rms_px";
    if (step_window_px > scanline_half_length_px)
      return "step_window_px must be <= scanline_half_length_px (both windows lie on the scanline)";
    if (min_scanlines_per_edge > max_scanlines_per_edge)
      return "min_scanlines_per_edge must be <= max_scanlines_per_edge";
    return nullptr;
  }
};

}  // namespace visnav
