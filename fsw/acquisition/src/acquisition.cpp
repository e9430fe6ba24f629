#include "visnav/acquisition/acquisition.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace visnav::acq {

const char* toString(AcquisitionState state) {
  switch (state) {
    case AcquisitionState::kIdle: return "idle";
    case AcquisitionState::kSearching: return "searching";
    case AcquisitionState::kVerifying: return "verifying";
    case AcquisitionState::kConfirming: return "confirming";
    case AcquisitionState::kSucceeded: return "succeeded";
    case AcquisitionState::kFailed: return "failed";
  }
  return "unknown";
}

const char* toString(AcquisitionFailure failure) {
  switch (failure) {
    case AcquisitionFailure::kNone: return "none";
    case AcquisitionFailure::kInvalidCue: return "invalid_cue";
    case AcquisitionFailure::kNoTarget: return "no_target";
    case AcquisitionFailure::kNoCandidate: return "no_candidate";
    case AcquisitionFailure::kNotConfirmed: return "not_confirmed";
    case AcquisitionFailure::kAmbiguous: return "ambiguous";
  }
  return "unknown";
}

LoadError Acquisition::init(const PinholeCamera& camera, const PolygonModel& model,
                            const AcquisitionParams& params, const NearRangeParams& nearrange) {
  if (const char* problem = params.crossCheck())
    return LoadError::failure(std::string("acquisition: ") + problem);
  m_camera = camera;
  m_params = params;
  m_bounding_radius_m = model.boundingRadius();
  LoadError e =
      m_grid.init(model, params.view_directions, params.roll_steps, params.max_obliquity_deg * kRadPerDeg);
  if (e.ok)
    e = m_window.init(params.max_working_side_px, params.max_strong_pixels,
                      2 * std::max(camera.width(), camera.height()));
  if (e.ok) e = m_scorer.init(camera, model, {params.samples_per_hypothesis, params.internal_edge_weight});
  NearRangeParams wide = nearrange;
  if (params.verify_scanline_half_length_px > 0)
    wide.scanline_half_length_px = params.verify_scanline_half_length_px;
  if (e.ok) e = m_verifier.init(camera, model, wide);
  if (e.ok) e = m_confirmer.init(camera, model, nearrange);
  if (e.ok) e = m_rival_confirmer.init(camera, model, nearrange);
  if (!e.ok) return e;
  m_symmetries.find(model);
  m_symmetries.findNear(model, params.near_twin_max_rel);
  m_symmetries.findMirrors(model);
  m_candidates.reserve(static_cast<std::size_t>(params.search_candidates));
  m_refined.reserve(static_cast<std::size_t>(params.candidates));
  m_verify_passes.reserve(static_cast<std::size_t>(params.candidates));
  m_verified.reserve(static_cast<std::size_t>(params.candidates));
  reset();
  return LoadError::success();
}

void Acquisition::reset() {
  m_state = AcquisitionState::kIdle;
  m_failure = AcquisitionFailure::kNone;
  m_candidates.clear();
  m_refined.clear();
  m_verify_passes.clear();
  m_verified.clear();
  m_next_hypothesis = 0;
  m_frames = 0;
  m_best_score = 0.0;
  m_has_near_twin = false;
  m_mirror = -1;
  m_mirror_alive = false;
  m_has_look_reference = false;
  m_twin_by_continuity = false;
  m_min_edge_snr = m_params.min_edge_snr;
  m_target_radius_working_px = 0.0;
}

void Acquisition::setLookReference(const Pose& reference, double tolerance_rad) {
  m_has_look_reference = reference.t_c_m.allFinite() && reference.R_c_m.allFinite() && tolerance_rad >= 0.0;
  m_look_reference = reference;
  m_look_tolerance_rad = tolerance_rad;
}

void Acquisition::fail(AcquisitionFailure failure) {
  m_state = AcquisitionState::kFailed;
  m_failure = failure;
}

void Acquisition::start(const FarRangeSolution& cue) {
  if (!cue.valid) {
    reset();
    fail(AcquisitionFailure::kInvalidCue);
    return;
  }
  start(cue.direction_c, cue.distance_m);
  if (cue.outline) m_min_edge_snr = m_params.outline_cue_min_edge_snr;
  // Far range's cue is judged at the working scale alone by default (far_cue_edge_snr_radius_px 0):
  // box-averaged, a limb's soft edge passes too (campaign plate/6, smallsat/10), and a dim cue passed early
  // fails unconfirmed and delays the retry (stop 85: box/73 41 -> 11 tracked frames).
  m_window.setCoarseSnrFactor(coarseSnrFactor(m_params.far_cue_edge_snr_radius_px));
}

