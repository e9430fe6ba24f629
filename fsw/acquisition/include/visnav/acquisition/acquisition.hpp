// Acquisition: from the far-range cue (direction, rough distance) and the image, a first 6-DOF pose
// the near-range tracker converges from. A resumable state machine, one step() per frame, bounded per call:
//   searching  : score hypotheses_per_cycle (attitude grid x distance) per frame on the cue's window against
//                the coarse-spread edge evidence, keep the best search_candidates distinct ones;
//   verifying  : one frame: refine every survivor by pattern search (coarse -> fine -> raw evidence), run
//                the near-range tracker on the best `candidates` (tracker_iterations passes), keep those it
//                tracks with a low residual, ordered by the edge evidence at the tracked pose;
//   confirming : the best verified candidate must keep tracking for confirm_frames frames (else the next);
//                its best distinct rival (the next verified pose or a near-symmetric twin of it, whichever
//                scores higher) is tracked alongside and must fall rival_margin behind or lose track;
//   succeeded / failed (no target in the window, no candidate verified, none confirmed, invalid cue).
// All memory is sized in init(); start() and step() allocate nothing and throw nothing.
#pragma once

#include <cstdint>

#include "visnav/acquisition/acquisition_params.hpp"
#include "visnav/acquisition/attitude_grid.hpp"
#include "visnav/acquisition/edge_scorer.hpp"
#include "visnav/acquisition/working_image.hpp"
#include "visnav/core/stage_interfaces.hpp"  // the FarRangeSolution cue
#include "visnav/geometry/model_symmetry.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav::acq {

enum class AcquisitionState : std::uint8_t {
  kIdle,
  kSearching,
  kVerifying,
  kConfirming,
  kSucceeded,
  kFailed
};
const char* toString(AcquisitionState state);

enum class AcquisitionFailure : std::uint8_t {
  kNone,
  kInvalidCue,    ///< cue not valid, not in front of the camera, or distance not positive
  kNoTarget,      ///< the window holds no edge structure above noise (min_edge_snr)
  kNoCandidate,   ///< no refined candidate passed the tracker check
  kNotConfirmed,  ///< every verified candidate lost track during confirmation
  kAmbiguous,     ///< a distinct rival pose kept tracking as well as the best until max_confirm_frames
};
const char* toString(AcquisitionFailure failure);

struct AcquisitionResult {
  AcquisitionState state = AcquisitionState::kIdle;
  AcquisitionFailure failure = AcquisitionFailure::kNone;
  Pose pose;                       ///< the confirmed pose (succeeded) or the current candidate
  Mat6 covariance = Mat6::Zero();  ///< tracker covariance over (omega, dt) of `pose`
  double quality = 0.0;
  double rms_px = 0.0;
  std::uint32_t tracker_flags = 0;  ///< succeeded: the confirming tracker's TrackFlag bits on the last frame
  int frames = 0;                   ///< frames stepped since start()
  int hypotheses_scored = 0;        ///< this step
  int hypotheses_done = 0;          ///< since start()
  int hypotheses_total = 0;         ///< attitude grid x range steps
  int candidates_verified = 0;
  int score_evaluations = 0;  ///< this step, including refinement
  int tracker_calls = 0;      ///< this step
  double best_score = 0.0;    ///< best coarse score [brightness / working px]
  double edge_snr = 0.0;      ///< of this frame's window
  /// The candidate has a near twin too close to resolve in the image that only continuity with the look
  /// reference (setLookReference) told apart: the ambiguity is real, the choice is the track's.
  bool twin_resolved_by_continuity = false;
  /// Succeeded with confirm_follows_motion, where the candidate moved across the line of sight between its
  /// last two fits (beyond their noise): the confirmed pose on the frame before (the last confirmation
  /// frame's, or the verification's) and its covariance, whose difference from `pose` is that motion.
  bool has_previous = false;
  Pose previous_pose;
  Mat6 previous_covariance = Mat6::Zero();
};

/// A coarse-search survivor (debug view): grid attitude with its distance and lateral alignment.
struct AcquisitionCandidate {
  double score = -1.0;
  Pose pose;
  Mat3 attitude = Mat3::Identity();  ///< compared for distinctness: grid attitude R_lm, or R_c_m once refined
};

/// What the verifying tracker made of a refined candidate on its last pass (debug view): why an attempt
/// ends no_candidate (lost, or a fit over max_rms_px or under min_quality).
struct AcquisitionVerifyPass {
  TrackStatus status = TrackStatus::kLost;
  double rms_px = 0.0;
  double quality = 0.0;
  Pose pose;
};

/// A refined candidate the near-range tracker accepted (debug view).
struct AcquisitionVerified {
  double score = 0.0;  ///< two-way edge agreement (F1) at the tracked pose minus rms_weight x rms
  double rms_px = 0.0;
  double quality = 0.0;
  Pose pose;
  Mat6 covariance = Mat6::Zero();
};

