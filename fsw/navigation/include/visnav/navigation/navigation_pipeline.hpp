// The pipeline of architecture.md: per frame the mode manager calls exactly one estimator (far range,
// acquisition or near range), then the Kalman filter, then FDIR, and returns a NavSolution. Replay, tests
// and the daemon run this same object; only the camera and the clock differ. All memory is sized in init();
// process() allocates nothing, throws nothing and is bounded (acquisition spreads its search over cycles).
#pragma once

#include <array>
#include <cstdint>

#include "visnav/acquisition/acquisition.hpp"
#include "visnav/core/frame.hpp"
#include "visnav/farrange/far_range_estimator.hpp"
#include "visnav/navigation/fdir_monitor.hpp"
#include "visnav/navigation/local_reacquisition.hpp"
#include "visnav/navigation/mode_manager.hpp"
#include "visnav/navigation/nav_solution.hpp"
#include "visnav/navigation/navigation_params.hpp"
#include "visnav/navigation/pose_filter.hpp"
#include "visnav/navigation/track_branch.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav::nav {

struct PipelineParams {
  NavigationParams navigation;
  NearRangeParams nearrange;
  far::FarRangeParams farrange;
  acq::AcquisitionParams acquisition;
  PoseFilterParams filter;
};

class NavigationPipeline {
 public:
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const PipelineParams& params);
  /// Per-stage timing source (CLOCK_MONOTONIC in flight; nullptr reports zero timings, as replay does for
  /// bit-identical output).
  void setClock(MonotonicClockNs clock);
  /// The camera's nominal frame period (from its configured rate), which the frame-age check allows for
  /// until two exposures have measured it. 0 (the default): no allowance before then.
  void setNominalFramePeriodNs(std::int64_t period_ns) { m_nominal_frame_period_ns = period_ns; }
  /// Enters near range from a known pose (replay with an initial pose, tests), bypassing acquisition.
  void startNearRange(const Pose& pose, std::uint64_t frame_number);

  /// One cycle. `frame` nullptr: the camera delivered nothing (counted, the filter coasts). `now_ns` is the
  /// cycle time on the executive's clock (simulated in replay), used for the frame-age check.
  Status process(const Frame* frame, std::int64_t now_ns, NavSolution& out);
  /// Ground command, validated and acknowledged (also in the health record).
  bool command(ModeCommandKind kind, std::uint32_t command_id, std::uint64_t frame_number, CommandAck& ack);
  /// Health record: mode, faults, counters, last transition, last command (task timing is the executive's).
  void fillHealth(HealthRecord& health) const;

  NavMode mode() const { return m_modes.mode(); }
  const ModeManager& modes() const { return m_modes; }
  const NearRangeTracker& nearRange() const { return m_near; }
  const NearRangeResult& lastNearRange() const { return m_near_result; }
  const far::FarRangeEstimator& farRange() const { return m_far; }
  const far::FarRangeResult& lastFarRange() const { return m_far_result; }
  const PoseFilter& filter() const { return m_filter; }
  /// Where the next frame's tracker (or reacquisition search) starts: the filter's prediction once it knows
  /// the attitude, else the last trusted pose.
  Pose predictedPose() const;
  /// The last pose the pipeline trusted (delivered, valid or not).
  const Pose& lastTrustedPose() const { return m_last_pose; }
  /// This frame's 6-DOF measurement update of the filter (near range): `dof` 0 when there was none (no pose,
  /// or the filter was (re)started from it). Its `nis` is what the innovation gate judged.
  const FilterUpdate& lastPoseUpdate() const { return m_last_pose_update; }
  /// Close-range reacquisition (searching while active()).
  const LocalReacquisition& reacquisition() const { return m_reacquisition; }
  /// This frame's reacquisition step (`hypotheses` 0 when none ran).
  const ReacquisitionStep& lastReacquisition() const { return m_reacquisition_step; }
  /// The acquisition mode's step of the last frame (state kIdle when the frame was not in that mode).
  const acq::AcquisitionResult& lastAcquisition() const { return m_acquisition_result; }
  const acq::Acquisition& acquisition() const { return m_acquisition; }
  /// Whether this frame's 6-DOF pose, delivered or withheld, showed a face (max_valid_view_angle_deg); true
  /// when there was none. For the campaign's offline gate replay.
  bool lastPoseShowedAFace() const { return m_pose_showed_face; }
  /// Whether the last frame's near-range fit met the branch continuity rule (keptTheBranch), whatever the
  /// branch's state: what tools/campaign/gate_replay.py replays.
  bool lastFitKeptTheBranch() const { return m_fit_kept_the_branch; }
  /// Whether the last frame's near-range fit had a near-twin rival the branch rule counted (the tracker's
  /// kFlagNearTwinRival, unless continuity with the last valid or the start pose's look chose): for the
  /// gate replay.
  bool lastNearTwinRival() const { return m_near_twin_rival; }
  /// Whether the last frame's depth-mirrored rival (kFlagAmbiguous) was resolved by the prediction and so
  /// no rival ([navigation] mirror_resolved_by_prediction): for the gate replay.
  bool lastMirrorResolved() const { return m_mirror_resolved; }
  /// Whether the last frame's pose is the filter's estimate after its fit ([navigation]
  /// deliver_filtered_pose), not the fit as measured.
  bool lastPoseFiltered() const { return m_pose_filtered; }
  /// The last frame's near-range fit's own attitude 1-sigma [deg] (its covariance with its systematic gain,
  /// before the filter; 0 when no near-range pose was delivered or withheld): what
  /// narrow_break_max_fit_attitude_sigma_deg judged, for the gate replay.
  double lastFitAttitudeSigmaDeg() const { return m_fit_attitude_sigma_deg; }
  /// Whether the last frame followed a break in which a near-range fit beside a narrow strip was withheld
  /// (narrow_break_reconfirms, narrow_break_max_fit_attitude_sigma_deg), as the pipeline judged it: for the
  /// gate replay.
  bool lastFollowedNarrowBreak() const { return m_followed_narrow_break; }
  /// Whether the last find (lastReacquisition().found) continued a branch a valid pose kept and so confirmed
  /// it (find_confirms_only_from_reference): for the gate replay.
  bool lastFindOnKnownBranch() const { return m_find_on_known_branch; }
  /// Tracks handed to their near twin (follow_near_twin) since init.
  std::uint64_t nearTwinsFollowed() const { return m_near_twins_followed; }
  /// Whether the last frame's near-range pose was withheld as a disputed jump (disputed_max_look_change_deg).
  bool lastPoseJumped() const { return m_pose_jumped; }
  /// Whether this frame's fit left the range the last valid pose predicts after a jump
  /// (branch_range_after_jump).
  bool lastFitBrokeRange() const { return m_range_broken; }
  /// branch_range_after_jump's test of a fit's range `range_m` against the last valid pose's, `frames` frames
  /// later: true when it is outside the span from the reference's range `reference_m` (standing still) to
  /// that range carried on at its rate (`carried_m`) by more than disputed_max_range_change_rel, widened
  /// by branch_range_growth_rel_per_frame per frame and by three of the carried range's 1-sigma
  /// `expected_sigma_m`, relative to the span's nearest end.
  static bool rangeLeftTheReference(const NavigationParams& nav, std::uint64_t frames, double range_m,
                                    double reference_m, double carried_m, double expected_sigma_m);

 private:
  void runFarRange(const MonoImage& image, NavSolution& out, ModeInputs& in);
  /// check_cue_before_handover: when this frame's far-range fix would be handed over, whether acquisition
  /// would find edge structure at it; if not, the fix is refuted and in.cue_lacks_edges set.
  void checkCueBeforeHandOver(const MonoImage& image, ModeInputs& in);
  void runAcquisition(const MonoImage& image, std::uint64_t frame_number, NavSolution& out, ModeInputs& in);
  /// acquire_beside_far_range: an acquisition beside far range started (from the last far fix) or ended
  /// without a pose (far range restarts unless the failure left its track).
  void acquisitionBesideFarRange(bool started);
  void runNearRange(const MonoImage& image, std::uint64_t frame_number, NavSolution& out, ModeInputs& in);
  void coast(NavSolution& out);
  bool closeRange() const;
  /// `covariance`: the fit's, as the filter takes it; x systematic_gain (NearRangeResult) for the user and
  /// the validity checks.
  void deliver(const Pose& pose, const Mat6& covariance, double quality, NavSolution& out,
               bool doubted = false, double systematic_gain = 1.0);
  /// The last word on validity: a pose is valid only while the track's mirror branch is known
  /// (track_branch.hpp).
  void confirmBranch(NavMode processed_in, NavSolution& out);
  /// follow_near_twin: after confirmBranch, an unconfirmed fit that lost lines to a near twin that fits
  /// them as well hands the track to the twin when the twin, tracked on the same image, finds more lines.
  void followNearTwin(NavMode processed_in, const MonoImage& image, const NavSolution& out);
  /// Restarts the filter on a pose the image vouches for against it: from three poses when the two frames
  /// before delivered one each (PoseFilter::initialiseFromThree), else from this one.
  void restartFilter(const Pose& pose, const Mat6& covariance);
  bool fuseNearRange(const NearRangeResult& r, NearRangeCheck& check);
  void startReacquisition(const MonoImage& image, std::uint64_t frame_number, NavSolution& out,
                          ModeInputs& in);
  void runReacquisition(const MonoImage& image, std::uint64_t frame_number, NavSolution& out, ModeInputs& in);
  /// After an unsuccessful searched frame: the filter's rates fade (reacquire_motion_decay_s).
  void fadeSearchRates();
  /// Restarts the filter from a reacquisition's confirmation: its last two frames give the velocity.
  void startFilterFromReacquisition(const ReacquisitionStep& step);
  /// A find may confirm the track's branch: a valid pose (or the start pose) kept one, and the find's look
  /// agrees with it (find_confirms_only_from_reference). A find that agrees with that pose carried by the
  /// filter's motion alone (findContinuesPrediction) is on it too; runReacquisition asks both.
  bool findOnKnownBranch(const Pose& found) const;
  /// The filter's state is the branch reference's, propagated by its motion model only: no measurement
  /// and no restart since (PoseFilter::measurementEpoch).
  bool predictionCarriesReference() const;
  /// That carried prediction holds and `found`'s look is within find_prediction_look_deg of it. Judged
  /// before the find restarts the filter.
  bool findContinuesPrediction(const Pose& found) const;
  /// After reacquire_acquisition_after_frames of local search: the acquisition, idle in near range,
  /// searches too, cued by the prediction; its find is delivered as the step's.
  void runCloseRangeAcquisition(const MonoImage& image, std::uint64_t frame_number, ReacquisitionStep& step);
  /// The line of sight of the next tile over the searched disc (reacquire_acquisition_tiles), at most
  /// kMaxTileRings rings of tiles round the prediction.
  static constexpr int kMaxTileRings = 32;
  Vec3 nextAcquisitionTile(const Vec3& predicted_direction, double spacing_px, double radius_px);
  /// The factor on the prediction's range for the next prediction-cued attempt (reacquire_range_ladder):
  /// 1 on every other attempt, on the others the next of the rungs (1 + range_span_rel)^2 nearer and
  /// farther in turn, nearest first, those whose range lies between the model's bounding radius and
  /// far_range_above_m. At most kMaxRangeRungs each way.
  static constexpr int kMaxRangeRungs = 16;
  double nextAcquisitionRangeFactor(double range_m);
  /// The range the track's range rate (kept by startReacquisition) reached since the search began, from the
  /// prediction's `predicted_range_m`, within the target's bounding radius and far_range_above_m; 0 when
  /// there is no rate or that range is within reacquire_range_tolerance_rel of the prediction's.
  double rateRungRange(double predicted_range_m) const;
  /// The filter's rate is a validated track's (reacquire_rate_rung_valid_track_only): the last valid pose
  /// closed a run of branch_range_reference_min_frames valid poses and the filter was not restarted since.
  bool rateFromValidTrack() const;
  /// This search frame starts at the filter's position when the search began, with the prediction's
  /// attitude (reacquire_motion_hedge): the prediction has moved more than a find's range tolerance from it.
  bool motionHedge(const Pose& predicted) const;
  void enterMode(NavMode mode);
  bool centreInImage(const Pose& pose) const;
  /// After a break of at most branch_continuity_frames: this near-range fit is clean, certain and kept the
  /// last valid pose's look (confirms the branch); after a longer one, up to
  /// branch_continuity_spotless_frames, only a spotless fit (no tracker flag but the texture fallback) does.
  bool keptTheBranch(const Pose& pose, const Mat6& covariance) const;
  /// This frame's near-range fit is degraded only by at most `allowed` selected lines it did not find
  /// (branch_continuity_missing_lines); false when `allowed` <= 0.
  bool onlyLinesMissing(int allowed) const;
  /// After a disputed jump: whether `pose` left the range the last valid pose predicts
  /// (branch_range_after_jump).
  bool fitLeftTheValidRange(const Pose& pose) const;
  /// Keeps the last valid pose's range and rate, and starts the range check after a disputed jump.
  void noteRangeReference(const NavSolution& out);
  /// Some surface of the model faces the camera within [navigation] max_valid_view_angle_deg on `pose`.
  bool showsAFace(const Pose& pose) const;
  /// Fills out.symmetric_twins and out.twin_by_continuity for a valid pose.
  void flagTwins(NavSolution& out) const;

  PinholeCamera m_camera;
  PipelineParams m_params;
  double m_max_view_cos = 1.0;         ///< cos of [navigation] max_valid_view_angle_deg; 1: the check is off
  bool m_pose_showed_face = true;      ///< lastPoseShowedAFace()
  bool m_fit_kept_the_branch = false;  ///< lastFitKeptTheBranch()
  bool m_pose_filtered = false;        ///< lastPoseFiltered()
  double m_fit_attitude_sigma_deg = 0.0;  ///< lastFitAttitudeSigmaDeg()
  bool m_followed_narrow_break = false;   ///< lastFollowedNarrowBreak()
  bool m_near_twin_rival = false;         ///< lastNearTwinRival()
  bool m_mirror_resolved = false;         ///< lastMirrorResolved()
  bool m_pose_jumped = false;             ///< lastPoseJumped()
  /// The track began with a find that chose between unresolvable near twins by continuity (flagTwins).
  bool m_track_twin_by_continuity = false;
  bool m_acquisition_awaits_near = false;  ///< acquisition_awaits_near_range: the next frame may confirm it
  bool m_far_track_kept = false;           ///< far_track_survives_unconfirmed: the next far range goes on
  MonotonicClockNs m_clock = nullptr;
  ModeManager m_modes;
  FdirMonitor m_fdir;
  PoseFilter m_filter;
  NearRangeTracker m_near;
  NearRangeTracker m_twin_probe;  ///< followNearTwin's second look, from the twin (same parameters)
  far::FarRangeEstimator m_far;
  acq::Acquisition m_acquisition;
  LocalReacquisition m_reacquisition;

  NearRangeResult m_near_result;
  ReacquisitionStep m_reacquisition_step;
  acq::AcquisitionResult m_acquisition_result;
  FilterUpdate m_last_pose_update;
  far::FarRangeResult m_far_result;
  FarRangeSolution m_last_far_fix;  ///< last valid far-range solution (cue for acquisition)
  Pose m_last_pose;                 ///< last trusted 6-DOF pose
  bool m_have_pose = false;
  /// The last two poses delivered on a frame (restartFilter), the newest at m_delivered_newest: exposure 0
  /// when none. As measured: where the filter's estimate was delivered (lastPoseFiltered), its fit.
  struct DeliveredPose {
    Pose pose;
    Mat6 covariance = Mat6::Identity();
    std::int64_t exposure_ns = 0;
  };
  std::array<DeliveredPose, 2> m_delivered{};
  unsigned m_delivered_newest = 0;
  int m_coasted = 0;                     ///< consecutive near-range frames the prediction filled in
  bool m_next_attempt_far_cued = false;  ///< the close-range acquisition's cues alternate (reacquire_far_cue)
  int m_acquisition_tile = 1;            ///< the next spiral cell (reacquire_acquisition_tiles)
  bool m_acquisition_tile_turn = false;  ///< they alternate between the prediction and the next tile
  int m_acquisition_rung = 0;            ///< the next rung of the range ladder (reacquire_range_ladder)
  bool m_acquisition_rung_turn = false;  ///< its attempts alternate between the prediction and the next rung
  double m_search_range_rate_m_s = 0.0;  ///< the track's range rate the search's prediction dropped (0: none)
  std::int64_t m_search_start_exposure_ns = 0;  ///< the search's first frame
  bool m_search_rate_turn = false;  ///< this frame's local search starts at rateRungRange (alternates)
  Vec3 m_search_start_t_c_m = Vec3::Zero();  ///< the filter's position when the search began (motion hedge)
  bool m_acquisition_rate_turn = false;  ///< the next prediction-cued acquisition attempt does (alternates)
  /// The track began with a reacquisition's find and none of its poses has yet met
  /// doubted_max_attitude_sigma_deg: its near-range poses are doubted.
  bool m_track_doubted = false;
  /// Fits after the operator's start pose still judged against it (start_pose_doubt_fits).
  int m_start_fits_pending = 0;
  /// The last near-range fit overruled the filter's innovation gate and restarted it
  /// (doubt_after_filter_restart); cleared by the next frame.
  bool m_fit_restarted_filter = false;
  /// This frame's near-range fault bits (checkNearRange), 0 on a frame not processed in near range.
  std::uint32_t m_near_range_faults = 0U;
  /// The last valid pose's range and range rate (the filter's) and exposure time; after a disputed jump
  /// (branch_range_after_jump) a fit's range is checked against them until a pose is valid again.
  double m_valid_range_m = 0.0;
  double m_valid_range_rate_mps = 0.0;
  double m_valid_range_sigma_m = 0.0;         ///< the filter's 1-sigma of that range
  double m_valid_range_rate_sigma_mps = 0.0;  ///< the filter's 1-sigma of that rate along the line of sight
  std::int64_t m_valid_exposure_ns = 0;
  bool m_have_valid_range = false;  ///< the last valid pose closed a run of branch_range_reference_min_frames
  int m_valid_run = 0;              ///< consecutive valid poses up to this frame
  bool m_range_check_active = false;
  bool m_range_broken = false;              ///< lastFitBrokeRange()
  int m_doubt_clear_run = 0;                ///< consecutive poses of a doubted track within the doubted limit
  bool m_find_confirms_branch = false;      ///< doubt_clear_frames > 1: the find's branch waits for its doubt
  std::uint64_t m_near_twins_followed = 0;  ///< nearTwinsFollowed()
  NearRangeResult m_twin_probe_result;      ///< followNearTwin's (a member: no large frame on the stack)
  bool m_find_on_known_branch = false;  ///< the find continues a branch a valid pose kept (findOnKnownBranch)
  Pose m_last_valid_pose;               ///< the last pose delivered as valid
  std::uint64_t m_frames_since_valid = ~0ULL;  ///< frames since then (~0: none yet)
  bool m_narrow_break = false;  ///< since then a near-range fit beside a narrow strip was withheld
  /// What continuity tells a near twin apart by (confirmBranch): the last valid pose, or the operator's start
  /// pose when none was valid since it, and the frames since (~0: neither).
  Pose m_branch_reference_pose;
  std::uint64_t m_frames_since_branch_reference = ~0ULL;
  std::uint64_t m_reference_filter_epoch = 0;  ///< the filter's measurementEpoch() after that reference
  std::uint64_t m_reference_track_epoch = 0;   ///< and its trackEpoch(): no restart since, while equal
  /// This frame's near-range fit was ambiguous: its mirrored rival's NIS against the filter's prediction
  /// (before the update), -1 otherwise (mirror_resolved_by_prediction).
  double m_mirror_nis = -1.0;
  TrackBranch m_branch;  ///< whether the track's mirror branch is known (the last word on validity)
  bool m_have_last_exposure = false;
  std::int64_t m_last_exposure_ns = 0;
  std::int64_t m_previous_exposure_ns = 0;  ///< the frame before the last one (0: none)
  std::uint64_t m_frames_processed = 0;
  std::int64_t m_nominal_frame_period_ns = 0;
  std::uint64_t m_cycles = 0;             ///< process() calls: NavSolution::cycle_number
  std::uint64_t m_last_frame_number = 0;  ///< camera sequence of the last frame processed
  CommandAck m_last_command;
};

}  // namespace visnav::nav
