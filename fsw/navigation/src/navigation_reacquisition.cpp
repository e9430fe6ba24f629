// NavigationPipeline's recovery of a track lost below the far-range hand-over: the local search, the
// close-range acquisition and the filter restart from their find (fsw/navigation/README.md, "Close-range
// reacquisition"). The rest of the class: navigation_pipeline.cpp.
#include <algorithm>
#include <cmath>

#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/navigation/square_spiral.hpp"

namespace visnav::nav {

void NavigationPipeline::startReacquisition(const MonoImage& image, std::uint64_t frame_number,
                                            NavSolution& out, ModeInputs& in) {
  m_near_result.status = TrackStatus::kLost;
  // The search is predicted from the filter: only with the motion it knows (pose_filter.hpp). A range rate
  // the prediction drops although it stands out on its own (below the start-at-rest prior) is kept for the
  // rate rung (rateRungRange), where it is a validated track's (rateFromValidTrack).
  const double range_rate_m_s =
      m_params.navigation.reacquire_range_rate_rung && m_filter.initialised() && rateFromValidTrack()
          ? m_filter.significantRangeRate()
          : 0.0;
  const std::uint32_t dropped =
      m_params.navigation.reacquire_drop_insignificant_rates ? m_filter.dropInsignificantRates() : 0U;
  m_search_range_rate_m_s = (dropped & PoseFilter::kDroppedVelocity) != 0U ? range_rate_m_s : 0.0;
  m_search_start_exposure_ns = m_last_exposure_ns;
  m_search_start_t_c_m = m_filter.initialised() ? m_filter.pose().t_c_m : Vec3::Zero();
  m_search_rate_turn = false;
  m_acquisition_rate_turn = false;
  m_reacquisition.start();
  m_acquisition.reset();
  m_far.reset();  // its light track starts with the search (reacquire_far_cue)
  m_next_attempt_far_cued = false;
  m_acquisition_tile = 1;
  m_acquisition_tile_turn = false;
  m_acquisition_rung = 0;
  m_acquisition_rung_turn = false;
  m_fdir.resetPersistence();
  runReacquisition(image, frame_number, out, in);
}

void NavigationPipeline::runReacquisition(const MonoImage& image, std::uint64_t frame_number,
                                          NavSolution& out, ModeInputs& in) {
  ReacquisitionStep& step = m_reacquisition_step;
  // Every other searching frame starts at the range the track's rate reached; a candidate is confirmed
  // against the prediction it was found at (the rung moves on with the rate meanwhile).
  Pose predicted = predictedPose();
  if (!m_reacquisition.confirming()) m_search_rate_turn = !m_search_rate_turn;
  const double rung_m = m_search_rate_turn ? rateRungRange(predicted.t_c_m.norm()) : 0.0;
  if (rung_m > 0.0) predicted.t_c_m *= rung_m / predicted.t_c_m.norm();
  const bool hedge = m_search_rate_turn && rung_m == 0.0 && motionHedge(predicted);
  if (hedge) predicted.t_c_m = m_search_start_t_c_m;
  m_reacquisition.step(image, predicted, frame_number, step);
  step.rate_rung_range_m = rung_m;
  step.motion_hedge = hedge;
  step.searched_t_c_m = predicted.t_c_m;
  if (!step.found) runCloseRangeAcquisition(image, frame_number, step);
  if (step.found) {
    m_near_result.status = step.status;  // the confirming tracker's verdict on the delivered pose
    m_near.reset();
    // Both judged against the prediction the find replaces, before the restart.
    const bool continues_prediction = findContinuesPrediction(step.pose);
    m_find_on_known_branch = continues_prediction || findOnKnownBranch(step.pose);
    const Vec3 carried_rate = m_filter.angularVelocity();
    const Mat3 carried_rate_covariance =
        m_filter.covariance().block<3, 3>(PoseFilter::kAngularVelocity, PoseFilter::kAngularVelocity);
    startFilterFromReacquisition(step);
    // The rate the coasted filter kept (a search drops the insignificant ones) goes on with the track it
    // continues; a restart at rest leaves a tumbling target's next fits rejected.
    if (continues_prediction && m_params.navigation.reacquire_carry_angular_rate && !carried_rate.isZero(0.0))
      (void)m_filter.carryAngularVelocity(carried_rate, carried_rate_covariance);
    m_fdir.resetPersistence();
    // A find has no track behind it yet, only its confirmation frames: it is doubted like a disputed pose
    // (campaign plate/135: re-found 13.8 deg off with a 1.7 deg 1-sigma; replayed on the full run
    // before the close-range acquisition was on: wrong frames 165 -> 160 for 0.001 of tracked mean).
    m_track_doubted = true;
    m_doubt_clear_run = 0;
    m_find_confirms_branch = m_params.navigation.doubt_clear_frames > 1 && m_find_on_known_branch;
    m_track_twin_by_continuity = step.twin_by_continuity;
    deliver(step.pose, step.covariance, step.quality, out, true);
  } else {
    coast(out);
    fadeSearchRates();
    in.reacquisition_timed_out =
        m_reacquisition.framesSearching() >= m_params.navigation.reacquire_timeout_frames;
  }
}

bool NavigationPipeline::findOnKnownBranch(const Pose& found) const {
  // The local search is judged against its prediction, and the prediction continues the lost track: where
  // no pose of that track was ever valid, it may be the wrong twin's (campaign octagon/172: acquired at 30 m
  // on the near-square plate's quarter turn, withheld by the near-twin checks, lost, and re-found on the
  // same quarter turn at 14 m). Such a find, or one whose look left the last valid pose's, earns its branch
  // as any unknown one does (track_branch.hpp).
  // A reference old enough that its tolerance keeps a quarter turn's twin too tells neither apart
  // (branch_reference_max_look_deg).
  // A find may still continue it as the filter carried it (findContinuesPrediction).
  if (!m_params.navigation.find_confirms_only_from_reference) return true;
  return m_frames_since_branch_reference != ~0ULL &&
         m_reacquisition.lookToleranceRad(m_frames_since_branch_reference) <=
             m_params.navigation.branch_reference_max_look_deg * kRadPerDeg &&
         m_reacquisition.lookConsistentWith(m_branch_reference_pose, m_frames_since_branch_reference, found);
}

bool NavigationPipeline::findContinuesPrediction(const Pose& found) const {
  // The reference carried to this frame by the rates its track measured (an eclipse coasts on them): a
  // find that close to it continues that track, however long ago the reference was (campaign plate/10:
  // re-found 43 frames after its last valid pose, 27 deg from it and 5 deg from its prediction, tumbling
  // 3.3 deg/s; withheld 3 frames for its rival-free count). The tolerance is fixed, not widened by the
  // prediction's covariance: a wrong twin is a quarter turn or twice a plate's tilt away.
  const double tolerance_deg = m_params.navigation.find_prediction_look_deg;
  return tolerance_deg > 0.0 && predictionCarriesReference() &&
         m_reacquisition.symmetries().lookDistanceRad(m_filter.pose(), found) <= tolerance_deg * kRadPerDeg;
}

bool NavigationPipeline::predictionCarriesReference() const {
  return m_frames_since_branch_reference != ~0ULL && m_filter.initialised() && m_filter.attitudeKnown() &&
         m_filter.measurementEpoch() == m_reference_filter_epoch;
}

void NavigationPipeline::fadeSearchRates() {
  // The motion the track left with predicts a few frames, not a whole search: a target swinging sideways
  // turns back, and a rate read from the last uncertain fits is wrong for good; carried in a straight line
  // they took the search's prediction away from the target (campaign octagon/37: 8 m off 60 frames into the
  // search where the last pose was 4 m off; box/7: 82 deg off where the last pose was 19 deg off).
  const double tau_s = m_params.navigation.reacquire_motion_decay_s;
  if (!(tau_s > 0.0) || m_previous_exposure_ns == 0 || !m_filter.initialised()) return;
  const double dt_s = static_cast<double>(m_last_exposure_ns - m_previous_exposure_ns) * 1e-9;
  if (dt_s > 0.0) (void)m_filter.scaleRates(std::exp(-dt_s / tau_s));
}

void NavigationPipeline::startFilterFromReacquisition(const ReacquisitionStep& step) {
  // From the frame before, predicted over the exposure interval and corrected with this frame's pose, the
  // filter leaves with the target's motion across the image instead of zero velocity, which a target moving
  // 16 px a frame outran on the next frame (campaign cao/45). Only that lateral motion is taken: the frame
  // before is set to this frame's attitude and range, because the difference of two single fits in
  // attitude or depth is their noise (a 1 deg difference read as 5 deg/s turned the prediction 35 deg away
  // over 20 frames of search, smallsat/72). A motion the filter rejects restarts it from this frame alone.
  if (!step.has_previous) {
    m_filter.initialise(step.pose, step.covariance);
    return;
  }
  const double dt_s = m_previous_exposure_ns > 0
                          ? static_cast<double>(m_last_exposure_ns - m_previous_exposure_ns) * 1e-9
                          : 0.0;
  const double range_m = step.pose.t_c_m.norm();
  const double previous_range_m = step.previous_pose.t_c_m.norm();
  if (dt_s > 0.0 && range_m > 0.0 && previous_range_m > 0.0) {
    Pose before;
    before.R_c_m = step.pose.R_c_m;
    before.t_c_m = step.previous_pose.t_c_m * (range_m / previous_range_m);
    if (m_filter.initialise(before, step.previous_covariance) == Status::kOk &&
        m_filter.predict(dt_s) == Status::kOk) {
      const FilterUpdate u = m_filter.update(step.pose, step.covariance, RejectedInnovation::kIgnored);
      if (u.status == Status::kOk && u.accepted) return;
    }
  }
  m_filter.initialise(step.pose, step.covariance);
}

Vec3 NavigationPipeline::nextAcquisitionTile(const Vec3& predicted_direction, double spacing_px,
                                             double radius_px) {
  // Every other attempt looks at the prediction itself: where it is still right, the target's clearest
  // frames must not fall on an attempt elsewhere (campaign cao/20: the prediction's window held the target,
  // approaching, with edge SNR 7.4 on the frame a tile had; re-found 51 frames later). The others walk the
  // spiral's cells whose centres lie within the searched disc and on the image (a window centred off the
  // image sees a sliver of it), round again after the last ring. Bounded by the cells the disc's rings hold.
  const bool tile_turn = m_acquisition_tile_turn;
  m_acquisition_tile_turn = !m_acquisition_tile_turn;
  Vec2 centre_px;
  if (!tile_turn || !(spacing_px > 0.0) || !m_camera.project(predicted_direction, centre_px))
    return predicted_direction;
  // The spacing shrinks with the target's predicted size: a prediction coasting away (range 1e5 m) with
  // direction_margin_deg 0 and f 1000 px spaces tiles ~0.02 px apart by arithmetic, ~35 000 rings (an int
  // overflow in the cell count).
  const double diagonal_px = std::hypot(m_camera.width(), m_camera.height());
  const int rings = static_cast<int>(std::min(std::min(std::max(radius_px, 0.0), diagonal_px) / spacing_px,
                                              static_cast<double>(kMaxTileRings)));
  const int cells = squareSpiralCells(rings);
  for (int tried = 1; tried < cells; ++tried) {
    if (m_acquisition_tile < 1 || m_acquisition_tile >= cells) m_acquisition_tile = 1;  // 0: the prediction
    const Eigen::Vector2i cell = squareSpiralCell(m_acquisition_tile++);
    const Vec2 offset = spacing_px * Vec2(cell.x(), cell.y());
    const Vec2 tile_px = centre_px + offset;
    if (offset.norm() <= radius_px && m_camera.inImage(tile_px)) return m_camera.bearing(tile_px);
  }
  return predicted_direction;
}

bool NavigationPipeline::rateFromValidTrack() const {
  // A rate measured by fits that were never delivered, or by a filter restarted since the last valid pose,
  // carries their errors into every other frame of the search: campaign box/5030 (never valid before the
  // loss, 24.7 deg off, its rate read closing while the prediction was already 17 % short: 53 -> 16
  // tracked) and box/25 (restarted at 3.2 m/s from three biased strip fits).
  if (!m_params.navigation.reacquire_rate_rung_valid_track_only) return true;
  return m_have_valid_range && m_filter.trackEpoch() == m_reference_track_epoch;
}

bool NavigationPipeline::motionHedge(const Pose& predicted) const {
  // The filter carries the velocity the track left with in a straight line; a target swinging sideways
  // turns back meanwhile (campaign plate/5004: 2.0 m/s when a 6.2 s eclipse began, the prediction 13 m and
  // 34 deg of line of sight off when the plate reappeared, the last trusted pose 3.4 m off).
  // The held start keeps the prediction's attitude (the rates the filter kept turn it) and is taken only
  // once the prediction has left it by more than a find's range tolerance: nearer, the frame would repeat
  // the prediction's starts.
  if (!m_params.navigation.reacquire_motion_hedge || !(m_search_start_t_c_m.z() > 0.0)) return false;
  const double range_m = predicted.t_c_m.norm();
  return range_m > 0.0 && (predicted.t_c_m - m_search_start_t_c_m).norm() >
                              m_params.navigation.reacquire_range_tolerance_rel * range_m;
}

double NavigationPipeline::rateRungRange(double predicted_range_m) const {
  if (m_search_range_rate_m_s == 0.0 || !(predicted_range_m > 0.0)) return 0.0;
  // The rate carried in a straight line: an approach goes on at the speed it was measured at (a slew or an
  // eclipse does not stop it); a wrong rung costs every other frame's starts and attempts. A local-search
  // find there is judged at 5 % of the rung's range, an acquisition's as at any range (its own checks).
  const double elapsed_s = static_cast<double>(m_last_exposure_ns - m_search_start_exposure_ns) * 1e-9;
  const double nearest_m = m_near.model().boundingRadius();
  const double farthest_m = std::max(nearest_m, m_params.navigation.far_range_above_m);
  const double rung_m =
      std::clamp(predicted_range_m + m_search_range_rate_m_s * elapsed_s, nearest_m, farthest_m);
  return std::abs(rung_m - predicted_range_m) >
                 m_params.navigation.reacquire_range_tolerance_rel * predicted_range_m
             ? rung_m
             : 0.0;
}

double NavigationPipeline::nextAcquisitionRangeFactor(double range_m) {
  // The track's range rate first (reacquire_range_rate_rung): every other attempt at the range it reached,
  // where it reached one off the prediction's.
  const double rung_m = rateRungRange(range_m);
  if (rung_m > 0.0) {
    m_acquisition_rate_turn = !m_acquisition_rate_turn;
    return m_acquisition_rate_turn ? rung_m / range_m : 1.0;
  }
  // Every other attempt stays at the prediction's range: where it is right (most searches) the ladder must
  // not take its attempts (campaign seeds 1-40 with every attempt on the ladder: smallsat/22 43 -> 0 and
  // box/9 31 -> 1 tracked frames). The others take rung k of -1, +1, -2, +2, ... (negative: nearer); a rung
  // whose range leaves the band is skipped, at most one pass over the rungs per call (bounded whatever the
  // band).
  const double span = m_params.acquisition.range_span_rel;
  if (!m_params.navigation.reacquire_range_ladder || !(span > 0.0) || !(range_m > 0.0)) return 1.0;
  m_acquisition_rung_turn = !m_acquisition_rung_turn;
  if (m_acquisition_rung_turn) return 1.0;
  const double step = (1.0 + span) * (1.0 + span);
  const double nearest_m = m_near.model().boundingRadius();
  const double farthest_m = m_params.navigation.far_range_above_m;
  for (int tried = 0; tried < 2 * kMaxRangeRungs; ++tried) {
    if (m_acquisition_rung < 0 || m_acquisition_rung >= 2 * kMaxRangeRungs) m_acquisition_rung = 0;
    const int index = m_acquisition_rung++;
    const int rung = (index / 2 + 1) * (index % 2 == 0 ? -1 : 1);
    const double factor = std::pow(step, rung);
    const double rung_range_m = range_m * factor;
    if (rung_range_m >= nearest_m && rung_range_m <= farthest_m) return factor;
  }
  return 1.0;
}

void NavigationPipeline::runCloseRangeAcquisition(const MonoImage& image, std::uint64_t frame_number,
                                                  ReacquisitionStep& step) {
  // The local search keeps the prediction's range and look and only moves it across the image: a target
  // that approaches, recedes or tumbles while lost leaves it for good (on the campaign's longest searches
  // the prediction was > 5 % off in range on 58 % of the frames and > 10 deg in attitude on 60 %). The
  // acquisition searches attitude and range around the prediction's line of sight instead, its window as
  // wide as the local search has grown, up to one target radius more (the lateral offset is the local
  // grid's job, and the acquisition re-centres on the window's edges; a window twice as wide coarsened its
  // working image and the right pose's edge agreement fell to 0.55, below the 0.7 it must keep). It runs in
  // near range only while the reacquisition is active; a failed attempt restarts from the next frame's
  // prediction.
  const int after = m_params.navigation.reacquire_acquisition_after_frames;
  if (after <= 0 || m_reacquisition.framesSearching() < after) return;
  const acq::AcquisitionState state = m_acquisition.state();
  const bool restart = state == acq::AcquisitionState::kIdle || state == acq::AcquisitionState::kFailed ||
                       state == acq::AcquisitionState::kSucceeded;
  if (restart) {
    const Pose predicted = predictedPose();
    const double range_m = predicted.t_c_m.norm();
    if (!(range_m > 0.0) || !(predicted.t_c_m.z() > 0.0)) return;
    const Vec3 predicted_direction = predicted.t_c_m / range_m;
    const double focal_px = m_camera.intrinsics().fx_px;
    const double target_radius_px = focal_px * m_near.model().boundingRadius() / range_m;
    const double margin_px = std::min(static_cast<double>(step.search_radius_px), target_radius_px);
    const double margin_deg =
        m_params.acquisition.direction_margin_deg + std::atan(margin_px / focal_px) * kDegPerRad;
    // Where far range sees the target, its line of sight is a measurement; the prediction's is not, and
    // while nothing is measured it drifts with the filter's last rates (campaign box/23: after a 46-frame
    // eclipse it went 10 to 120 deg off). Far range's line of sight is taken only where the prediction's
    // window does not hold it, and on every other attempt: far range also locks on clutter where the
    // prediction was right (box/37), and an attempt cued by far range while the prediction was 1.9 deg off
    // the target's line of sight and right in range confirmed a pose 5.6 % off in range (box/191). Its
    // distance is not taken: gamma / sqrt(n) holds for a target a few pixels across, and an extended one's
    // outline has far fewer response pixels than its area (a plate at 12 m read 65 m); the prediction's range
    // is, along the fix's line of sight. Far range's own light track is kept over the search's frames.
    const bool far_turn = m_next_attempt_far_cued;
    m_next_attempt_far_cued = !m_next_attempt_far_cued;
    bool cued = false;
    if (m_params.navigation.reacquire_far_cue && far_turn) {
      m_far.estimate(image, m_far_result);
      if (m_far_result.valid) {
        const Vec3 direction = m_far_result.direction_c.normalized();
        const double off_deg =
            std::acos(std::clamp(direction.dot(predicted_direction), -1.0, 1.0)) * kDegPerRad;
        if (off_deg > margin_deg) {
          m_acquisition.start(direction, range_m * direction.z());
          cued = m_acquisition.state() == acq::AcquisitionState::kSearching;
        }
      }
    }
    step.far_cue = cued;
    if (!cued) {
      // A window's half-size h (Acquisition::start, at the prediction's range) less the target's radius r
      // is how far off centre the target may lie and still be whole in it: tiles 2 (h - r) apart leave no
      // point of the disc further than that from the nearest tile's centre along either image axis.
      const double half_px = m_params.acquisition.window_margin * target_radius_px +
                             focal_px * std::tan(margin_deg * kRadPerDeg);
      const double spacing_px = 2.0 * (half_px - target_radius_px);
      Vec3 direction = predicted_direction;
      // Where far range sees nothing (a limb, a gradient), the outline slid over the searched disc at the
      // prediction's look and range (the local search's cue, this frame) still points at the target; its
      // best match is taken on far range's turn, and only where the prediction's window would not hold the
      // whole target there. The other turn stays at the prediction: a cue on clutter holds an attempt for
      // up to four frames, and a target reappearing in the prediction's window was found late behind it
      // (campaign box/36 with the cue on every attempt: 127 -> 93 tracked).
      Vec2 cue_offset_px;
      Vec2 centre_px;
      if (m_params.navigation.reacquire_acquisition_outline_cue && far_turn &&
          m_reacquisition.bestCueOffset(cue_offset_px) && cue_offset_px.norm() > half_px - target_radius_px &&
          m_camera.project(predicted_direction, centre_px)) {
        direction = m_camera.bearing(centre_px + cue_offset_px);
        step.outline_cue = true;
      } else if (m_params.navigation.reacquire_acquisition_tiles) {
        direction = nextAcquisitionTile(predicted_direction, spacing_px, step.search_radius_px);
      }
      // At the prediction its own depth (as with tiles off), on a tile the range along it; on the rate's
      // rung (reacquire_range_rate_rung) or the range ladder's (reacquire_range_ladder) that times its
      // factor.
      const double factor = nextAcquisitionRangeFactor(range_m);
      m_acquisition.start(
          direction,
          factor * (direction == predicted_direction ? predicted.t_c_m.z() : range_m * direction.z()),
          margin_deg);
    }
  }
  // The track lost a few frames ago tells a near twin the image cannot resolve from the true pose: the
  // same look test, with this frame's tolerance, that the find must pass below. Its reference is the last
  // valid pose, or the operator's start pose before any (m_branch_reference_pose).
  if (m_params.navigation.reacquire_twin_continuity && m_frames_since_branch_reference != ~0ULL)
    m_acquisition.setLookReference(m_branch_reference_pose,
                                   m_reacquisition.lookToleranceRad(m_frames_since_branch_reference));
  acq::AcquisitionResult result;
  if (m_acquisition.step(image, frame_number, result) != Status::kOk) return;
  step.acquisition_state = static_cast<int>(result.state);
  step.acquisition_failure = static_cast<int>(result.failure);
  step.acquisition_edge_snr = result.edge_snr;
  if (result.state != acq::AcquisitionState::kSucceeded) return;
  // A find the local search would not take either: a fit without corners (point-to-line fallback) or with
  // a mirrored rival fits a flat-lit box's mirrored pose as well as the true one (campaign box/191: found
  // 107 deg and 12 % in range off, delivered for 31 frames without this check).
  if ((result.tracker_flags & (kFlagResidualFallback | kFlagAmbiguous)) != 0U) {
    ++step.starts_weak;
    return;
  }
  // The stale prediction cannot judge the range (right finds were up to 160 % off it after long searches),
  // nor its look once the filter coasts on a rate from a bad track (box/78: 16 deg off at the loss, 29 deg
  // four frames later). The last valid pose judges the look, with the local search's tolerance widening per
  // frame since it: a box turned onto another face a few frames after the loss is refused (campaign box/160:
  // found 89 deg off 11 frames after its last valid pose). Before any valid pose, the operator's start pose
  // judges it (campaign box/147: no pose of its first frames valid, then found 84 deg off 42 frames later).
  if (m_frames_since_branch_reference != ~0ULL &&
      !m_reacquisition.lookConsistentWith(m_branch_reference_pose, m_frames_since_branch_reference,
                                          result.pose)) {
    ++step.starts_inconsistent;
    return;
  }
  step.found = true;
  step.by_acquisition = true;
  step.twin_by_continuity = result.twin_resolved_by_continuity;
  // The confirmation's frame before, where it followed the target's motion: the filter leaves with that
  // motion (startFilterFromReacquisition) instead of at rest, which a target crossing the image 19 px a frame
  // outran on the next frame (campaign cao/1).
  step.has_previous = result.has_previous;
  step.previous_pose = result.previous_pose;
  step.previous_covariance = result.previous_covariance;
  step.status =
      result.rms_px > m_params.nearrange.degraded_rms_px ? TrackStatus::kDegraded : TrackStatus::kTracking;
  step.pose = result.pose;
  step.covariance = result.covariance;
  step.quality = result.quality;
  m_reacquisition.stop();
}

}  // namespace visnav::nav