int Acquisition::coarseSnrFactor(int edge_snr_radius_px) const {
  return edge_snr_radius_px > 0
             ? static_cast<int>(std::min(m_target_radius_working_px / edge_snr_radius_px, 16.0))
             : 1;
}

void Acquisition::start(const Vec3& direction_c, double distance_m) {
  start(direction_c, distance_m, m_params.direction_margin_deg);
}

void Acquisition::start(const Vec3& direction_c, double distance_m, double direction_margin_deg) {
  reset();
  const double norm = direction_c.norm();
  Vec2 centre_px;
  if (!direction_c.allFinite() || !(norm > 0.0) || !(direction_c.z() / norm > 0.05) ||
      !(direction_margin_deg >= 0.0 && direction_margin_deg < 80.0) || !std::isfinite(distance_m) ||
      !(distance_m > 0.0) || !m_camera.project(direction_c / norm, centre_px)) {
    fail(AcquisitionFailure::kInvalidCue);
    return;
  }
  m_cue_direction = direction_c / norm;
  m_cue_distance_m = distance_m;
  // Window: the target at the nearest distance covered, plus the direction error covered.
  const CameraIntrinsics& k = m_camera.intrinsics();
  const double range = distance_m / m_cue_direction.z();
  const double nearest = range / (1.0 + m_params.range_span_rel);
  const double half_px = m_params.window_margin * k.fx_px * m_bounding_radius_m / nearest +
                         k.fx_px * std::tan(direction_margin_deg * kRadPerDeg);
  const double expected_radius_px = k.fx_px * m_bounding_radius_m / range;
  // A cue a few metres off a large target asks for more than the image holds: capped before the factor's
  // conversion to int (the window caps the rest, WorkingImage::setWindow).
  const double max_px = 2.0 * std::max(m_camera.width(), m_camera.height());
  const int scale =
      std::max(1, static_cast<int>(std::min(expected_radius_px, max_px) / m_params.working_radius_px + 0.5));
  const int used = m_window.setWindow(centre_px, std::min(half_px, max_px), scale);
  m_target_radius_working_px = std::min(expected_radius_px, max_px) / used;
  m_window.setCoarseSnrFactor(coarseSnrFactor(m_params.edge_snr_radius_px));
  m_state = AcquisitionState::kSearching;
}

bool Acquisition::cueLacksEdges(const FarRangeSolution& cue, const MonoImage& image, double& edge_snr) {
  edge_snr = 0.0;
  if (image.empty() || image.width() != m_camera.width() || image.height() != m_camera.height()) return false;
  start(cue);
  const bool searching = m_state == AcquisitionState::kSearching;
  if (searching) {
    prepareWindow(image);
    edge_snr = m_window.stats().detectionSnr();
  }
  const bool lacks = searching && edge_snr < m_min_edge_snr;  // what step() fails kNoTarget on
  reset();
  return lacks;
}

void Acquisition::prepareWindow(const MonoImage& image) {
  m_window.prepare(image, m_params.fine_spread_px, m_params.coarse_spread_px, m_params.evidence_cap);
}

void Acquisition::offer(BoundedBuffer<Candidate>& list, const Candidate& c, double min_angle_rad,
                        const ModelSymmetries* symmetries) {
  // Distinct attitudes only: one peak of the score fills one slot, not all of them. With `symmetries`, a
  // symmetric twin of a listed attitude is that attitude (a box's half turns would fill four slots).
  const double min_cos = std::cos(min_angle_rad);
  std::size_t slot = list.size();
  for (std::size_t i = 0; i < list.size(); ++i) {
    // cos of the angle between the two attitudes: (trace(R_a^T R_b S) - 1) / 2, the closest twin S.
    const Mat3 relative = list[i].attitude.transpose() * c.attitude;
    double trace = relative.trace();
    for (int k = 1; symmetries != nullptr && k < symmetries->size(); ++k)
      trace = std::max(trace, (relative * (*symmetries)[k]).trace());
    if (0.5 * (trace - 1.0) > min_cos) {
      if (c.score <= list[i].score) return;
      slot = i;
      break;
    }
  }
  if (slot == list.size()) {
    if (!list.full()) {
      list.push(c);
    } else if (c.score > list[slot - 1].score) {
      slot = slot - 1;
      list[slot] = c;
    } else {
      return;
    }
  } else {
    list[slot] = c;
  }
  sortBestFirst(list, slot);
}

