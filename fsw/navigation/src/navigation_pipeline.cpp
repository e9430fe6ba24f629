#include "visnav/navigation/navigation_pipeline.hpp"

#include <algorithm>
#include <cmath>

#include "visnav/farrange/nav_conversion.hpp"

namespace visnav::nav {

/// Longest exposure interval still taken as the camera's frame period by the frame-age check (0.1 Hz).
constexpr std::int64_t kMaxFramePeriodNs = 10'000'000'000LL;

LoadError NavigationPipeline::init(const PinholeCamera& camera, const PolygonModel& model,
                                   const PipelineParams& params) {
  m_camera = camera;
  m_params = params;
  m_params.navigation =
      params.navigation.withDerivedHandover(model.boundingRadius(), camera.intrinsics().fx_px);
  if (!(m_params.navigation.far_range_above_m > m_params.navigation.acquire_below_m))
    return LoadError::failure("navigation: far_range_above_m must exceed acquire_below_m (hysteresis)");
  LoadError e = m_modes.init(m_params.navigation);
  if (e.ok) e = m_filter.init(params.filter);
  if (e.ok) e = m_near.init(camera, model, params.nearrange);
  if (e.ok && m_params.navigation.follow_near_twin) e = m_twin_probe.init(camera, model, params.nearrange);
  m_twin_probe.setNearTwinChecks(true);  // its second look must have no near twin of its own
  if (e.ok) e = m_far.init(camera, params.farrange);
  m_far.setTargetRadius(model.boundingRadius());
  m_far.setRecheckMaxDistance(m_params.navigation.acquire_below_m);
  if (e.ok) e = m_acquisition.init(camera, model, params.acquisition, params.nearrange);
  if (e.ok)
    e = m_reacquisition.init(camera, model, m_params.navigation, params.nearrange, params.acquisition);
  if (!e.ok) return e;
  m_fdir.init(m_params.navigation, model, camera.intrinsics().fx_px);
  m_branch.init(m_params.navigation.branch_confirm_frames);
  m_max_view_cos = m_params.navigation.max_valid_view_angle_deg > 0.0
                       ? std::cos(m_params.navigation.max_valid_view_angle_deg * kRadPerDeg)
                       : 1.0;
  m_last_command = CommandAck{};
  m_near_twins_followed = 0;
  copyBounded("none", m_last_command.reason.data(), m_last_command.reason.size());
  return LoadError::success();
}

void NavigationPipeline::setClock(MonotonicClockNs clock) {
  m_clock = clock;
  m_near.setClock(clock);
  m_far.setClock(clock);
}

void NavigationPipeline::startNearRange(const Pose& pose, std::uint64_t frame_number) {
  m_last_pose = pose;
  m_have_pose = true;
  m_delivered = {};  // given, not measured on a frame
  m_coasted = 0;
  m_track_doubted = false;  // the operator's pose
  m_start_fits_pending = std::max(0, m_params.navigation.start_pose_doubt_fits);
  m_fit_restarted_filter = false;
  m_have_valid_range = false;  // a new track: no valid pose's range to keep yet
  m_range_check_active = false;
  m_valid_run = 0;
  m_find_confirms_branch = false;
  m_find_on_known_branch = false;
  m_track_twin_by_continuity = false;
  m_acquisition_awaits_near = false;
  m_filter.reset();
  // The given pose starts the filter (start_pose_sigma_*): the first measurements are checked against it.
  // Without it an ambiguous first fit (which never starts a track) left the filter empty and the prediction
  // frozen at the start pose while the target approached (campaign box/26).
  const NavigationParams& nav = m_params.navigation;
  const double range = pose.t_c_m.norm();
  if (nav.start_pose_sigma_deg > 0.0 && nav.start_pose_sigma_rel > 0.0 && range > 0.0) {
    // sqrt(trace) is the configured sigma: a third of its square on each axis.
    const double attitude_var = std::pow(nav.start_pose_sigma_deg * kRadPerDeg, 2) / 3.0;
    const double position_var = std::pow(nav.start_pose_sigma_rel * range, 2) / 3.0;
    Mat6 covariance = Mat6::Zero();
    covariance.topLeftCorner<3, 3>() = attitude_var * Mat3::Identity();
    covariance.bottomRightCorner<3, 3>() = position_var * Mat3::Identity();
    m_filter.initialise(pose, covariance);
  }
  m_near.reset();
  m_reacquisition.stop();
  m_branch.setKnown();  // the operator's pose says which branch
  m_branch_reference_pose = pose;
  m_frames_since_branch_reference = 0;
  m_reference_filter_epoch = m_filter.measurementEpoch();
  m_reference_track_epoch = m_filter.trackEpoch();
  m_modes.transition(NavMode::kNearRange, "start: initial pose given", frame_number);
  m_fdir.resetPersistence();
}

bool NavigationPipeline::centreInImage(const Pose& pose) const {
  Vec2 px;
  if (!m_camera.project(pose.t_c_m, px)) return false;
  return px.x() >= 0.0 && px.y() >= 0.0 && px.x() < m_camera.width() && px.y() < m_camera.height();
}

void NavigationPipeline::coast(NavSolution& out) {
  // Sec. II-H: no usable measurement this frame. The filter keeps propagating and its prediction fills the
  // pose fields for a few frames, but it is not delivered as valid: after a slew or a wrong motion model the
  // prediction can be far off, and a wrong pose reported as valid is the worst failure.
  if (!m_filter.initialised() || !m_filter.attitudeKnown() || m_coasted >= m_params.navigation.coast_frames)
    return;
  ++m_coasted;
  out.pose = m_filter.pose();
  out.covariance = m_filter.poseCovariance();
  out.quality = 0.0;
}

void NavigationPipeline::runFarRange(const MonoImage& image, NavSolution& out, ModeInputs& in) {
  // The far-range estimator gates by its own light track (last position, velocity, size). The filter's
  // prediction is not fed to it: from a few-pixel cluster the early distances are off by up to ~60 %, and a
  // filter initialised on them predicted a size that gated the true target out (measured on
  // full_approach_ci: far range lost the target from frame 20 on).
  m_far.estimate(image, m_far_result);
  out.far = far::toFarRangeSolution(m_far_result);
  if (!out.far.valid) {
    m_fdir.raise(kFaultFarRangeNoTarget);
    return;
  }
  m_last_far_fix = out.far;
  in.far_valid = true;
  in.far_distance_m = out.far.distance_m;
  if (!m_filter.initialised()) {
    Vec3 t;
    Mat3 cov;
    if (positionFromFarRange(out.far.direction_c, out.far.distance_m,
                             m_params.filter.far_direction_sigma_deg * kRadPerDeg,
                             m_params.filter.far_distance_sigma_rel, t, cov))
      m_filter.initialisePosition(t, cov);
    return;
  }
  // updateFarRange scales the uncertainty with the predicted range (the measured one would trust short
  // readings more and bias the range low).
  if (!m_filter.updateFarRange(out.far.direction_c, out.far.distance_m).accepted &&
      m_filter.consecutiveRejections() >=
          static_cast<std::uint32_t>(m_params.navigation.far_filter_reset_rejections))
    m_filter.reset();  // the filter lost the target: the next fix restarts it
}

Pose NavigationPipeline::predictedPose() const {
  return m_filter.initialised() && m_filter.attitudeKnown() ? m_filter.pose() : m_last_pose;
}

bool NavigationPipeline::closeRange() const {
  // Below the far-range hand-over the target is too large for far range to find again: a loss there is
  // recovered locally (close-range reacquisition), never by falling back.
  return m_last_pose.t_c_m.z() <= m_params.navigation.far_range_above_m;
}

void NavigationPipeline::runNearRange(const MonoImage& image, std::uint64_t frame_number, NavSolution& out,
                                      ModeInputs& in) {
  in.depth_known = m_have_pose;
  // The fit before overruled the filter: this one agrees, at best, with that single disputed fit.
  const bool follows_restart = m_fit_restarted_filter;
  m_fit_restarted_filter = false;
  if (m_reacquisition.active()) {
    m_near_result = NearRangeResult{};  // the main tracker did not run (status lost)
    runReacquisition(image, frame_number, out, in);
    in.depth_m = m_last_pose.t_c_m.z();
    return;
  }
  // Near twins are refitted while the branch is to be confirmed (confirmBranch): a quarter-turned
  // near-square plate passes every other test of an acquisition's first frames.
  m_near.setNearTwinChecks(m_acquisition_awaits_near || !m_branch.known());
  m_near.track(image, predictedPose(), frame_number, m_near_result);
  const NearRangeResult& r = m_near_result;
  out.tracked_surfaces = r.tracked_surfaces;
  out.lines_used = r.lines_used;
  out.lines_total = r.lines_total;

  NearRangeCheck check;
  check.near = &r;
  const bool measured = r.status != TrackStatus::kLost;
  check.evidence_good = measured && imageEvidenceGood(r, m_params.navigation);
  bool accepted = false;
  double predicted_range_m = 0.0;
  if (measured) {
    predicted_range_m = predictedPose().t_c_m.norm();  // before a disputed fit restarts the filter
    check.centre_in_image = centreInImage(r.pose);
    accepted = fuseNearRange(r, check);
  }
  const std::uint32_t faults = m_fdir.checkNearRange(check);
  m_near_range_faults = faults;
  // Checked against the start pose alone (the first), or a prediction from it and one fit, without motion.
  const bool start_fit = measured && m_start_fits_pending > 0;
  if (start_fit) --m_start_fits_pending;
  const bool dropped = !measured || m_fdir.faultPersisted() ||
                       nearFitBreaksTrack(check, m_last_pose_update.nis, m_params.navigation);
  if (!dropped && accepted) {
    // A fault (e.g. the innovation gate on a measurement the image supports) is flagged in fault_bits and
    // halves the quality; it does not swap the measurement for the prediction.
    // A 6-DOF update above a chi-square limit (0: off).
    const auto nis_above = [this](double limit) {
      return limit > 0.0 && m_last_pose_update.dof == 6 && m_last_pose_update.nis > limit;
    };
    // A fit the gate let through but the filter found surprising (doubt_nis_chi2) is more often a one-frame
    // spike than the target's motion (campaign smallsat/5017: 5.2 deg off for one frame at NIS 20).
    const bool surprising = nis_above(m_params.navigation.doubt_nis_chi2);
    // The first fit after an operator's start pose has no track behind it, only a prior: one that disagrees
    // with it (start_pose_doubt_nis_chi2) is doubted like a find (campaign octagon/7, octagon/7028,
    // plate/7032: 5.5-7.1 deg off at NIS 9.0-9.7).
    const bool start_disputed = start_fit && nis_above(m_params.navigation.start_pose_doubt_nis_chi2);
    const bool restart_unconfirmed = follows_restart && m_params.navigation.doubt_after_filter_restart;
    const bool doubted =
        nearFitDoubted(r, faults, m_params.navigation) || surprising || start_disputed || restart_unconfirmed;
    // Disputed by the filter and turned further since the frame before than a target turns in one frame:
    // tracked, not valid. Against the last pose, not the prediction: a filter restarted from two alternating
    // fits predicts a rate they do not have (slew_box: 13.6 deg/s). Until deliver() below, m_last_pose is the
    // frame before's pose, and m_coasted 0 says it was delivered then.
    // Its range against the prediction's, which carries the approach's speed (a slew changes neither).
    const NavigationParams& nav = m_params.navigation;
    const bool disputed = (faults & kFaultInnovation) != 0U && m_have_pose && m_coasted == 0;
    const bool turned = nav.disputed_max_look_change_deg > 0.0 &&
                        m_reacquisition.symmetries().lookDistanceRad(m_last_pose, r.pose) * kDegPerRad >
                            nav.disputed_max_look_change_deg;
    const bool moved_in_range =
        nav.disputed_max_range_change_rel > 0.0 && predicted_range_m > 0.0 &&
        std::fabs(r.pose.t_c_m.norm() / predicted_range_m - 1.0) > nav.disputed_max_range_change_rel;
    // Or disputed far beyond the gate: a NIS no consistent fit reaches (campaign box/5018: 5.3 deg off at
    // NIS 85 and 0.44 deg 1-sigma, its look 4.4 deg from the frame before's).
    const bool far_beyond_gate = nav.disputed_max_nis > 0.0 && m_last_pose_update.dof == 6 &&
                                 m_last_pose_update.nis > nav.disputed_max_nis;
    const bool jumped = disputed && (turned || moved_in_range || far_beyond_gate);
    // The filter's estimate after a complete fit it accepted, certain on its own, carries the frames before
    // it; the error of a partial or uncertain fit repeats from frame to frame, and averaging it only hides
    // it: such a fit is delivered as measured (deliver_filtered_pose; deliver_filtered_partial_fit takes a
    // partial fit its lines do not doubt too, unless its track's find is still doubted: fitMayBeFiltered).
    m_pose_filtered = check.innovation_accepted && fitMayBeFiltered(r, nav, m_track_doubted) &&
                      withinValidSigmas(r.pose, r.covariance * r.systematic_gain, nav);
    deliver(m_pose_filtered ? m_filter.pose() : r.pose,
            m_pose_filtered ? m_filter.poseCovariance() : r.covariance,
            faults == 0U ? r.quality : 0.5 * r.quality, out, doubted || m_track_doubted, r.systematic_gain);
    // A filter restart (restartFilter) starts from the fits as measured, not from the estimates that averaged
    // them: those lag a change of motion the fits already show (campaign box/23 with partial fits filtered:
    // restarted from them, the filter took a motion no fit showed, NIS 14-85 after it).
    if (m_pose_filtered)
      m_delivered[m_delivered_newest] = DeliveredPose{r.pose, r.covariance, m_last_exposure_ns};
    m_pose_jumped = jumped;
    const bool misses_outline = minimalFitMissesOutline(r, nav);
    if (jumped || misses_outline) {
      out.withheld |= (jumped ? kWithheldJumped : 0U) | (misses_outline ? kWithheldMissesOutline : 0U);
      out.pose_valid = false;
    }
  } else if (dropped && closeRange()) {
    startReacquisition(image, frame_number, out, in);
  } else {
    coast(out);
    in.near_fault_persisted = m_fdir.faultPersisted();
  }
  in.depth_m = out.pose_valid ? out.pose.t_c_m.z() : m_last_pose.t_c_m.z();
}

void NavigationPipeline::enterMode(NavMode mode) {
  m_fdir.resetPersistence();
  m_start_fits_pending = 0;
  m_fit_restarted_filter = false;
  m_range_check_active = false;
  m_coasted = 0;
  const bool far_track_kept = m_far_track_kept;
  m_far_track_kept = false;
  switch (mode) {
    case NavMode::kStandby: break;
    case NavMode::kFarRange:
      if (far_track_kept) {
        m_far.skipFrames(m_acquisition_result.frames);  // the failed acquisition's frames
      } else {
        m_far.reset();
      }
      m_reacquisition.stop();
      break;
    case NavMode::kAcquisition: m_acquisition.start(m_last_far_fix); break;
    case NavMode::kNearRange:
      m_near.reset();
      m_reacquisition.stop();
      break;
  }
}

Status NavigationPipeline::process(const Frame* frame, std::int64_t now_ns, NavSolution& out) {
  out = NavSolution{};
  m_last_pose_update = FilterUpdate{};
  m_reacquisition_step = ReacquisitionStep{};
  m_acquisition_result = acq::AcquisitionResult{};
  m_pose_showed_face = true;
  m_fit_kept_the_branch = false;
  m_near_twin_rival = false;
  m_mirror_resolved = false;
  m_mirror_nis = -1.0;
  m_pose_jumped = false;
  m_range_broken = false;
  m_pose_filtered = false;
  m_fit_attitude_sigma_deg = 0.0;
  m_followed_narrow_break = false;
  const std::int64_t start = m_clock != nullptr ? m_clock() : 0;
  out.cycle_number = ++m_cycles;
  out.frame_number = m_last_frame_number;
  const NavMode mode_before = m_modes.mode();
  out.mode = mode_before;
  NavMode processed_as = mode_before;
  Status status = Status::kOk;
  ModeInputs in;
  if (frame == nullptr || frame->image.empty()) {
    m_fdir.raise(kFaultNoFrame);
    if (mode_before == NavMode::kNearRange) coast(out);
  } else if (frame->image.width() != m_camera.width() || frame->image.height() != m_camera.height()) {
    // A frame the camera contract says cannot happen (driver or config fault): counted apart from a missing
    // one, and not processed.
    ++m_frames_processed;
    m_fdir.raise(kFaultBadFrame);
    if (mode_before == NavMode::kNearRange) coast(out);
    status = Status::kInvalidArgument;
  } else {
    ++m_frames_processed;
    m_last_frame_number = frame->sequence;
    out.frame_number = frame->sequence;
    out.frame_received = true;
    out.exposure_time_ns = frame->exposure_time_ns;
    // The camera's period: the interval between the last two exposures, up to kMaxFramePeriodNs (a longer
    // gap is a loss, not a period); before two frames, the nominal one the caller gave.
    const std::int64_t interval_ns = m_have_last_exposure ? frame->exposure_time_ns - m_last_exposure_ns : 0;
    const std::int64_t period_ns =
        interval_ns > 0 && interval_ns <= kMaxFramePeriodNs ? interval_ns : m_nominal_frame_period_ns;
    m_fdir.checkFrameAge(static_cast<double>(now_ns - frame->exposure_time_ns) * 1e-6,
                         static_cast<double>(period_ns) * 1e-6);
    // Propagate the filter to this exposure (two periods after a missed frame: the timestamps say so).
    if (m_have_last_exposure && m_filter.initialised()) {
      const double dt_s = static_cast<double>(frame->exposure_time_ns - m_last_exposure_ns) * 1e-9;
      if (dt_s > 0.0) m_filter.predict(dt_s);
    }
    m_previous_exposure_ns = m_have_last_exposure ? m_last_exposure_ns : 0;
    m_have_last_exposure = true;
    m_last_exposure_ns = frame->exposure_time_ns;
    m_near_range_faults = 0U;
    switch (mode_before) {
      case NavMode::kStandby: break;
      case NavMode::kFarRange:
        runFarRange(frame->image, out, in);
        if (m_modes.acquiringBesideFarRange()) {
          runAcquisition(frame->image, out.frame_number, out, in);
          processed_as = NavMode::kAcquisition;  // its pose and branch are an acquisition's
        } else {
          checkCueBeforeHandOver(frame->image, in);
        }
        break;
      case NavMode::kAcquisition: runAcquisition(frame->image, out.frame_number, out, in); break;
      case NavMode::kNearRange: runNearRange(frame->image, out.frame_number, out, in); break;
    }
  }
  confirmBranch(processed_as, out);
  if (frame != nullptr && out.frame_received) followNearTwin(mode_before, frame->image, out);
  noteRangeReference(out);
  if (out.pose_valid) {
    m_last_valid_pose = out.pose;
    m_frames_since_valid = 0;
    m_branch_reference_pose = out.pose;
    m_frames_since_branch_reference = 0;
    m_reference_filter_epoch = m_filter.measurementEpoch();
    m_reference_track_epoch = m_filter.trackEpoch();
    flagTwins(out);
  } else if (m_frames_since_valid != ~0ULL) {
    ++m_frames_since_valid;
  }
  // A strip's lines may be biased (kFlagNarrowFace): a break it caused is no short gap
  // (narrow_break_reconfirms).
  if (out.pose_valid) {
    m_narrow_break = false;
  } else if (mode_before == NavMode::kNearRange && frame != nullptr && out.frame_received &&
             m_near_result.status != TrackStatus::kLost && (m_near_result.flags & kFlagNarrowFace) != 0U) {
    m_narrow_break = true;
  }
  if (!out.pose_valid && m_frames_since_branch_reference != ~0ULL) ++m_frames_since_branch_reference;
  const bool was_acquiring_beside = m_modes.acquiringBesideFarRange();
  if (m_modes.step(in, out.frame_number)) {
    enterMode(m_modes.mode());
  } else if (m_modes.acquiringBesideFarRange() != was_acquiring_beside) {
    acquisitionBesideFarRange(m_modes.acquiringBesideFarRange());
  }
  out.fault_bits = m_fdir.endFrame();
  if (m_clock != nullptr) out.timing.process_us = static_cast<double>(m_clock() - start) * 1e-3;
  return status;
}

bool NavigationPipeline::command(ModeCommandKind kind, std::uint32_t command_id, std::uint64_t frame_number,
                                 CommandAck& ack) {
  const NavMode before = m_modes.mode();
  const bool accepted = m_modes.command(kind, command_id, m_last_far_fix.valid, frame_number, ack);
  if (accepted && kind == ModeCommandKind::kReacquire) m_far.clearRefuted();  // the operator overrides
  if (accepted && m_modes.mode() != before) enterMode(m_modes.mode());
  m_last_command = ack;
  return accepted;
}

void NavigationPipeline::fillHealth(HealthRecord& health) const {
  health.mode = m_modes.mode();
  health.fault_bits = m_fdir.activeFaults();
  health.fault_counts = m_fdir.faultCounts();
  health.frames_processed = m_frames_processed;
  health.mode_transitions = m_modes.transitionCount();
  health.last_transition = m_modes.lastTransition();
  health.last_command = m_last_command;
}

}  // namespace visnav::nav
