// Per-frame verdicts of visnav-campaign (definitions: tools/campaign/README.md) and the recovery events of a
// scene. Pure functions over hand-checkable inputs, so the unit tests can build frames by hand.
#pragma once

#include <vector>

#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/navigation/nav_solution.hpp"

namespace visnav::campaign {

struct Thresholds {
  double wrong_position_rel = 0.05;  ///< of the true range |t|
  double wrong_attitude_deg = 5.0;   ///< modulo the model's symmetries
  double accurate_position_rel = 0.01;
  double accurate_attitude_deg = 1.0;
  double min_visible_px = 20.0;              ///< projected bounding-sphere diameter 2 f R / z
  double min_facing_cos = 0.17364817766693;  ///< cos 80 deg: some surface must face the camera this much
  /// Approach scenes expect a 6-DOF pose once the truth depth t_c_m.z is at most this: the near band of the
  /// scenes (5-30 m). A fixed yardstick, not read from the configuration under test (the pipeline's own
  /// hand-over distance is a parameter, derived by default from the target's size).
  double near_range_max_m = 30.0;
  /// A far-range fix is on the target when its line of sight is within the target's angular radius
  /// (bounding sphere) plus this of the line of sight to the model origin; else it is on something else.
  double far_on_target_margin_deg = 0.1;
};

/// The target is in view, whatever its size: not eclipsed, in front of the camera, its bounding sphere's
/// centre (the model origin) projects inside the image. Far range may see it from a pixel on.
bool targetInView(const PinholeCamera& camera, const Pose& truth, bool eclipsed);

/// The target can be seen: not eclipsed, in front of the camera, its bounding sphere's centre (the model
/// origin) projects inside the image, 2 f R / z >= min_visible_px, and some surface faces the camera
/// (n . line of sight < -min_facing_cos: a single-sided plate seen from behind or edge-on shows nothing).
bool targetVisible(const PinholeCamera& camera, const PolygonModel& model, const Pose& truth, bool eclipsed,
                   const Thresholds& th = {});

struct FrameOutcome {
  int frame = 0;
  bool visible = false;
  bool expected = false;  ///< visible, and a 6-DOF pose is due (near scenes; approach scenes: within 30 m)
  bool eclipsed = false;
  bool slew = false;                           ///< the line of sight jumped at this frame
  double range_m = 0.0;                        ///< |t| of the truth
  nav::NavMode mode = nav::NavMode::kStandby;  ///< the mode the frame was processed in
  bool pose_valid = false;
  std::uint32_t fault_bits = 0;
  double position_error_m = 0.0;    ///< |t_est - t_truth| (pose_valid only)
  double attitude_error_deg = 0.0;  ///< modulo symmetries (pose_valid only)
  bool has_nis = false;
  double nis = 0.0;
  double process_us = 0.0;
  bool far_valid = false;  ///< far range's fix this frame (direction/distance)
  double far_distance_m = 0.0;
  double far_eq16_distance_m = 0.0;    ///< the far fix's eq. 16 distance (far_distance_m may be the extent's)
  double far_extent_px = 0.0;          ///< the far fix's cluster extent (FarRangeResult::extent_px)
  double far_extent_distance_m = 0.0;  ///< its distance from that extent and the model's radius
  bool in_view = false;                ///< targetInView
  double far_direction_error_deg = 0.0;  ///< far_valid: its line of sight against the model origin's
  bool far_off_target = false;  ///< in_view, far_valid, and the fix beyond far_on_target_margin_deg (above)
  // The 6-DOF measurement the pipeline produced this frame, delivered or withheld (diagnostics: --frames).
  // A coasted prediction is not one. Lets an output gate be judged offline over a whole campaign.
  bool has_candidate = false;
  double candidate_position_error_m = 0.0;
  double candidate_attitude_error_deg = 0.0;  ///< modulo symmetries
  double attitude_sigma_deg = 0.0;            ///< sqrt(trace) of the candidate's attitude covariance
  double position_sigma_rel = 0.0;            ///< sqrt(trace) of its position covariance / range
  std::uint32_t near_flags = 0;               ///< the near-range tracker's flags (0 when it did not run)
  std::uint32_t withheld = 0;                 ///< NavSolution::withheld: why a computed pose was not valid
  /// The near-range fit's NearRangeResult::systematic_gain and CovarianceTerms (0 where none): a replay of
  /// [nearrange] line_end_bias_px rescales attitude_sigma_deg by them.
  double systematic_gain = 0.0;
  double cov_residual_factor = 0.0;
  double cov_vertex_factor = 0.0;
  double cov_bias_factor_per_px2 = 0.0;
  double cov_interior_factor_per_px2 = 0.0;  ///< CovarianceTerms::interior_factor_per_px2
  double cov_narrow_factor_per_px2 = 0.0;    ///< CovarianceTerms::narrow_factor_per_px2
  int lines_used = 0;
  int lines_total = 0;
  int scanlines = 0;           ///< scanlines the tracker cast on its selected edges
  int inlier_points = 0;       ///< edge points on its fitted lines
  bool evidence_good = false;  ///< nav::imageEvidenceGood of the tracker's result (false when it did not run)
  bool reacquired = false;     ///< the candidate came from close-range reacquisition
  int symmetric_twins = 0;  ///< NavSolution::symmetric_twins: attitudes the image cannot tell apart (valid)
  bool shows_face = true;   ///< the candidate showed a face (NavigationPipeline::lastPoseShowedAFace)
  bool twin_by_continuity = false;  ///< NavSolution::twin_by_continuity
  bool kept_branch = false;         ///< NavigationPipeline::lastFitKeptTheBranch
  bool mirror_resolved = false;     ///< NavigationPipeline::lastMirrorResolved
  bool near_twin_rival = false;     ///< NavigationPipeline::lastNearTwinRival
  bool find_on_branch = true;       ///< a find (reacquired) that confirmed the branch: lastFindOnKnownBranch
  /// The candidate's distance |t| (has_candidate), for range-continuity replays.
  double candidate_range_m = 0.0;
  bool jumped = false;        ///< NavigationPipeline::lastPoseJumped
  bool range_broken = false;  ///< NavigationPipeline::lastFitBrokeRange
  /// --oracle (or --trace), on a visible frame without a valid pose: what a near-range tracker started at
  /// the truth makes of this image. -1 not asked, 0 no fit the pipeline would take (lost, or image evidence
  /// too weak: nav::imageEvidenceGood), 1 a fit, but wrong or not certain enough
  /// to be valid, 2 a right and certain fit: the image supports the pose, the frame was lost by the search
  /// or the gates. 0 and 1 are the image's (or the tracker's measurement's) limits.
  int oracle = -1;
  /// With `oracle` >= 0: the first image-evidence test that fit fails (nav::EvidenceVerdict as int, 0: it
  /// passes them all); -1 not asked. Says why the image does not support a frame with `oracle` 0.
  int oracle_evidence = -1;
  bool pose_filtered = false;  ///< NavigationPipeline::lastPoseFiltered ([navigation] deliver_filtered_pose)
  /// NavigationPipeline::lastFitAttitudeSigmaDeg: the near-range fit's own 1-sigma, before the filter
  double fit_attitude_sigma_deg = 0.0;
  bool narrow_break = false;  ///< NavigationPipeline::lastFollowedNarrowBreak
  // Verdicts (classifyFrame).
  bool wrong = false;
  bool tracked = false;
  bool accurate = false;
};

/// A pose this far off is wrong: position error > wrong_position_rel of the range (a range <= 0 counts as
/// wrong) or attitude error > wrong_attitude_deg.
bool poseErrorIsWrong(double position_error_m, double range_m, double attitude_error_deg,
                      const Thresholds& th);

/// Sets wrong / tracked / accurate from pose_valid, mode, range and the errors:
///   wrong    = pose_valid and (position error > 5 % of range or attitude error > 5 deg)
///   tracked  = pose_valid and mode near range or acquisition, and not wrong
///   accurate = tracked and position error <= 1 % of range and attitude error <= 1 deg
void classifyFrame(FrameOutcome& f, const Thresholds& th = {});

enum class EventKind { kSlew = 0, kEclipseEnd, kReappear, kLoss };
constexpr int kEventKindCount = 4;
const char* toString(EventKind kind);

struct RecoveryEvent {
  EventKind kind = EventKind::kLoss;
  int frame = 0;     ///< the event's frame index
  int latency = -1;  ///< frames from the event to the next tracked frame (0: tracked at once); -1: never
};

/// Recovery events of a scene, in frame order, at most one per frame (priority slew, eclipse end, reappear,
/// loss):
///   slew        the slew frame;
///   eclipse end the first non-eclipsed frame after an eclipse, when it is visible (else the next visible
///   one); reappear    a visible frame after a non-visible one (other causes: out of view, back side), once
///   some
///               frame was tracked (or `tracked_at_start`: near scenes start from a given pose);
///   loss        a visible frame not tracked right after a tracked frame (frame 0: after the given start
///               pose, when `tracked_at_start`).
/// Latency: frames from the event to the first tracked frame at or after it; -1 when the scene ends first.
std::vector<RecoveryEvent> recoveryEvents(const std::vector<FrameOutcome>& frames, bool tracked_at_start);

}  // namespace visnav::campaign
