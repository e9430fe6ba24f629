// FDIR monitor (issue 3): per-frame checks of the near-range measurement (edge-point inlier ratio, usable
// lines, LM residual and convergence, innovation against the Kalman prediction, range and image bounds)
// and of the frame itself (age). Faults are counted per bit; a near-range fault held for
// fault_persistence_frames consecutive frames asks the pipeline to drop the track. An innovation fault on a
// measurement with good image evidence is flagged but does not count towards that persistence: the filter,
// not the image, is then wrong. Pure logic.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/geometry/polygon_model.hpp"
#include "visnav/navigation/nav_solution.hpp"
#include "visnav/navigation/navigation_params.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav::nav {

struct NearRangeCheck {
  const NearRangeResult* near = nullptr;  ///< required
  bool innovation_checked = false;        ///< a filter prediction existed to compare with
  bool innovation_accepted = true;        ///< the filter's NIS gate
  bool centre_in_image = true;            ///< the estimated target centre projects inside the image
  bool evidence_good = false;             ///< the image supports the measurement (imageEvidenceGood)
};

/// Lines, inliers, residual and edge support of a near-range measurement all say the image holds the
/// model where the tracker put it, the pose came from intersected vertices (eq. 7), not from the
/// point-to-line fallback, and its own covariance is within the delivery limits
/// (`max_valid_attitude_sigma_deg`, `max_valid_position_sigma_rel`). Such a measurement wins over a filter
/// that rejects it; close-range reacquisition takes a start or a confirmation only on it.
/// `continues_rival_free_fit`: the fit continues one that had no depth-mirrored rival (a confirmation of a
/// reacquisition's candidate): a rival that fits as well (kFlagAmbiguous) is then told apart by that
/// continuity, as a track's is (track_branch.hpp), and does not count against the evidence.
bool imageEvidenceGood(const NearRangeResult& r, const NavigationParams& params,
                       bool continues_rival_free_fit = false);

/// Which of imageEvidenceGood's tests a measurement fails first, in the order it applies them (kGood: none).
/// The campaign's oracle counts the frames the image does not support by it (tools/campaign/README.md).
enum class EvidenceVerdict : std::uint8_t {
  kGood = 0,
  kLost,          ///< no fit: the tracker lost the target
  kNoCorners,     ///< point-to-line fallback (kFlagResidualFallback): too few corners for eq. 7
  kMirrorRival,   ///< a depth-mirrored rival fits as well (kFlagAmbiguous)
  kFewLines,      ///< min_usable_lines / evidence_min_line_fraction
  kFewInliers,    ///< evidence_min_inlier_ratio
  kHighResidual,  ///< evidence_max_rms_px
  kWeakSupport,   ///< evidence_min_edge_support
  kUncertain,     ///< its own 1-sigma above max_valid_attitude_sigma_deg / max_valid_position_sigma_rel
};
constexpr int kEvidenceVerdictCount = 9;
const char* toString(EvidenceVerdict verdict);
EvidenceVerdict imageEvidenceVerdict(const NearRangeResult& r, const NavigationParams& params,
                                     bool continues_rival_free_fit = false);

/// A near-range fit the navigation doubts (fsw/navigation/README.md, "Certain enough to deliver"): the
/// filter's innovation gate rejected it (`faults` has kFaultInnovation), it used fewer than
/// `doubt_min_line_fraction` of its selected lines or left out any of at most `doubt_every_line_up_to` (it
/// rests on part of the outline), or a tracked face was seen as a narrow strip beside its lines
/// (kFlagNarrowFace, with `doubt_narrow_face`). Such a pose is valid only within
/// `doubted_max_attitude_sigma_deg`: its covariance knows the noise, not the bias.
bool nearFitDoubted(const NearRangeResult& r, std::uint32_t faults, const NavigationParams& params);

/// A fit that ends the track on its frame (`break_nis_chi2`, 0: never): its image evidence is not good, it
/// used fewer than `break_max_line_fraction` of its selected lines and the filter rejected it at an NIS
/// (`nis`) above `break_nis_chi2`. Such a fit says the target is not where the track predicts (a slew):
/// searching from the prediction now beats coasting on such fits until the tracker gives up.
bool nearFitBreaksTrack(const NearRangeCheck& check, double nis, const NavigationParams& params);

/// The most lines a minimal near-range fit uses: 4 lines give 4 vertices for 6 unknowns, so one displaced
/// line is absorbed by the attitude instead of showing in the residual.
constexpr int kMinimalFitLines = 4;
/// A minimal fit (at most kMinimalFitLines lines) whose pose predicts more than
/// `minimal_fit_max_missing_lines` selected lines the image did not give: tracked, never valid.
bool minimalFitMissesOutline(const NearRangeResult& r, const NavigationParams& params);

