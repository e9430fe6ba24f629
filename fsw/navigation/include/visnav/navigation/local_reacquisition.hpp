// Close-range reacquisition: after a near-range loss below the far-range hand-over, the track comes back
// from the last good pose and the predicted motion, without passing through far range (which cannot see an
// extended target). Each frame tries a bounded number of tracker starts: the prediction rotated about the
// camera centre so the target's centre moves over a hexagonal grid of image offsets, ring by ring, out to a
// radius that widens with the frames searched (a slew moves the whole image; an eclipse or a missed
// prediction leaves the target near where it was). Before the outer rings, reacquire_cue_starts starts go
// where the predicted outline, slid over the searched disc on the frame's polarity-free edge evidence
// (acq::EdgeScorer::bestShifts), matches best: the outline cue. A start is a candidate only with good image
// evidence (lines, inliers, residual, edge support), and only when no distinct pose (modulo the model's
// symmetries) tracks as well in the same frame; it is delivered after it keeps tracking with the flight
// settings and moves consistently for reacquire_confirm_frames, and only when its range and its look along
// the line of sight agree with the prediction. Until then the answer is "lost", never a guess. All memory is
// sized in init(); step() allocates nothing and is bounded by the parameters.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/acquisition/acquisition_params.hpp"
#include "visnav/acquisition/edge_scorer.hpp"
#include "visnav/acquisition/working_image.hpp"
#include "visnav/geometry/model_symmetry.hpp"
#include "visnav/navigation/navigation_params.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav::nav {

struct ReacquisitionStep {
  bool found = false;  ///< confirmed: pose and covariance below are the delivered measurement
  TrackStatus status = TrackStatus::kLost;  ///< the confirming tracker's verdict (found)
  bool candidate = false;                   ///< a candidate is being confirmed
  bool ambiguous = false;  ///< two distinct poses tracked equally well this frame: none was taken
  Pose pose;
  Mat6 covariance = Mat6::Zero();
  double quality = 0.0;
  /// found: the confirmation's pose on the frame before (the target's motion between the two starts the
  /// filter's velocity; a target moving 16 px a frame outruns the flight tracker's scanlines at zero
  /// velocity).
  bool has_previous = false;  ///< previous_pose is set: the find's pose on the frame before
  Pose previous_pose;
  Mat6 previous_covariance = Mat6::Zero();
  /// found by the acquisition that searches alongside after reacquire_acquisition_after_frames
  /// (navigation_pipeline.cpp), not by the local grid.
  bool by_acquisition = false;
  int acquisition_state = -1;         ///< that acquisition's AcquisitionState this frame (-1: not run)
  int acquisition_failure = 0;        ///< and its AcquisitionFailure when it failed (0: none)
  double acquisition_edge_snr = 0.0;  ///< and its window's edge SNR (0: no window prepared)
  bool far_cue = false;      ///< that acquisition was cued by far range this frame (reacquire_far_cue)
  bool outline_cue = false;  ///< or by the outline cue's best match (reacquire_acquisition_outline_cue)
  /// The search's prediction was moved to this range this frame: the range the track's rate reached since
  /// the search began (reacquire_range_rate_rung; 0: the prediction's own range).
  double rate_rung_range_m = 0.0;
  /// It started at the filter's position when the search began (reacquire_motion_hedge).
  bool motion_hedge = false;
  Vec3 searched_t_c_m = Vec3::Zero();  ///< the position this frame's local search started at
  /// found by that acquisition with a near twin the image cannot resolve, told apart by the look of the
  /// last valid pose (acq::AcquisitionResult::twin_resolved_by_continuity)
  bool twin_by_continuity = false;
  int hypotheses = 0;  ///< tracker starts tried this frame
  int cue_starts = 0;  ///< of them, at the outline's best shifts (reacquire_cue_starts)
  int search_radius_px = 0;
  // Why the starts of this frame were not taken (diagnostics: the campaign's --trace).
  int starts_lost = 0;          ///< the wide tracker lost the target from the start
  int starts_weak = 0;          ///< tracked, but the image evidence was not good
  int starts_inconsistent = 0;  ///< good evidence, but range or look disagree with the prediction
  double best_quality = 0.0;    ///< the best candidate's quality (0: none)
};

