// NavigationPipeline's output gates, which of its poses are valid (fsw/navigation/README.md, "One frame",
// item 4, from "Certain enough to deliver" on): the pose's own certainty and view, a doubted track's tighter
// limit, the track's branch and its continuity across a short break, and the symmetric-twin flag. The rest
// of the class: navigation_pipeline.cpp.
#include <algorithm>
#include <cmath>

#include "visnav/navigation/navigation_pipeline.hpp"

namespace visnav::nav {

namespace {
/// branch_range_after_jump's range tolerance holds the reference's range, carried on, to this many of its
/// 1-sigma: a bound on what the filter knew, not a tuning.
constexpr double kRangeSigmas = 3.0;
/// The run of valid poses is counted up to here (a track of years stays within int).
constexpr int kValidRunCap = 1000000;
}  // namespace

void NavigationPipeline::flagTwins(NavSolution& out) const {
  // The "flag the ambiguity": the track keeps the twin continuous with it (acquisition, reacquisition
  // and the tracker all do), and the user is told how many others the image would have accepted.
  const double depth_m = out.pose.t_c_m.z();
  out.symmetric_twins = m_acquisition.symmetries().indistinguishableTwins(
      depth_m > 0.0 ? m_camera.intrinsics().fx_px / depth_m : 0.0,
      m_params.acquisition.near_twin_min_separation_px);
  out.twin_by_continuity = m_track_twin_by_continuity;
}

bool NavigationPipeline::showsAFace(const Pose& pose) const {
  // An edge-on plate's outline is two pairs of edges a few pixels apart: its fits lock biased with a small
  // covariance (campaign plate/132: 7 frames 1.1-2.8 m off at 17.5 m, 0.7-1.5 deg 1-sigma).
  if (!(m_max_view_cos < 1.0)) return true;  // off
  for (const ModelSurface& s : m_near.model().surfaces()) {
    const Vec3 centre_c = pose.transform(s.centroid_m);
    const double distance = centre_c.norm();
    if (distance > 0.0 && -(pose.R_c_m * s.normal_m).dot(centre_c) > m_max_view_cos * distance) return true;
  }
  return false;
}

void NavigationPipeline::deliver(const Pose& pose, const Mat6& covariance, double quality, NavSolution& out,
                                 bool doubted, double systematic_gain) {
  m_coasted = 0;
  m_last_pose = pose;
  m_have_pose = true;
  m_delivered_newest ^= 1U;  // the older slot becomes the newest: no copy of the other
  // The filter's restart takes the scatter's covariance, as its updates do (fuseNearRange).
  m_delivered[m_delivered_newest] = DeliveredPose{pose, covariance, m_last_exposure_ns};
  // The user's covariance, and the validity below, add the lines' systematic end error
  // ([nearrange] line_end_bias_px): the scatter alone put box/25's fit at 0.8 deg 1-sigma, 6 deg off.
  const Mat6 delivered_covariance = covariance * systematic_gain;
  // The pose is tracked whatever its uncertainty (the next frame is predicted from it), but it is valid
  // output only when its own covariance says it is known to the accuracy a user may rely on: a small target
  // far out has an attitude the image barely constrains, and a pose wrong by degrees then looks as good as
  // a right one (campaign plate/12: 12 deg off from the true start, 3.9 deg 1-sigma).
  const NavigationParams& nav = m_params.navigation;
  // A doubted pose (the filter disputes it, or part of its outline was not found) must be better determined:
  // a fit on the wrong edges has few of them and weak geometry, its covariance knows the noise but not the
  // bias (smallsat/83: 1.5 deg 1-sigma, 12 deg off).
  const PoseSigmas sigma = poseSigmas(pose, delivered_covariance);
  double attitude_limit_deg = nav.max_valid_attitude_sigma_deg;
  if (doubted && nav.doubted_max_attitude_sigma_deg > 0.0)
    attitude_limit_deg = attitude_limit_deg > 0.0
                             ? std::min(attitude_limit_deg, nav.doubted_max_attitude_sigma_deg)
                             : nav.doubted_max_attitude_sigma_deg;
  const bool position_certain =
      nav.max_valid_position_sigma_rel <= 0.0 || sigma.position_rel <= nav.max_valid_position_sigma_rel;
  const bool certain =
      (attitude_limit_deg <= 0.0 || sigma.attitude_deg <= attitude_limit_deg) && position_certain;
  const bool undoubted_certain =
      (nav.max_valid_attitude_sigma_deg <= 0.0 || sigma.attitude_deg <= nav.max_valid_attitude_sigma_deg) &&
      position_certain;
  m_pose_showed_face = showsAFace(pose);
  // A track that began with a reacquisition's find stays doubted until one of its poses meets the doubted
  // limit: a find a few degrees off, withheld on its own frame, is otherwise continued and delivered once the
  // filter has restarted from it (campaign box/25: re-found 17.7 deg off, then 20 frames valid at 17-20 deg
  // with a 1.1-2.3 deg 1-sigma). Replayed on the full run: wrong frames 210 -> 193, tracked mean 0.549 ->
  // 0.547.
  // doubt_clear_frames: the find's doubt ends only after that many such poses in a row, and its poses are
  // withheld until then (campaign box/191: a find 12 deg off met the limit on every other frame).
  bool find_still_doubted = false;
  if (m_track_doubted && nav.doubted_max_attitude_sigma_deg > 0.0) {
    m_doubt_clear_run = sigma.attitude_deg <= nav.doubted_max_attitude_sigma_deg ? m_doubt_clear_run + 1 : 0;
    find_still_doubted = m_doubt_clear_run < std::max(1, nav.doubt_clear_frames);
  } else {
    m_doubt_clear_run = 0;
  }
  if (doubted && nav.doubted_max_attitude_sigma_deg > 0.0 &&
      sigma.attitude_deg <= nav.doubted_max_attitude_sigma_deg && !find_still_doubted)
    m_track_doubted = false;
  out.pose_valid = certain && !find_still_doubted && m_pose_showed_face;
  out.withheld = (undoubted_certain ? 0U : kWithheldUncertain) |
                 (undoubted_certain && !certain ? kWithheldDoubted : 0U) |
                 (find_still_doubted ? kWithheldFindDoubted : 0U) |
                 (m_pose_showed_face ? 0U : kWithheldEdgeOn);
  out.pose = pose;
  out.covariance = delivered_covariance;
  out.quality = quality;
}

void NavigationPipeline::confirmBranch(NavMode processed_in, NavSolution& out) {
  // track_branch.hpp says why. A fit without corners (point-to-line fallback) is not checked against its
  // twin well enough to count as rival-free.
  // A near twin (kFlagNearTwinRival) is no rival where continuity chooses: the look of the last valid pose
  // (or of the operator's start pose, before any) keeps the fit and refuses the twin (a near-cubic box's
  // quarter turn is 90 deg away; without this exception seeds 1-40 lost 37 tracked frames of right poses, and
  // box/67, whose first frames were too uncertain to deliver, 70 frames without the start pose).
  m_near_twin_rival =
      processed_in == NavMode::kNearRange && (m_near_result.flags & kFlagNearTwinRival) != 0U &&
      !(m_frames_since_branch_reference != ~0ULL &&
        m_reacquisition.lookConsistentWith(m_branch_reference_pose, m_frames_since_branch_reference,
                                           m_near_result.pose) &&
        !m_reacquisition.lookConsistentWith(m_branch_reference_pose, m_frames_since_branch_reference,
                                            m_near_result.near_twin_rival));
  // A find off a known branch (findOnKnownBranch) had no near twin refitted: not rival-free either.
  const bool find_off_branch = m_reacquisition_step.found && !m_find_on_known_branch;
  // A depth-mirrored rival is no rival where the track continues its reference and the prediction rejects
  // the mirror while it accepted the fit: the image cannot tell the two apart, the motion can (a plate's
  // other tilt is twice its tilt away). Campaign octagon/11, /15, /20: right fits withheld for it alone.
  m_mirror_resolved = m_mirror_nis > m_filter.params().pose_gate_chi2 && m_last_pose_update.accepted &&
                      m_frames_since_branch_reference != ~0ULL &&
                      m_filter.trackEpoch() == m_reference_track_epoch;
  const std::uint32_t rival_flags = kFlagResidualFallback | (m_mirror_resolved ? 0U : kFlagAmbiguous);
  // A strip's two lines are a large share of a fit on few lines, and their bias is not in its 1-sigma: such
  // a fit confirms nothing unless it is very certain (campaign box/7035: three strip fits of 5 lines at 0.85
  // deg confirmed a branch 5 deg off).
  const NavigationParams& nav = m_params.navigation;
  const bool narrow_unconfirming =
      processed_in == NavMode::kNearRange && (m_near_result.flags & kFlagNarrowFace) != 0U &&
      m_near_result.lines_used <= nav.narrow_confirm_max_lines &&
      poseSigmas(out.pose, out.covariance).attitude_deg > nav.narrow_confirm_max_attitude_sigma_deg;
  const bool rival_free =
      processed_in != NavMode::kNearRange || ((m_near_result.flags & rival_flags) == 0U &&
                                              !m_near_twin_rival && !find_off_branch && !narrow_unconfirming);
  // After a break a strip caused, the run of branch_confirm_frames asks whether the track is biased, and
  // the filter's estimate cannot say: it averages the frames as if their errors were independent, and a
  // biased fit repeats its error (campaign box/25: strip fits withheld, then fits at 1.04-1.24 deg 1-sigma,
  // filtered to 0.72-0.84, confirmed 5.5 deg off). Each fit of that run must be known on its own. A
  // delivered pose that is not filtered is the fit's own.
  if (processed_in == NavMode::kNearRange && out.quality > 0.0)
    m_fit_attitude_sigma_deg =
        (m_pose_filtered
             ? poseSigmas(m_near_result.pose, m_near_result.covariance * m_near_result.systematic_gain)
             : poseSigmas(out.pose, out.covariance))
            .attitude_deg;
  m_followed_narrow_break = m_narrow_break;
  const bool fit_uncertain = nav.narrow_break_max_fit_attitude_sigma_deg > 0.0 && m_narrow_break &&
                             m_fit_attitude_sigma_deg > nav.narrow_break_max_fit_attitude_sigma_deg;
  // An acquisition awaiting near range (runAcquisition) is confirmed by the next frame's valid, rival-free
  // fit, which the filter started from it did not reject as a jump; anything else leaves the branch unknown.
  // Not by an outline-only fit that missed a line (fitConfirmsHandOver).
  const bool awaited = m_acquisition_awaits_near && processed_in == NavMode::kNearRange && rival_free &&
                       fitConfirmsHandOver(m_near_result, m_params.navigation);
  if (processed_in != NavMode::kAcquisition) m_acquisition_awaits_near = false;
  // Evaluated whatever the branch's state, for the campaign's gate replay (lastFitKeptTheBranch).
  // After a jump a fit must also keep the last valid pose's range to count toward the branch, by continuity
  // or by the count (fitLeftTheValidRange).
  m_range_broken = processed_in == NavMode::kNearRange && fitLeftTheValidRange(out.pose);
  m_fit_kept_the_branch = processed_in == NavMode::kNearRange && out.pose_valid && !m_range_broken &&
                          keptTheBranch(out.pose, out.covariance);
  // With doubt_clear_frames > 1 the find's own frame is withheld: its confirmation of the branch (the twin
  // chosen by continuity with the last valid pose) passes to the track's first valid pose after it.
  const bool find_confirms =
      (m_reacquisition_step.found && m_find_on_known_branch) ||
      (m_find_confirms_branch && processed_in == NavMode::kNearRange && out.pose_valid);
  m_find_confirms_branch = m_find_confirms_branch && m_track_doubted && !out.pose_valid;
  const bool confirmed = (processed_in == NavMode::kAcquisition && !m_acquisition_awaits_near) ||
                         find_confirms || awaited || m_fit_kept_the_branch;
  // A confirmation also needs the predicted motion's agreement, as an acquisition's does (campaign box/5001:
  // a track the filter restarted from rejected fits, confirmed 13.6 % off by three frames, the last
  // rejected).
  const bool motion_agrees = !m_params.navigation.branch_confirm_needs_filter ||
                             processed_in != NavMode::kNearRange ||
                             (m_near_range_faults & kFaultInnovation) == 0U;
  const bool passed_the_pose_gates = out.pose_valid;
  out.pose_valid = m_branch.step(out.pose_valid,
                                 rival_free && motion_agrees && !m_range_broken && !fit_uncertain, confirmed);
  if (passed_the_pose_gates && !out.pose_valid) out.withheld |= kWithheldBranchUnknown;
}

void NavigationPipeline::followNearTwin(NavMode processed_in, const MonoImage& image,
                                        const NavSolution& out) {
  // A withheld track on a near twin stays there: the checks withhold it, frame after frame, and nothing
  // moves it (campaign octagon/172: acquired on the quarter turn at 30 m, 6 of 8 lines found, the true
  // pose's fit from the truth 8 of 8). The twin that fits the found lines as well is tracked on the same
  // image; it takes the track only if it finds more lines than the kept pose. Without that second look a
  // near-square box's right pose that lost a line went to its wrong twin and back (seeds 1-40: box/16,
  // box/30 and cao/7 lost every valid frame).
  if (!m_params.navigation.follow_near_twin || processed_in != NavMode::kNearRange || out.pose_valid ||
      m_branch.known() || !m_near_twin_rival || (m_near_result.flags & kFlagLineRejected) == 0U)
    return;
  // The second look must be as clean as a fit gets (status tracking: every selected line, no mirrored
  // rival), no worse in rms, and have no near twin of its own that fits as well: campaign plate/28's
  // 4-line plate, whose true pose found 3 lines, had a twin that found 4 on clutter and was followed away.
  NearRangeResult& probe = m_twin_probe_result;
  m_twin_probe.reset();
  if (m_twin_probe.track(image, m_near_result.near_twin_rival, out.frame_number, probe) != Status::kOk ||
      probe.status != TrackStatus::kTracking || probe.lines_used <= m_near_result.lines_used ||
      probe.rms_px > m_near_result.rms_px ||
      (probe.flags & (kFlagAmbiguous | kFlagResidualFallback | kFlagNearTwinRival)) != 0U)
    return;
  m_filter.initialise(probe.pose, probe.covariance);
  m_last_pose = probe.pose;
  ++m_near_twins_followed;
}

bool NavigationPipeline::keptTheBranch(const Pose& pose, const Mat6& covariance) const {
  // A short break is no reason to forget which twin the track follows when the fit after it is as good as
  // one can be: the tracker's status tracking (all lines, no mirrored rival), the filter's prediction
  // accepted it, its attitude is known to the doubted limit, and its look stayed with the last valid pose
  // (the target turns a degree or so a frame; a flat target's twin is twice its tilt away). Looser, the rule
  // resumed biased tracks: on seeds 1-40 with ambiguous and degraded fits allowed, 547 frames more were
  // tracked and 13 more were confidently wrong (5-8 deg off, the last valid pose already 2-7 deg off), where
  // the three rival-free frames had withheld them.
  const NavigationParams& nav = m_params.navigation;
  if (nav.branch_continuity_frames <= 0 || m_frames_since_valid == ~0ULL) return false;
  const int longest = std::max(nav.branch_continuity_frames, nav.branch_continuity_spotless_frames);
  if (m_frames_since_valid > static_cast<std::uint64_t>(longest)) return false;
  if (!m_last_pose_update.accepted) return false;
  // A fit withheld beside a narrow strip in the break may have been the biased one the track then kept
  // (campaign box/129: 114-115 withheld, 116 kept the branch 6.3 deg off).
  if (nav.narrow_break_reconfirms && m_narrow_break) return false;
  if (m_frames_since_valid > static_cast<std::uint64_t>(nav.branch_continuity_frames)) {
    // A longer break keeps the branch only on a spotless fit: every line, no flag of any doubt. Any clean fit
    // after 5 or 8 frames let campaign box/25 through on a narrow face's strip, 8.3 deg off (stops 60, 65).
    if (m_near_result.status != TrackStatus::kTracking || (m_near_result.flags & ~kFlagTextureFallback) != 0U)
      return false;
  } else if (m_near_result.status != TrackStatus::kTracking &&
             !onlyLinesMissing(nav.branch_continuity_missing_lines)) {
    return false;
  }
  if (nav.doubted_max_attitude_sigma_deg > 0.0 &&
      poseSigmas(pose, covariance).attitude_deg > nav.doubted_max_attitude_sigma_deg)
    return false;
  const double tolerance_rad =
      (nav.branch_continuity_look_deg +
       nav.reacquire_tolerance_growth_deg_per_frame * static_cast<double>(m_frames_since_valid + 1)) *
      kRadPerDeg;
  return m_reacquisition.symmetries().lookDistanceRad(m_last_valid_pose, pose) <= tolerance_rad;
}

bool NavigationPipeline::onlyLinesMissing(int allowed) const {
  // A fit degraded only because some selected lines found too few points (an edge along a dark face, a
  // gradient where the contrast passes through zero) is measured on the others as well as any: no high
  // residual, no point-to-line fallback, no rival of either kind, no face seen as a strip whose lines may be
  // biased. What it lacks is lines, and a short break does not change which twin those lines follow.
  constexpr std::uint32_t kOtherDoubts =
      kFlagResidualHigh | kFlagResidualFallback | kFlagAmbiguous | kFlagNearTwinRival | kFlagNarrowFace;
  const NearRangeResult& r = m_near_result;
  return allowed > 0 && r.status == TrackStatus::kDegraded && (r.flags & kOtherDoubts) == 0U &&
         r.lines_total - r.lines_used <= allowed;
}

bool NavigationPipeline::fitLeftTheValidRange(const Pose& pose) const {
  // After a disputed jump the filter restarts on the jumped track and agrees with it; the range the last
  // valid pose was heading for does not (campaign smallsat/7023: 13 % in one frame, then confirmed 16-17 %
  // off). A slew or a turn leaves the range alone.
  const NavigationParams& nav = m_params.navigation;
  if (!m_range_check_active || m_frames_since_valid == ~0ULL || m_near_result.status == TrackStatus::kLost)
    return false;
  const double dt_s = static_cast<double>(m_last_exposure_ns - m_valid_exposure_ns) * 1e-9;
  // The reference's range and rate are the filter's, known only as well as its covariance says.
  const double expected_sigma_m = std::hypot(m_valid_range_sigma_m, m_valid_range_rate_sigma_mps * dt_s);
  return rangeLeftTheReference(nav, m_frames_since_valid + 1, pose.t_c_m.norm(), m_valid_range_m,
                               m_valid_range_m + m_valid_range_rate_mps * dt_s, expected_sigma_m);
}

bool NavigationPipeline::rangeLeftTheReference(const NavigationParams& nav, std::uint64_t frames,
                                               double range_m, double reference_m, double carried_m,
                                               double expected_sigma_m) {
  // The range is expected between the reference's, standing still, and the reference's carried on at its
  // range rate: the filter's rate after a run of fits may be their noise with a covariance that does not
  // say so (campaign octagon/5038: a target at rest, the right track after a jump withheld for 21 frames
  // when the rate was carried on alone).
  const double low_m = std::min(reference_m, carried_m);
  const double high_m = std::max(reference_m, carried_m);
  if (!(low_m > 0.0) || !(range_m > 0.0)) return false;
  const double nearest_m = std::clamp(range_m, low_m, high_m);
  const double tolerance = nav.disputed_max_range_change_rel +
                           nav.branch_range_growth_rel_per_frame * static_cast<double>(frames) +
                           kRangeSigmas * expected_sigma_m / nearest_m;
  return std::fabs(range_m / nearest_m - 1.0) > tolerance;
}

void NavigationPipeline::noteRangeReference(const NavSolution& out) {
  // The filter's range rate is the track's only after a run of valid poses; one or two after a start or a
  // find carry about the prior's rate (zero) with a confidence the motion has not earned (campaign
  // smallsat/14: valid once at 42 m after an acquisition, closing at 3.9 m/s, the filter's range rate
  // -0.15 m/s at 0.47 m/s 1-sigma; box/7036 after a find: 0.00 at 0.05. With either as the reference the
  // right track after a jump was withheld for the rest of the scene). Counted with the check off too: the
  // rate rung reads it (rateFromValidTrack).
  if (!out.pose_valid) {
    m_valid_run = 0;
  } else {
    m_valid_run = std::min(m_valid_run + 1, kValidRunCap);
    m_have_valid_range = m_valid_run >= m_params.navigation.branch_range_reference_min_frames;
  }
  if (!m_params.navigation.branch_range_after_jump) return;  // off: the check never starts
  if (out.pose_valid) {
    m_valid_exposure_ns = m_last_exposure_ns;
    m_range_check_active = false;
    // The reference is the filter's estimate on this frame, not the fit alone: one valid fit 3.8 % off in
    // range (4 of its own 1-sigma, accepted by the gate) made the right fits after it look broken
    // (campaign octagon/2 frame 138). Both the range and its rate are known as well as the covariance says.
    const bool filtered = m_filter.initialised() && m_filter.attitudeKnown();
    const Vec3 t_c_m = filtered ? m_filter.pose().t_c_m : out.pose.t_c_m;
    const double range_m = t_c_m.norm();
    m_valid_range_m = range_m;
    if (!filtered || !(range_m > 0.0)) {
      m_valid_range_rate_mps = 0.0;
      m_valid_range_sigma_m = 0.0;
      m_valid_range_rate_sigma_mps = m_filter.params().initial_velocity_sigma_m_s;  // the prior's, at rest
      return;
    }
    const Vec3 line_of_sight = t_c_m / range_m;
    const auto sigma_along_line_of_sight = [&](int first) {
      const Mat3 block = m_filter.covariance().block<3, 3>(first, first);
      return std::sqrt(std::max(0.0, line_of_sight.dot(block * line_of_sight)));
    };
    m_valid_range_rate_mps = m_filter.velocity().dot(line_of_sight);
    m_valid_range_sigma_m = sigma_along_line_of_sight(PoseFilter::kPosition);
    m_valid_range_rate_sigma_mps = sigma_along_line_of_sight(PoseFilter::kVelocity);
    return;
  }
  if (m_reacquisition_step.found) m_range_check_active = false;  // a find has its own confirmation
  if (m_pose_jumped && m_have_valid_range) m_range_check_active = true;
}

}  // namespace visnav::nav