class Acquisition {
 public:
  /// Allocates everything. `nearrange` configures the verifying and confirming trackers.
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const AcquisitionParams& params,
                 const NearRangeParams& nearrange);

  /// Begins a new acquisition from a cue: direction_c (unit, camera frame) and distance_m (t_c_m.z).
  void start(const Vec3& direction_c, double distance_m);
  /// The same with the direction error covered given for this start (degrees, >= 0) instead of
  /// `direction_margin_deg`: a cue from a track lost some frames ago is less certain than a far-range fix.
  void start(const Vec3& direction_c, double distance_m, double direction_margin_deg);
  void start(const FarRangeSolution& cue);
  void reset();
  /// After start(): the last valid pose of a track lost a few frames ago, and how far [rad] the target's
  /// look (attitude along its line of sight, modulo symmetries) may have moved since. A candidate whose near
  /// twin the image cannot resolve (near_twin_min_separation_px) is then not refused when its look is within
  /// that tolerance and the twin's is not: continuity chooses, and the result says so. start() and reset()
  /// clear it.
  void setLookReference(const Pose& reference, double tolerance_rad);

  /// Whether an acquisition started at `cue` would fail kNoTarget on `image` (its window's edge SNR under
  /// min_edge_snr), judged without starting one: the state is idle afterwards (reset()). `edge_snr` gets the
  /// window's SNR (0 for an invalid cue, which lacks nothing: false). For a hand-over that would fail on its
  /// first frame. Allocation-free.
  bool cueLacksEdges(const FarRangeSolution& cue, const MonoImage& image, double& edge_snr);

  /// One frame. kInvalidArgument for an image of the wrong size (the step is skipped, nothing changes).
  Status step(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out);

  AcquisitionState state() const { return m_state; }
  /// The model's symmetries and near twins (within near_twin_max_rel), found at init.
  const ModelSymmetries& symmetries() const { return m_symmetries; }
  /// The best distinct coarse hypotheses so far, best first (debug view for tests and tools).
  const BoundedBuffer<AcquisitionCandidate>& candidates() const { return m_candidates; }
  /// The refined candidates the tracker checked, best first (debug view).
  const BoundedBuffer<AcquisitionCandidate>& refined() const { return m_refined; }
  /// After verification, the verifier's pass on each of refined(), in its order (debug view; empty before).
  const BoundedBuffer<AcquisitionVerifyPass>& verifyPasses() const { return m_verify_passes; }
  /// The candidates the tracker accepted, best first (debug view).
  const BoundedBuffer<AcquisitionVerified>& verified() const { return m_verified; }
  /// The window of the last searched or verified frame (debug view).
  const WorkingImage& window() const { return m_window; }
  int hypothesisCount() const { return m_grid.size() * m_params.range_steps; }
  const AcquisitionParams& params() const { return m_params; }
  /// While confirming: whether a rival is tracked alongside the candidate, and where it is (diagnostics);
  /// the same for the candidate's depth-reversed twin.
  bool rivalAlive() const { return m_state == AcquisitionState::kConfirming && m_rival_alive; }
  const Pose& rivalPose() const { return m_rival.pose; }
  bool mirrorAlive() const { return m_state == AcquisitionState::kConfirming && m_mirror_alive; }
  const Pose& mirrorPose() const { return m_mirror_pose; }

 private:
  using Candidate = AcquisitionCandidate;
  using Verified = AcquisitionVerified;

  void fail(AcquisitionFailure failure);
  void prepareWindow(const MonoImage& image);
  /// The box-averaging factor of the window's second edge SNR for a target radius of edge_snr_radius_px (0:
  /// 1).
  int coarseSnrFactor(int edge_snr_radius_px) const;
  void search(AcquisitionResult& out);
  static void offer(BoundedBuffer<Candidate>& list, const Candidate& c, double min_angle_rad,
                    const ModelSymmetries* symmetries = nullptr);
  void verify(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out);
  bool trackCandidate(NearRangeTracker& tracker, const MonoImage& image, std::uint64_t frame_number,
                      int passes, Pose& pose, NearRangeResult& result, AcquisitionResult& out) const;
  bool acceptable(const NearRangeResult& r) const;
  void confirm(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out);
  /// A pose followed through confirmation: where it was on the last frame (with its position covariance),
  /// and its step across the line of sight since the frame before (confirm_follows_motion). `moving`: that
  /// step is motion, not the two fits' noise, and predicts the next frame.
  struct Followed {
    Pose pose;
    Mat3 position_covariance = Mat3::Zero();
    Vec3 step_m = Vec3::Zero();
    bool moving = false;
    void restart(const Pose& at, const Mat6& covariance) {
      pose = at;
      position_covariance = covariance.bottomRightCorner<3, 3>();
      step_m.setZero();
      moving = false;
    }
  };
  bool confirmStep(NearRangeTracker& tracker, const MonoImage& image, std::uint64_t frame_number,
                   Followed& followed, NearRangeResult& r, double& agreement);
  /// Sets `followed`'s step from its last pose to `fit` (this frame's), and takes `fit` as its pose.
  void followTo(Followed& followed, const NearRangeResult& fit) const;
  /// A start for `pose` on this frame from the best shift of its outline over the window's coarse evidence,
  /// within what a target can move in a frame (confirm_follows_motion). False when no shift scores.
  bool shiftedStart(const Pose& pose, Pose& start);
  void chooseRival();
  /// True when a near twin of `pose` moves the model's vertices less than near_twin_min_separation_px and
  /// the look reference does not tell the two apart; where it keeps the twin and not `pose`, `pose` becomes
  /// the twin.
  bool unresolvedNearTwin(Pose& pose);
  /// `pose`'s look is within the tolerance of the look reference (false without one).
  bool looksContinuous(const Pose& pose) const;
  double agreementF1(const Pose& pose);
  double evidenceScore(const NearRangeResult& r);
  bool bestNearTwin(const MonoImage& image, std::uint64_t frame_number, const Pose& pose, Verified& twin,
                    AcquisitionResult& out);
  void challengeByNearTwin(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out);
  /// The candidate's best depth-reversed twin (m_mirror, m_mirror_score), for chooseRival().
  void challengeByMirrorTwin(const MonoImage& image, std::uint64_t frame_number, const Verified& candidate,
                             AcquisitionResult& out);
  /// `twin`, a depth-reversed twin of `candidate` (ModelSymmetries::mirrorTwin), refitted by `tracker`: false
  /// when it is the candidate itself, shows no face, or the tracker pulls it back onto the candidate; else
  /// its score: its agreement as it stands less the refit's residual (the candidate's when the tracker lost
  /// it).
  bool mirrorTwinScore(NearRangeTracker& tracker, const MonoImage& image, std::uint64_t frame_number,
                       const Verified& candidate, const Pose& twin, double& score, AcquisitionResult& out);
  bool nextCandidate(const MonoImage& image, std::uint64_t frame_number, AcquisitionResult& out);
  template <typename T>
  static void sortBestFirst(BoundedBuffer<T>& list, std::size_t from);

  PinholeCamera m_camera;
  AcquisitionParams m_params;
  AttitudeGrid m_grid;
  WorkingImage m_window;
  EdgeScorer m_scorer;
  NearRangeTracker m_verifier;         ///< wide scanlines: larger capture range on a candidate
  NearRangeTracker m_confirmer;        ///< the flight tracker's settings: what the hand-over will meet
  NearRangeTracker m_rival_confirmer;  ///< tracks the best distinct rival alongside
  ModelSymmetries m_symmetries;
  double m_bounding_radius_m = 0.0;

  AcquisitionState m_state = AcquisitionState::kIdle;
  AcquisitionFailure m_failure = AcquisitionFailure::kNone;
  Vec3 m_cue_direction = Vec3::UnitZ();
  double m_cue_distance_m = 0.0;
  double m_target_radius_working_px = 0.0;  ///< the cue's expected target radius on the working image
  double m_min_edge_snr = 0.0;  ///< the no-target threshold for this cue (min_edge_snr or the outline cue's)
  int m_next_hypothesis = 0;
  int m_frames = 0;
  double m_best_score = 0.0;
  BoundedBuffer<Candidate> m_candidates;                 ///< search survivors, best first
  BoundedBuffer<Candidate> m_refined;                    ///< refined, best first (the tracker checks these)
  BoundedBuffer<AcquisitionVerifyPass> m_verify_passes;  ///< parallel to m_refined once verified
  BoundedBuffer<Verified> m_verified;                    ///< highest evidence first
  int m_current = 0;                                     ///< verified candidate under confirmation
  int m_confirmed = 0;
  int m_confirm_frames_run = 0;
  bool m_rival_alive = false;
  Followed m_rival;
  bool m_has_near_twin = false;  ///< m_near_twin is a near-symmetric twin of the current candidate
  Verified m_near_twin;
  int m_mirror = -1;  ///< the current candidate's best depth-reversed twin (mirrorTwin index), -1: none
  double m_mirror_score = 0.0;        ///< its score (mirrorTwinScore)
  bool m_mirror_alive = false;        ///< m_mirror's twin of the candidate keeps up (re-made every frame)
  Pose m_mirror_pose;                 ///< that twin on the last frame
  bool m_has_look_reference = false;  ///< setLookReference since start()
  Pose m_look_reference;
  double m_look_tolerance_rad = 0.0;
  bool m_twin_by_continuity = false;  ///< the current candidate's unresolvable twin was refused by continuity
  Followed m_followed;                ///< the candidate under confirmation
  Pose m_previous_pose;               ///< the candidate's confirmed pose on the frame before m_last's
  Mat6 m_previous_covariance = Mat6::Zero();
  NearRangeResult m_last;
};

}  // namespace visnav::acq