class LocalReacquisition {
 public:
  /// `evidence`: the outline cue reads edges as the acquisition does (its spreads, cap, samples and
  /// internal-edge weight).
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const NavigationParams& params,
                 const NearRangeParams& nearrange, const acq::AcquisitionParams& evidence = {});
  void start();
  void stop() { m_active = false; }
  bool active() const { return m_active; }
  int framesSearching() const { return m_frames; }
  /// A candidate is being confirmed: the next step() judges it against the prediction it is given.
  bool confirming() const { return m_active && m_confirming; }
  const ModelSymmetries& symmetries() const { return m_symmetries; }
  /// The candidate keeps the last step's predicted range and look (attitude seen along its own line of
  /// sight, modulo symmetries) within tolerances that widen with the frames searched: a slew or a missed
  /// prediction moves the target across the image, but does not turn it over or move it in depth.
  bool consistentWithPrediction(const Pose& candidate) const {
    return agrees(m_predicted, candidate, static_cast<std::uint64_t>(m_frames), true);
  }
  /// The look alone (no range) against a pose `frames` frames old, with the same widening tolerance: what
  /// the close-range acquisition's find must keep against the last valid pose. Its range may be far from
  /// it (an approach while lost), but in a few frames a target cannot turn over.
  bool lookConsistentWith(const Pose& reference, std::uint64_t frames, const Pose& candidate) const {
    return agrees(reference, candidate, frames, false);
  }
  /// The attitude tolerance of those tests after `frames` frames [rad].
  double lookToleranceRad(std::uint64_t frames) const;

  /// This frame's best match of the predicted outline over the searched disc (findCues): its image offset
  /// from the prediction's centre [px] (zero when the prediction matched best); false when no cue ran.
  bool bestCueOffset(Vec2& offset_px) const {
    offset_px = m_best_cue_offset_px;
    return m_best_cue_found;
  }

  /// One frame; `predicted` is the filter's prediction for this exposure (or the last good pose).
  void step(const MonoImage& image, const Pose& predicted, std::uint64_t frame_number,
            ReacquisitionStep& out);

 private:
  bool agrees(const Pose& reference, const Pose& candidate, std::uint64_t frames, bool check_range) const;
  Pose hypothesis(const Pose& predicted, int index) const;
  /// The pose turned about the camera centre so that its projected centre moves by offset_px (a slew).
  Pose movedAcrossImage(const Pose& pose, const Vec2& offset_px) const;
  /// The predicted outline slid over the disc of radius_px around it: the image offsets (full px) of its
  /// best matches into m_cue_peaks' shifts, at most `capacity`; returns their count.
  int findCues(const MonoImage& image, const Pose& predicted, double radius_px, int capacity);
  /// One hypothesis: within one frame's motion plus what the tracker cannot resolve around `r`.
  PoseTolerance tolerance(const NearRangeResult& r) const;

  static int hypothesesWithinRings(int rings) { return 1 + 3 * rings * (rings + 1); }
  /// `passes` tracker steps from `start`; whether the result's image evidence is good
  /// (imageEvidenceGood, with `continues_rival_free_fit`).
  bool trackFrom(NearRangeTracker& tracker, const MonoImage& image, const Pose& start,
                 std::uint64_t frame_number, int passes, NearRangeResult& result,
                 bool continues_rival_free_fit = false) const;
  void search(const MonoImage& image, const Pose& predicted, std::uint64_t frame_number,
              ReacquisitionStep& out);
  void confirm(const MonoImage& image, std::uint64_t frame_number, ReacquisitionStep& out);
  /// The wide tracker from `start`, then the flight tracker from its pose into `r`: good image evidence?
  bool refitFrom(const MonoImage& image, const Pose& start, std::uint64_t frame_number, bool continuity,
                 NearRangeResult& r);
  /// `around` moved to where its outline best matches the frame within the confirmation's motion limit
  /// (the match at `around` itself excluded): false without one.
  bool cueNear(const MonoImage& image, const Pose& around, Pose& cue_start);

  PinholeCamera m_camera;
  NavigationParams m_params;
  ModelSymmetries m_symmetries;
  NearRangeTracker m_wide;    ///< long scanlines: the capture range of one start
  NearRangeTracker m_flight;  ///< the flight tracker's settings: what the hand-over will meet
  double m_step_px = 1.0;
  bool m_active = false;
  bool m_confirming = false;
  int m_frames = 0;
  int m_cursor = 0;
  int m_confirmed = 0;
  Pose m_candidate;
  Mat6 m_candidate_covariance = Mat6::Zero();
  Vec6 m_candidate_motion = Vec6::Zero();  ///< per frame, between the last two confirmation frames
  bool m_candidate_moving = false;         ///< m_candidate_motion measured
  Pose m_predicted;                        ///< this frame's prediction (step())
  double m_bounding_radius_m = 0.0;
  double m_cue_min_radius_px = 0.0;  ///< reacquire_cue_min_radius_deg on this camera
  acq::WorkingImage m_cue_window;    ///< the searched disc, box-averaged to kCueWindowSidePx at most
  acq::EdgeScorer m_cue_scorer;
  acq::AcquisitionParams m_evidence;  ///< fine/coarse spread and cap of m_cue_window
  /// This frame's cue: bestShifts' peaks, then (findCues) their offsets in full-resolution px.
  std::array<acq::ShiftPeak, LocalSearchLimits::kMaxCueStarts> m_cue_peaks{};
  bool m_best_cue_found = false;             ///< this frame's findCues had a peak
  Vec2 m_best_cue_offset_px = Vec2::Zero();  ///< its best, from the prediction's centre (full px)
};

}  // namespace visnav::nav
