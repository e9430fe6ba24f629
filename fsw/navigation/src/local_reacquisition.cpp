#include "visnav/navigation/local_reacquisition.hpp"

#include <algorithm>
#include <cmath>

#include "visnav/navigation/fdir_monitor.hpp"

namespace visnav::nav {

namespace {

/// Tracker passes per start: the first pulls the pose in from the wide capture range, the second refines.
constexpr int kPassesPerStart = 2;
/// A rival must track at least this share of the best start's quality to make the frame ambiguous.
constexpr double kRivalQualityShare = 0.9;
/// The outline cue's window: at most this many working pixels a side (the disc is box-averaged to fit), and
/// the target's radius at about kCueTargetRadiusPx working pixels at most (more adds cost, not evidence).
constexpr int kCueWindowSidePx = 160;
constexpr double kCueTargetRadiusPx = 32.0;
/// Shifts tried 4 working px apart (half the default coarse spread, 8: a peak is not missed between two).
constexpr double kCueShiftStepPx = 4.0;

}  // namespace

LoadError LocalReacquisition::init(const PinholeCamera& camera, const PolygonModel& model,
                                   const NavigationParams& params, const NearRangeParams& nearrange,
                                   const acq::AcquisitionParams& evidence) {
  m_camera = camera;
  m_params = params;
  m_symmetries.find(model);
  NearRangeParams wide = nearrange;
  wide.scanline_half_length_px = params.reacquire_scanline_half_length_px;
  m_step_px = std::max(1.0, params.reacquire_step_rel * params.reacquire_scanline_half_length_px);
  m_bounding_radius_m = model.boundingRadius();
  m_cue_min_radius_px =
      camera.intrinsics().fx_px * std::tan(params.reacquire_cue_min_radius_deg * kRadPerDeg);
  LoadError e = m_wide.init(camera, model, wide);
  if (e.ok) e = m_flight.init(camera, model, nearrange);
  if (e.ok) e = m_cue_window.init(kCueWindowSidePx, 256, 2 * std::max(camera.width(), camera.height()));
  m_evidence = evidence;
  if (e.ok)
    e = m_cue_scorer.init(
        camera, model, acq::ScorerSettings{evidence.samples_per_hypothesis, evidence.internal_edge_weight});
  if (!e.ok) return LoadError::failure("reacquisition: " + e.message);
  m_active = false;
  return LoadError::success();
}

void LocalReacquisition::start() {
  m_active = true;
  m_confirming = false;
  m_frames = 0;
  m_cursor = 0;
  m_confirmed = 0;
}

PoseTolerance LocalReacquisition::tolerance(const NearRangeResult& r) const {
  return PoseTolerance::widened(m_params.reacquire_max_motion_rel * r.pose.t_c_m.z(),
                                m_params.reacquire_max_rotation_deg * kRadPerDeg, r.covariance);
}

Pose LocalReacquisition::hypothesis(const Pose& predicted, int index) const {
  // Index 0: the prediction. Ring k >= 1 holds 6k starts at radius k * step, evenly spaced.
  if (index == 0) return predicted;
  int ring = 1;
  while (hypothesesWithinRings(ring) <= index) ++ring;  // bounded: ring <= the largest ring searched
  const int j = index - hypothesesWithinRings(ring - 1);
  const double angle = 2.0 * kPi * j / (6.0 * ring);
  return movedAcrossImage(predicted, ring * m_step_px * Vec2(std::cos(angle), std::sin(angle)));
}

Pose LocalReacquisition::movedAcrossImage(const Pose& pose, const Vec2& offset_px) const {
  Vec2 centre_px;
  if (!m_camera.project(pose.t_c_m, centre_px)) return pose;
  // Rotating the pose about the camera centre moves the target in the image as a slew does.
  const Mat3 r = rotationBetween(m_camera.bearing(centre_px), m_camera.bearing(centre_px + offset_px));
  Pose h;
  h.R_c_m = r * pose.R_c_m;
  h.t_c_m = r * pose.t_c_m;
  return h;
}

int LocalReacquisition::findCues(const MonoImage& image, const Pose& predicted, double radius_px,
                                 int capacity) {
  // The grid walks its rings a dozen starts a frame: a target that moved 150 px while lost waited ~10
  // frames for the walk to reach it, and had moved on by then (campaign box/114: 17 px a frame). The
  // outline at the predicted look and range, slid over the whole disc on the frame's polarity-free edge
  // evidence, points at it in one frame; the starts there are judged like any other (image evidence,
  // consistency with the prediction, rivals), so a cue on clutter costs a start, never a wrong pose.
  Vec2 centre_px;
  const double range_m = predicted.t_c_m.z();
  if (capacity <= 0 || !(range_m > 0.0) || !m_camera.project(predicted.t_c_m, centre_px)) return 0;
  const double target_radius_px = m_camera.intrinsics().fx_px * m_bounding_radius_m / range_m;
  // An outline wider than the image has nothing to slide over (a prediction coasted past the camera: campaign
  // plate/26 hung on such a window before WorkingImage capped it).
  const double diagonal_px = std::hypot(m_camera.width(), m_camera.height());
  if (!(target_radius_px <= diagonal_px)) return 0;
  const double half_px = std::min(radius_px, diagonal_px) + 1.2 * target_radius_px;
  const int scale = std::max({1, static_cast<int>(std::ceil(2.0 * half_px / kCueWindowSidePx)),
                              static_cast<int>(target_radius_px / kCueTargetRadiusPx + 0.5)});
  const int used = m_cue_window.setWindow(centre_px, half_px, scale);
  m_cue_window.prepare(image, m_evidence.fine_spread_px, m_evidence.coarse_spread_px,
                       m_evidence.evidence_cap);
  const double separation_px = std::max(2.0 * kCueShiftStepPx, 0.5 * target_radius_px / used);
  const int peaks = m_cue_scorer.bestShifts(predicted, m_cue_window, radius_px / used, kCueShiftStepPx,
                                            separation_px, m_cue_peaks.data(), capacity);
  if (peaks > 0) {
    m_best_cue_found = true;
    m_best_cue_offset_px = m_cue_peaks[0].shift * static_cast<double>(used);
  }
  int count = 0;
  for (int k = 0; k < peaks; ++k) {
    const Vec2 offset_px = m_cue_peaks[static_cast<std::size_t>(k)].shift * static_cast<double>(used);
    if (offset_px.norm() < 0.5 * m_step_px) continue;  // the prediction itself: tried already
    m_cue_peaks[static_cast<std::size_t>(count++)].shift = offset_px;
  }
  return count;
}

bool LocalReacquisition::agrees(const Pose& reference, const Pose& candidate, std::uint64_t frames,
                                bool check_range) const {
  const double range = reference.t_c_m.norm();
  if (!(range > 0.0) || !(candidate.t_c_m.norm() > 0.0)) return false;
  // The reference turned about the camera centre onto the candidate's line of sight: what a slew does.
  const Pose aligned = ModelSymmetries::turnedOntoLineOfSight(reference, candidate);
  PoseTolerance tol;
  // Turned onto the candidate's line of sight, the reference differs from it in position by the range
  // difference alone: a tolerance beyond both ranges leaves the look as the only test.
  tol.position_m =
      check_range ? m_params.reacquire_range_tolerance_rel * range : 2.0 * (range + candidate.t_c_m.norm());
  tol.attitude_rad = lookToleranceRad(frames);
  return m_symmetries.equivalent(candidate, aligned, tol);
}

double LocalReacquisition::lookToleranceRad(std::uint64_t frames) const {
  return (m_params.reacquire_attitude_tolerance_deg +
          m_params.reacquire_tolerance_growth_deg_per_frame * static_cast<double>(frames)) *
         kRadPerDeg;
}

bool LocalReacquisition::trackFrom(NearRangeTracker& tracker, const MonoImage& image, const Pose& start,
                                   std::uint64_t frame_number, int passes, NearRangeResult& result,
                                   bool continues_rival_free_fit) const {
  tracker.reset();
  Pose pose = start;
  for (int pass = 0; pass < passes; ++pass) {
    tracker.track(image, pose, frame_number, result);
    if (result.status == TrackStatus::kLost) return false;
    pose = result.pose;
  }
  // Degraded is fine (a grazing face's line rejected): the evidence test judges what was used.
  return imageEvidenceGood(result, m_params, continues_rival_free_fit);
}

void LocalReacquisition::search(const MonoImage& image, const Pose& predicted, std::uint64_t frame_number,
                                ReacquisitionStep& out) {
  const double radius_px = m_step_px + m_params.reacquire_growth_px_per_frame * m_frames;
  const double diagonal_px = std::hypot(m_camera.width(), m_camera.height());
  const int rings = static_cast<int>(std::ceil(std::min(radius_px, diagonal_px) / m_step_px));
  const int total = hypothesesWithinRings(rings);
  out.search_radius_px = static_cast<int>(rings * m_step_px);
  bool have_best = false;
  NearRangeResult best;
  bool ambiguous = false;
  NearRangeResult r;
  // The prediction and its first ring are tried on every frame (a target that reappears after an eclipse
  // is most likely there); the rest of the budget walks the outer rings, continuing where the last frame
  // stopped, so the whole widening grid is covered over the frames.
  const int inner = std::min(hypothesesWithinRings(1), total);
  const int per_frame = m_params.reacquire_hypotheses_per_frame;
  // Then the outline's best matches over the disc, then the outer rings with what is left of the budget.
  // A slew moves the target a hundred pixels at once: the cue may look wider than the grid has grown, and
  // its starts may also take the part of the budget a grid of one ring cannot fill.
  const double cue_radius_px = std::max<double>(out.search_radius_px, m_cue_min_radius_px);
  const int room = per_frame - inner;
  const int cues =
      room > 0 ? findCues(image, predicted, cue_radius_px, std::min(m_params.reacquire_cue_starts, room)) : 0;
  const int budget = std::min(per_frame, total + cues);
  for (int n = 0; n < budget; ++n) {
    Pose start;
    if (n < inner) {
      start = hypothesis(predicted, n);
    } else if (n < inner + cues) {
      start = movedAcrossImage(predicted, m_cue_peaks[static_cast<std::size_t>(n - inner)].shift);
      ++out.cue_starts;
    } else {
      if (m_cursor < inner || m_cursor >= total) m_cursor = inner;  // re-centred on each frame's prediction
      start = hypothesis(predicted, m_cursor++);
    }
    ++out.hypotheses;
    if (!trackFrom(m_wide, image, start, frame_number, kPassesPerStart, r)) {
      ++(r.status == TrackStatus::kLost ? out.starts_lost : out.starts_weak);
      continue;
    }
    if (!consistentWithPrediction(r.pose)) {
      ++out.starts_inconsistent;
      continue;
    }
    if (!have_best) {
      best = r;
      have_best = true;
      continue;
    }
    if (m_symmetries.equivalent(r.pose, best.pose, tolerance(best))) {
      if (r.quality > best.quality) best = r;
      continue;
    }
    // A distinct pose that explains the image about as well: no way to tell which is right.
    if (r.quality >= kRivalQualityShare * best.quality && best.quality >= kRivalQualityShare * r.quality)
      ambiguous = true;
    if (r.quality > best.quality) best = r;
  }
  if (!have_best) return;
  out.best_quality = best.quality;
  if (ambiguous) {
    out.ambiguous = true;
    return;
  }
  m_candidate = best.pose;
  m_candidate_covariance = best.covariance;
  m_candidate_moving = false;
  m_confirming = true;
  m_confirmed = 0;
  m_flight.reset();
  out.candidate = true;
}

void LocalReacquisition::confirm(const MonoImage& image, std::uint64_t frame_number, ReacquisitionStep& out) {
  // The candidate moved on by a frame's motion: the last measured one once known. The wide tracker pulls it
  // in over that motion where the flight tracker alone loses it (a target moving 16 px a frame, campaign
  // cao/45); the flight tracker judges it as the hand-over will meet it. Flight first: among the many edges
  // of a satellite the wide scanlines may catch a neighbour the flight tracker would not.
  // The candidate's own frame was rival-free (search): a confirming fit whose depth-mirrored rival fits as
  // well continues it as a track continues through such frames (track_branch.hpp), and the motion
  // tolerance below still holds it to the candidate. A flat target seen nearly face-on flags every other
  // frame so (campaign octagon/167: re-found 2 frames after a 7.8 deg slew, then refused on the next,
  // never found again; 13 -> 106 of 157 tracked).
  const Pose start = m_candidate_moving ? m_candidate.boxPlus(m_candidate_motion) : m_candidate;
  NearRangeResult r;
  const bool continuity = m_params.reacquire_confirm_through_ambiguity;
  m_flight.track(image, start, frame_number, r);
  bool good = imageEvidenceGood(r, m_params, continuity);
  if (!good) good = refitFrom(image, start, frame_number, continuity, r);
  // The first confirmation has no measured motion: a target crossing the image faster than the capture
  // range left the candidate behind (campaign cao/5, 15-18 px a frame). Its outline's best match near it
  // says where it went; the judgement below is unchanged (motion tolerance from the candidate itself).
  Pose cue_start;
  if (!good && m_params.reacquire_confirm_at_cue && cueNear(image, start, cue_start)) {
    ++out.cue_starts;
    good = refitFrom(image, cue_start, frame_number, continuity, r);
  }
  const bool consistent = good && tolerance(r).holds(r.pose, start) && consistentWithPrediction(r.pose);
  if (!good || !consistent) {
    m_confirming = false;  // back to searching on the next frame
    return;
  }
  out.has_previous = true;
  out.previous_pose = m_candidate;
  out.previous_covariance = m_candidate_covariance;
  m_candidate_motion = m_candidate.boxMinus(r.pose);
  m_candidate_moving = true;
  m_candidate = r.pose;
  m_candidate_covariance = r.covariance;
  out.candidate = true;
  if (++m_confirmed < m_params.reacquire_confirm_frames) return;
  out.found = true;
  out.status = r.status;
  out.pose = r.pose;
  out.covariance = r.covariance;
  out.quality = r.quality;
  m_active = false;
}

bool LocalReacquisition::refitFrom(const MonoImage& image, const Pose& start, std::uint64_t frame_number,
                                   bool continuity, NearRangeResult& r) {
  // The wide tracker pulls the pose in, the flight tracker judges it as the hand-over will meet it.
  NearRangeResult wide;
  if (!trackFrom(m_wide, image, start, frame_number, kPassesPerStart, wide, continuity)) return false;
  m_flight.track(image, wide.pose, frame_number, r);
  return imageEvidenceGood(r, m_params, continuity);
}

bool LocalReacquisition::cueNear(const MonoImage& image, const Pose& around, Pose& cue_start) {
  // Over the largest motion a confirmation accepts (reacquire_max_motion_rel of the range, f x it in px).
  // The search's own cue of this frame (bestCueOffset, read by the acquisition) is left as it was.
  const bool best_found = m_best_cue_found;
  const Vec2 best_offset_px = m_best_cue_offset_px;
  const double radius_px = m_camera.intrinsics().fx_px * m_params.reacquire_max_motion_rel;
  const int cues = findCues(image, around, radius_px, 2);
  m_best_cue_found = best_found;
  m_best_cue_offset_px = best_offset_px;
  if (cues <= 0) return false;
  cue_start = movedAcrossImage(around, m_cue_peaks[0].shift);
  return true;
}

void LocalReacquisition::step(const MonoImage& image, const Pose& predicted, std::uint64_t frame_number,
                              ReacquisitionStep& out) {
  out = ReacquisitionStep{};
  m_best_cue_found = false;
  if (!m_active) return;
  m_predicted = predicted;
  if (m_confirming) {
    confirm(image, frame_number, out);
  } else {
    search(image, predicted, frame_number, out);
  }
  ++m_frames;
}

}  // namespace visnav::nav