template <typename T>
void Acquisition::sortBestFirst(BoundedBuffer<T>& list, std::size_t from) {
  // One insertion step keeps the list best first (its length is bounded by the parameters).
  for (std::size_t i = from; i > 0 && list[i].score > list[i - 1].score; --i) std::swap(list[i], list[i - 1]);
}

void Acquisition::search(AcquisitionResult& out) {
  const GradientStats& stats = m_window.stats();
  // Hypotheses look along the line of sight through the window's edge centroid (the cue when none).
  Vec3 los = m_cue_direction;
  Vec2 cue_px;
  m_camera.project(m_cue_direction, cue_px);
  Vec2 centre = m_window.toWorking(cue_px);
  if (stats.has_strong) {
    centre = stats.strong_centroid_w;
    los = m_camera.bearing(m_window.toFull(centre));
  }
  const Mat3 R_cl = rotationZTo(los);
  const double range = m_cue_distance_m / m_cue_direction.z();
  const int steps = m_params.range_steps;
  const int total = hypothesisCount();
  int attitude_cached = -1;
  Mat3 R_lm = Mat3::Identity();
  for (int n = 0; n < m_params.hypotheses_per_cycle && m_next_hypothesis < total; ++n) {
    const int index = m_next_hypothesis++;
    const int attitude = index / steps;
    const int step = index % steps;
    if (attitude != attitude_cached) {
      R_lm = m_grid.rotation(attitude);
      attitude_cached = attitude;
    }
    const double exponent = steps > 1 ? 2.0 * step / (steps - 1) - 1.0 : 0.0;
    Candidate c;
    c.attitude = R_lm;
    c.pose.R_c_m = R_cl * R_lm;
    c.pose.t_c_m = los * (range * std::pow(1.0 + m_params.range_span_rel, exponent));
    // Centred on the window's edge centroid, then the best of a few shifts one coarse spread apart: the
    // centroid of the strong edges is biased where some of the target's edges have little contrast.
    Vec2 shift = Vec2::Zero();
    c.score = m_scorer.scoreAligned(c.pose, m_window, Evidence::kCoarse, centre, m_params.shift_steps,
                                    std::max(1, m_params.coarse_spread_px), shift);
    ++out.hypotheses_scored;
    if (!(c.score > 0.0)) continue;
    c.pose = m_scorer.shifted(c.pose, m_window, shift);
    m_best_score = std::max(m_best_score, c.score);
    offer(m_candidates, c, 1.5 * m_grid.spacingRad());
  }
  out.score_evaluations += out.hypotheses_scored;
  if (m_next_hypothesis >= total) m_state = AcquisitionState::kVerifying;
}

bool Acquisition::acceptable(const NearRangeResult& r) const {
  const bool status_ok =
      r.status == TrackStatus::kTracking || (m_params.accept_degraded && r.status == TrackStatus::kDegraded);
  return status_ok && r.rms_px <= m_params.max_rms_px && r.quality >= m_params.min_quality;
}

bool Acquisition::trackCandidate(NearRangeTracker& tracker, const MonoImage& image,
                                 std::uint64_t frame_number, int passes, Pose& pose, NearRangeResult& result,
                                 AcquisitionResult& out) const {
  tracker.reset();
  for (int pass = 0; pass < passes; ++pass) {
    tracker.track(image, pose, frame_number, result);
    ++out.tracker_calls;
    if (result.status == TrackStatus::kLost) return false;
    const double moved = pose.boxMinus(result.pose).norm();
    pose = result.pose;
    if (moved < 1e-6 && acceptable(result)) break;  // converged: further passes change nothing
  }
  return acceptable(result);
}