/// A pose known to `max_valid_attitude_sigma_deg` and `max_valid_position_sigma_rel` by `covariance` (each
/// limit 0: not checked): what validity asks of an undoubted pose, and image evidence of its fit.
bool withinValidSigmas(const Pose& pose, const Mat6& covariance, const NavigationParams& params);

/// A near-range fit whose error is mostly its own noise: every selected line found and no tracked face seen
/// as a narrow strip beside its lines (kFlagNarrowFace). A partial fit leans on fewer lines the same way
/// frame after frame, so its error repeats and a filter averaging it only hides it
/// (`[navigation] deliver_filtered_pose`).
bool fitIsComplete(const NearRangeResult& r);

/// A near-range fit whose pose may be delivered as the filter's estimate after it (`[navigation]
/// deliver_filtered_pose`, when the filter accepted it and it is certain on its own): a complete fit, or with
/// `deliver_filtered_partial_fit` a partial fit its lines do not doubt (fitDoubtedByItsLines) without a face
/// seen as a narrow strip (kFlagNarrowFace), whose two steps the tracker cannot tell apart, on a track not
/// `find_doubted` (it began with a reacquisition's find whose doubt no pose has cleared yet).
bool fitMayBeFiltered(const NearRangeResult& r, const NavigationParams& params, bool find_doubted);

/// The first near-range fit after an acquisition may confirm the acquisition's branch (`[navigation]
/// acquisition_awaits_near_range`): with `handover_needs_whole_outline`, not when it measured only the
/// outline (kFlagSilhouetteOnly) and missed a selected line (kFlagLineRejected), what a turned pose whose
/// outline matches leaves. Rival-freedom and the filter are judged by the caller.
bool fitConfirmsHandOver(const NearRangeResult& r, const NavigationParams& params);

/// The part of nearFitDoubted that is the fit's lines: fewer used than `doubt_min_line_fraction` of those
/// selected, or any unused of at most `doubt_every_line_up_to`.
bool fitDoubtedByItsLines(const NearRangeResult& r, const NavigationParams& params);

class FdirMonitor {
 public:
  /// The model and `focal_px` derive the plausibility limits the parameters leave 0: below, the camera
  /// inside the model's bounding box (in the model frame); above, the depth where the target spans 4 px.
  void init(const NavigationParams& params, const PolygonModel& model, double focal_px);
  /// The configured lower end of the depth band (0: the model's box is the limit instead).
  double minDepthM() const { return m_min_depth_m; }
  double maxDepthM() const { return m_max_depth_m; }
  /// The camera centre of `pose` lies inside the model's bounding box: no pose of a real target puts it
  /// there.
  bool cameraInsideTarget(const Pose& pose) const;
  /// Clears the consecutive-fault count (after a mode change); cumulative counters stay.
  void resetPersistence() { m_consecutive = 0; }

  /// Checks one near-range frame; returns the fault bits raised and records them.
  std::uint32_t checkNearRange(const NearRangeCheck& check);
  /// Frame-level check, any mode: kFaultFrameAge when the frame is older than `frame_period_ms` (the
  /// camera's, 0 when not known yet) plus max_frame_latency_ms.
  std::uint32_t checkFrameAge(double age_ms, double frame_period_ms);
  /// Records faults found elsewhere (no frame, far range without target, acquisition failure, slips).
  void raise(std::uint32_t bits);
  /// Ends the frame: the bits raised since the last endFrame() become the active set.
  std::uint32_t endFrame();

  bool faultPersisted() const { return m_consecutive >= m_params.fault_persistence_frames; }
  int consecutiveFaultFrames() const { return m_consecutive; }
  std::uint32_t activeFaults() const { return m_active; }
  const std::array<std::uint32_t, kFaultBitCount>& faultCounts() const { return m_counts; }

 private:
  NavigationParams m_params;
  double m_min_depth_m = 0.0;
  double m_max_depth_m = 0.0;
  Vec3 m_box_min_m = Vec3::Zero();  ///< the model's axis-aligned bounding box, model frame
  Vec3 m_box_max_m = Vec3::Zero();
  std::uint32_t m_pending = 0;
  std::uint32_t m_active = 0;
  int m_consecutive = 0;
  std::array<std::uint32_t, kFaultBitCount> m_counts{};
};

}  // namespace visnav::nav
