// Acquisition, confirmation (see acquisition.hpp): the candidate under confirmation, its rival (the next
// distinct verified pose or a near-symmetric twin of it, whichever scores higher) and the per-frame checks
// both must pass. Never a coin toss: a rival that keeps up means failure `ambiguous`.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "visnav/acquisition/acquisition.hpp"

namespace visnav::acq {

bool Acquisition::looksContinuous(const Pose& pose) const {
  return m_has_look_reference && m_symmetries.lookDistanceRad(m_look_reference, pose) <= m_look_tolerance_rad;
}

bool Acquisition::unresolvedNearTwin(Pose& pose) {
  // The tracker may lose the true twin of a wrong candidate (box/187 at 26 m: from the truth its fit lacked
  // corners and was not accepted), so a twin too close to resolve must block without being tracked, unless
  // a track lost a few frames ago tells the two apart: its look keeps one and not the other (a quarter-turn
  // twin is 90 deg away; campaign box/44, 1.2 px apart at 14 m, was never reacquired). The image cannot
  // choose between them, so the one continuous with the track is taken, whichever was found.
  m_twin_by_continuity = false;
  const double depth_m = pose.t_c_m.z();
  if (!(m_params.near_twin_min_separation_px > 0.0) || !(depth_m > 0.0)) return false;
  const double px_per_m = m_camera.intrinsics().fx_px / depth_m;
  for (int pass = 0; pass < 2; ++pass) {  // a second pass only after swapping to the continuous twin
    const bool candidate_continuous = looksContinuous(pose);
    bool swapped = false;
    for (int i = 0; i < m_symmetries.nearCount() && !swapped; ++i) {
      if (!(m_symmetries.nearSeparationM(i) * px_per_m < m_params.near_twin_min_separation_px)) continue;
      const Pose twin = m_symmetries.nearTwin(pose, i);
      const bool twin_continuous = looksContinuous(twin);
      if (candidate_continuous && !twin_continuous) {
        m_twin_by_continuity = true;
      } else if (pass == 0 && !candidate_continuous && twin_continuous) {
        pose = twin;
        m_twin_by_continuity = true;
        swapped = true;
      } else {
        return true;
      }
    }
    if (!swapped) return false;
  }
  return true;
}

void Acquisition::chooseRival() {
  // The best verified pose that is not a symmetric twin of the current one, or the current one's near twin
  // when it scores higher, is a rival when it scores within rival_margin: both are tracked through
  // confirmation, so an equally good alternative is never silently dropped.
  m_rival_alive = false;
  const Verified& best = m_verified[static_cast<std::size_t>(m_current)];
  // Distinct means beyond what the tracker can resolve (PoseTolerance::widened).
  const PoseTolerance same =
      PoseTolerance::widened(m_params.confirm_max_motion_rel * best.pose.t_c_m.z(),
                             m_params.confirm_max_rotation_deg * kRadPerDeg, best.covariance);
  // With a look reference (setLookReference: a track lost a few frames ago) that keeps the candidate, a pose
  // whose look it refuses is no rival: the pipeline would refuse that find anyway, and where the image
  // cannot choose (an unresolvable near twin, found as a candidate of its own) continuity does.
  const bool best_continuous = looksContinuous(best.pose);
  const Verified* rival = nullptr;
  for (std::size_t i = static_cast<std::size_t>(m_current) + 1; i < m_verified.size(); ++i) {
    if (m_symmetries.equivalent(m_verified[i].pose, best.pose, same)) continue;
    if (best_continuous && !looksContinuous(m_verified[i].pose)) continue;
    rival = &m_verified[i];
    break;  // sorted best first: later ones score lower still
  }
  const bool twin_refused = best_continuous && !looksContinuous(m_near_twin.pose);
  if (m_has_near_twin && !twin_refused && (rival == nullptr || m_near_twin.score > rival->score) &&
      !m_symmetries.equivalent(m_near_twin.pose, best.pose, same))
    rival = &m_near_twin;
  // The depth-reversed twin competes on its own, beside the rival above: each has to fall behind.
  if (m_mirror >= 0) m_mirror_pose = m_symmetries.mirrorTwin(best.pose, m_mirror);
  m_mirror_alive = m_mirror >= 0 && m_mirror_score >= best.score - m_params.rival_margin &&
                   !(best_continuous && !looksContinuous(m_mirror_pose));
  if (rival != nullptr && rival->score >= best.score - m_params.rival_margin) {
    m_rival_alive = true;
    m_rival.restart(rival->pose, rival->covariance);
    m_rival_confirmer.reset();
  }
}

void Acquisition::challengeByMirrorTwin(const MonoImage& image, std::uint64_t frame_number,
                                        const Verified& candidate, AcquisitionResult& out) {
  // Scored by its agreement as it stands, less the residual of its refit: at weak perspective the tracker
  // slides the twin along the line of sight (campaign box/120 at 62 m: the truth, 3.4 deg from the wrong
  // candidate's twin, refitted 13.7 m off in range with 0.09 px rms against the candidate's 0.18, and its
  // agreement there fell from 0.91 to 0.60), so the refit's agreement would put the truth behind. A twin
  // the tracker pulls back onto the candidate is no rival (the image chose); mirrorTwinScore says the rest.
  m_mirror = -1;
  if (!m_params.mirror_twin_checks) return;
  for (int i = 0; i < m_symmetries.mirrorCount(); ++i) {
    double score = 0.0;
    if (!mirrorTwinScore(m_verifier, image, frame_number, candidate,
                         m_symmetries.mirrorTwin(candidate.pose, i), score, out))
      continue;
    if (m_mirror < 0 || score > m_mirror_score) {
      m_mirror = i;
      m_mirror_score = score;
    }
  }
}

bool Acquisition::mirrorTwinScore(NearRangeTracker& tracker, const MonoImage& image,
                                  std::uint64_t frame_number, const Verified& candidate, const Pose& twin,
                                  double& score, AcquisitionResult& out) {
  const PoseTolerance same =
      PoseTolerance::widened(m_params.confirm_max_motion_rel * candidate.pose.t_c_m.z(),
                             m_params.confirm_max_rotation_deg * kRadPerDeg, candidate.covariance);
  if (m_symmetries.equivalent(twin, candidate.pose, same)) return false;  // a face-on plate's twin is itself
  Pose refit = twin;
  NearRangeResult r;
  if (!trackCandidate(tracker, image, frame_number, m_params.tracker_iterations, refit, r, out)) {
    // A twin that shows no face is none; one the tracker merely lost is not refuted by that (test
    // MirrorTwinAcquisitionTest, box/120's box at 65 m: the truth, within 1.7 deg of the wrong candidate's
    // twin, lost by the verifier): it stands as it is, with the candidate's residual.
    if ((r.flags & kFlagNoSurface) != 0U) return false;
    score = agreementF1(twin) - m_params.rms_weight * candidate.rms_px;
    ++out.score_evaluations;
    return true;
  }
  if (m_symmetries.equivalent(r.pose, candidate.pose, same)) return false;  // the image chose the candidate
  score = agreementF1(twin) - m_params.rms_weight * r.rms_px;
  out.score_evaluations += 2;
  return true;
}

double Acquisition::agreementF1(const Pose& pose) {
  // Two-way edge agreement on this frame's window, within the fine spread (plus half a pixel of rounding).
  return m_scorer.agreement(pose, m_window, m_params.fine_spread_px + 0.5).f1;
}

double Acquisition::evidenceScore(const NearRangeResult& r) {
  // How verified candidates are ranked: agreement at the tracked pose less a residual term (see verify()).
  return agreementF1(r.pose) - m_params.rms_weight * r.rms_px;
}

bool Acquisition::bestNearTwin(const MonoImage& image, std::uint64_t frame_number, const Pose& pose,
                               Verified& twin, AcquisitionResult& out) {
  // The near twins that agree best with the window before tracking (one agreement evaluation each; ties go
  // to the lower index), then the tracker on those: the best one it accepts.
  std::array<std::pair<double, int>, ModelSymmetries::kCapacity> prior{};
  const int count = m_symmetries.nearCount();
  for (int i = 0; i < count; ++i)
    prior[static_cast<std::size_t>(i)] = {agreementF1(m_symmetries.nearTwin(pose, i)), i};
  out.score_evaluations += count;
  const int kept = std::min(m_params.near_twin_checks, count);
  std::partial_sort(prior.begin(), prior.begin() + kept, prior.begin() + count,
                    [](const std::pair<double, int>& a, const std::pair<double, int>& b) {
                      return a.first > b.first || (a.first == b.first && a.second < b.second);
                    });
  bool found = false;
  for (int k = 0; k < kept; ++k) {
    Pose candidate = m_symmetries.nearTwin(pose, prior[static_cast<std::size_t>(k)].second);
    NearRangeResult r;
    if (!trackCandidate(m_verifier, image, frame_number, m_params.tracker_iterations, candidate, r, out))
      continue;
    const double score = evidenceScore(r);
    ++out.score_evaluations;
    if (!found || score > twin.score) twin = Verified{score, r.rms_px, r.quality, r.pose, r.covariance};
    found = true;
  }
  return found;
}

void Acquisition::challengeByNearTwin(const MonoImage& image, std::uint64_t frame_number,
                                      AcquisitionResult& out) {
  // The current candidate's best near twin, for chooseRival(). It may block the candidate, never replace it:
  // a twin that scored higher was confirmed 75 deg off in campaign box/49 where the candidate was right.
  m_has_near_twin = false;
  challengeByMirrorTwin(image, frame_number, m_verified[static_cast<std::size_t>(m_current)], out);
  if (m_symmetries.nearCount() == 0 || m_params.near_twin_checks == 0) return;
  m_has_near_twin = bestNearTwin(image, frame_number, m_verified[static_cast<std::size_t>(m_current)].pose,
                                 m_near_twin, out);
}

bool Acquisition::shiftedStart(const Pose& pose, Pose& start) {
  // The candidate's outline slid over this frame's coarse evidence, no further than a target moves in a
  // frame (confirm_max_motion_rel of the depth, confirmStep's own limit), then to the fine evidence.
  const double scale = static_cast<double>(m_window.scale());
  const double max_shift_px = m_params.confirm_max_motion_rel * m_camera.intrinsics().fx_px / scale;
  const double step_px = static_cast<double>(std::max(1, m_params.coarse_spread_px));
  ShiftPeak best;
  if (m_scorer.bestShifts(pose, m_window, max_shift_px, step_px, step_px, &best, 1) < 1) return false;
  start = m_scorer.shifted(pose, m_window, best.shift);
  return true;
}

void Acquisition::followTo(Followed& followed, const NearRangeResult& fit) const {
  // Only the motion across the line of sight: the last position taken to this fit's range (the depth
  // difference of two single fits is their noise, a far target's few per cent). It is motion where the
  // two fits agree in range within what a target moves in a frame (confirm_max_motion_rel: far out a fit
  // that jumped 29 -> 24 m also moved its origin's bearing, cao/27) and where it is significant against
  // the two fits' position covariance (a still target's step is their noise; chi-square 3 dof, 99 %).
  constexpr double kStepChi2 = 11.34;
  const double last_range_m = followed.pose.t_c_m.norm();
  const double range_m = fit.pose.t_c_m.norm();
  const Mat3 position_covariance = fit.covariance.bottomRightCorner<3, 3>();
  followed.moving = false;
  followed.step_m.setZero();
  if (last_range_m > 0.0 &&
      std::abs(range_m - last_range_m) <= m_params.confirm_max_motion_rel * followed.pose.t_c_m.z()) {
    followed.step_m = fit.pose.t_c_m - followed.pose.t_c_m * (range_m / last_range_m);
    const Eigen::LDLT<Mat3> factor(followed.position_covariance + position_covariance);
    followed.moving = factor.info() == Eigen::Success && factor.isPositive() &&
                      followed.step_m.dot(factor.solve(followed.step_m)) > kStepChi2;
  }
  followed.position_covariance = position_covariance;
  followed.pose = fit.pose;
}

bool Acquisition::confirmStep(NearRangeTracker& tracker, const MonoImage& image, std::uint64_t frame_number,
                              Followed& followed, NearRangeResult& r, double& agreement) {
  // One confirmation frame: the pose keeps tracking with the flight settings, moves as a rigid target can
  // between two frames, and keeps explaining the window's edges both ways. With confirm_follows_motion a
  // pose that moves is predicted by its step over the frame before, as the filter predicts a track, and the
  // motion test asks how far it left that prediction; a pose lost from its start is tracked again from
  // where its outline went on this frame (shiftedStart): a target crossing the image faster than the
  // scanlines reach was lost on every confirmation frame (campaign cao/1, 19 px a frame).
  const bool follow = m_params.confirm_follows_motion;
  Pose start = followed.pose;
  if (follow && followed.moving) start.t_c_m += followed.step_m;
  tracker.track(image, start, frame_number, r);
  bool tracked = acceptable(r);
  if (!tracked && follow) {
    Pose shifted;
    if (shiftedStart(start, shifted)) {
      tracker.reset();
      tracker.track(image, shifted, frame_number, r);
      tracked = acceptable(r);
    }
  }
  if (!tracked) return false;
  // What a target can move in one frame, plus what the tracker cannot resolve: the first flight-tracker pass
  // moves a far plate's weakly observed tilt by more than a target can turn.
  const bool consistent = PoseTolerance::widened(m_params.confirm_max_motion_rel * start.t_c_m.z(),
                                                 m_params.confirm_max_rotation_deg * kRadPerDeg, r.covariance)
                              .holds(r.pose, start);
  agreement = agreementF1(r.pose);
  followTo(followed, r);
  return consistent && agreement >= m_params.min_confirm_agreement;
}

bool Acquisition::nextCandidate(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out) {
  // Lost on the way: the next verified candidate, re-checked on this frame.
  NearRangeResult r;
  for (++m_current; m_current < static_cast<int>(m_verified.size()); ++m_current) {
    Verified& current = m_verified[static_cast<std::size_t>(m_current)];
    Pose pose = current.pose;
    if (!trackCandidate(m_verifier, image, frame_number, m_params.tracker_iterations, pose, r, out)) continue;
    if (unresolvedNearTwin(r.pose)) continue;  // what verify() refuses for the first candidate
    // Re-scored on this frame, like its near twin is.
    current = Verified{evidenceScore(r), r.rms_px, r.quality, r.pose, r.covariance};
    ++out.score_evaluations;
    challengeByNearTwin(image, frame_number, out);
    m_followed.restart(current.pose, current.covariance);
    m_previous_pose = current.pose;
    m_previous_covariance = current.covariance;
    m_confirmed = 0;
    m_confirm_frames_run = 0;
    m_confirmer.reset();
    chooseRival();
    return true;
  }
  return false;
}

void Acquisition::confirm(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out) {
  prepareWindow(image);  // the agreement is judged on this frame's edges
  ++m_confirm_frames_run;
  NearRangeResult r;
  double agreement = 0.0;
  ++out.tracker_calls;
  const Pose before = m_followed.pose;
  if (!confirmStep(m_confirmer, image, frame_number, m_followed, r, agreement)) {
    if (!nextCandidate(image, frame_number, out)) fail(AcquisitionFailure::kNotConfirmed);
    return;
  }
  if (m_confirmed > 0) {  // else the verification's, set with the candidate
    m_previous_pose = before;
    m_previous_covariance = m_last.covariance;
  }
  m_last = r;
  ++m_confirmed;
  const double score = agreement - m_params.rms_weight * r.rms_px;
  if (m_mirror_alive) {
    // Re-made from this frame's pose and judged as at verification (mirrorTwinScore): it keeps up while
    // the tracker holds it apart from the pose and the window's edges cannot tell the two apart.
    double mirror_score = 0.0;
    const Verified current{score, r.rms_px, r.quality, r.pose, r.covariance};
    m_mirror_pose = m_symmetries.mirrorTwin(m_followed.pose, m_mirror);
    m_mirror_alive =
        mirrorTwinScore(m_verifier, image, frame_number, current, m_mirror_pose, mirror_score, out) &&
        mirror_score >= score - m_params.rival_margin;
  }
  if (m_rival_alive) {
    NearRangeResult rival;
    double rival_agreement = 0.0;
    ++out.tracker_calls;
    const bool rival_tracks =
        confirmStep(m_rival_confirmer, image, frame_number, m_rival, rival, rival_agreement);
    const double rival_score = rival_agreement - m_params.rms_weight * rival.rms_px;
    m_rival_alive = rival_tracks && rival_score >= score - m_params.rival_margin;
  }
  if (m_confirmed < m_params.confirm_frames) return;
  if (!m_rival_alive && !m_mirror_alive) {
    m_state = AcquisitionState::kSucceeded;
  } else if (m_confirm_frames_run >= m_params.max_confirm_frames) {
    fail(AcquisitionFailure::kAmbiguous);  // never a coin toss between two poses: status lost, retry later
  }
}

}  // namespace visnav::acq