void Acquisition::verify(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out) {
  RefineSettings refine;
  refine.levels = m_params.refine_levels;
  refine.rotation_step_rad = 0.5 * m_grid.spacingRad();
  refine.lateral_step_working_px = 0.5 * m_params.coarse_spread_px;
  refine.range_step_rel =
      0.5 * (std::pow(1.0 + m_params.range_span_rel, 2.0 / std::max(1, m_params.range_steps - 1)) - 1.0);
  // Refine every survivor on this frame; the distinct results that best agree with the window both ways
  // (the refinement's mean evidence alone favours poses showing only the strongest edges) go to the tracker.
  m_refined.clear();
  for (const Candidate& c : m_candidates) {
    Candidate r = c;
    if (!(m_scorer.refine(m_window, refine, r.pose, out.score_evaluations) > 0.0)) continue;
    r.score = agreementF1(r.pose);
    r.attitude = r.pose.R_c_m;
    offer(m_refined, r, 2.0 * kRadPerDeg, &m_symmetries);
  }
  m_verified.clear();
  m_verify_passes.clear();
  for (const Candidate& c : m_refined) {
    Pose pose = c.pose;
    NearRangeResult r;
    const bool accepted =
        trackCandidate(m_verifier, image, frame_number, m_params.tracker_iterations, pose, r, out);
    m_verify_passes.push({r.status, r.rms_px, r.quality, r.pose});
    if (!accepted) continue;
    // Rank by the two-way agreement at the tracked pose (the tracker's residual only covers the lines it
    // kept, and a wrong pose can fit those well), less a residual term: depth-reversed ("Necker") poses
    // explain the same edges, only perspective tells them apart, and that shows in the full-resolution fit.
    Verified v{evidenceScore(r), r.rms_px, r.quality, r.pose, r.covariance};
    ++out.score_evaluations;
    m_verified.push(v);
    sortBestFirst(m_verified, m_verified.size() - 1);
  }
  if (m_verified.empty()) return fail(AcquisitionFailure::kNoCandidate);
  if (unresolvedNearTwin(m_verified[0].pose)) return fail(AcquisitionFailure::kAmbiguous);
  m_current = 0;
  challengeByNearTwin(image, frame_number, out);
  m_followed.restart(m_verified[0].pose, m_verified[0].covariance);
  m_previous_pose = m_verified[0].pose;
  m_previous_covariance = m_verified[0].covariance;
  m_confirmer.reset();
  m_confirmed = 0;
  m_confirm_frames_run = 0;
  chooseRival();
  if (m_params.confirm_frames == 0 && !m_rival_alive && !m_mirror_alive) {
    m_last.pose = m_verified[0].pose;
    m_last.covariance = m_verified[0].covariance;
    m_last.quality = m_verified[0].quality;
    m_last.rms_px = m_verified[0].rms_px;
    m_last.flags = 0U;
    m_state = AcquisitionState::kSucceeded;
    return;
  }
  m_state = AcquisitionState::kConfirming;
}

Status Acquisition::step(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out) {
  out = AcquisitionResult{};
  Status status = Status::kOk;
  const bool active = m_state == AcquisitionState::kSearching || m_state == AcquisitionState::kVerifying ||
                      m_state == AcquisitionState::kConfirming;
  if (image.empty() || image.width() != m_camera.width() || image.height() != m_camera.height()) {
    status = Status::kInvalidArgument;
  } else if (active) {
    ++m_frames;
    if (m_state != AcquisitionState::kConfirming) {
      prepareWindow(image);
      out.edge_snr = m_window.stats().detectionSnr();
      if (out.edge_snr < m_min_edge_snr) fail(AcquisitionFailure::kNoTarget);
    }
    switch (m_state) {
      case AcquisitionState::kSearching: search(out); break;
      case AcquisitionState::kVerifying: verify(image, frame_number, out); break;
      case AcquisitionState::kConfirming: confirm(image, frame_number, out); break;
      default: break;
    }
  }
  out.state = m_state;
  out.failure = m_failure;
  out.frames = m_frames;
  out.hypotheses_done = m_next_hypothesis;
  out.hypotheses_total = hypothesisCount();
  out.candidates_verified = static_cast<int>(m_verified.size());
  out.twin_resolved_by_continuity = m_twin_by_continuity;
  out.best_score = m_best_score;
  out.pose = m_followed.pose;
  if (m_state == AcquisitionState::kSucceeded) {
    out.pose = m_last.pose;
    out.covariance = m_last.covariance;
    out.quality = m_last.quality;
    out.rms_px = m_last.rms_px;
    out.tracker_flags = m_last.flags;
    // Only a step that is motion (followTo): two fits of a still target differ by their noise, and a
    // filter started from that difference was more certain of a motion it did not have (campaign box/44:
    // the next fit rejected at NIS 29.5, the branch confirmed 4 frames later).
    out.has_previous = m_params.confirm_follows_motion && m_confirmed > 0 && m_followed.moving;
    out.previous_pose = m_previous_pose;
    out.previous_covariance = m_previous_covariance;
  }
  return status;
}

}  // namespace visnav::acq
