// Scores a replay against truth: per-frame errors, worst-case envelopes, far-range direction/distance errors,
// the mode timeline, summary and requirement checks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/eval/envelope.hpp"
#include "visnav/eval/metrics.hpp"
#include "visnav/eval/replay_csv.hpp"

namespace visnav::eval {

struct TruthPose {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  Pose pose;  ///< T_c_m
};

struct FrameRecord {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  double distance_m = 0.0;  ///< truth t_c_m.z
  TrackStatus status = TrackStatus::kMissing;
  bool scored = false;  ///< tracked row with a pose: errors below are meaningful
  AxisValues error{};   ///< estimate - truth [m | deg]
  double attitude_error_deg = 0.0;
  std::vector<FrameEnvelope> envelopes;    ///< one per envelope size; invalid when not computed (stride)
  std::vector<std::uint8_t> inside;        ///< per envelope size: scored and |error| <= envelope on all axes
  ReplayMode mode = ReplayMode::kUnknown;  ///< of the replay row (kUnknown: no row or no mode column)
  bool far_scored = false;                 ///< the row has far_valid = 1: far_error is meaningful
  FarRangeError far_error{};               ///< direction [deg], signed distance [%] (metrics.hpp)
};

/// One change of the replay's mode between consecutive truth frames that have a mode.
struct ModeChange {
  std::int64_t frame = 0;  ///< first frame in the new mode
  ReplayMode from = ReplayMode::kUnknown;
  ReplayMode to = ReplayMode::kUnknown;
};

struct EnvelopeSummary {
  double delta_px = 0.0;
  int frames_with_envelope = 0;  ///< denominator of the inside fraction
  int inside_count = 0;
  double inside_fraction = 0.0;
  AxisValues max_envelope{};
  int failed_solves = 0;
};

struct EvaluationSummary {
  int frames_evaluated = 0;  ///< truth frames
  int frames_tracking = 0;
  int frames_degraded = 0;
  int frames_lost = 0;       ///< status lost
  int frames_missing = 0;    ///< no replay row
  int frames_init = 0;       ///< status init: not scored, not a loss
  int track_loss_count = 0;  ///< lost + missing
  int unmatched_replay_rows = 0;
  std::array<ErrorStats, kAxisCount> axes{};
  ErrorStats attitude{};
  std::vector<EnvelopeSummary> envelopes;
  ErrorStats far_direction_deg{};                   ///< over the far_scored frames
  ErrorStats far_distance_pct{};                    ///< |distance error| [%] over the far_scored frames
  bool has_modes = false;                           ///< the replay has a mode column
  std::array<int, kReplayModeCount> mode_frames{};  ///< truth frames per mode (ReplayMode order)
  std::vector<ModeChange> transitions;              ///< in frame order
  ReplayMode final_mode = ReplayMode::kUnknown;     ///< mode of the replay row with the highest frame number
  /// The filter's NIS over the replay rows that have one (6 dof: mean 6 when the filter and the tracker's
  /// covariance are consistent; `nis.count` 0 when the replay has no nis column).
  ErrorStats nis{};
  double nis_mean = 0.0;
  int nis_above_gate = 0;  ///< above kNisGate6Dof
};

/// Chi-square, 6 dof, 99.9 %: the filter's default gate (`[filter] pose_gate_chi2`); 0.1 % of a consistent
/// filter's updates exceed it.
constexpr double kNisGate6Dof = 22.46;

struct EvaluationOptions {
  std::vector<double> envelope_px{1.0, 0.25};
  int envelope_stride = 1;  ///< envelope on every n-th truth frame (index in the truth list)
  /// Rotations S of the model frame under which the model looks the same (e.g. 180 deg about the normal of
  /// a uniform rectangular plate). Each estimate is scored against the equivalent truth (R S, t) nearest to
  /// it: an acquisition that picks the symmetric twin is not an error the camera could see.
  std::vector<Mat3> model_symmetries;
  EnvelopeOptions envelope;
};

struct Evaluation {
  std::vector<double> envelope_px;
  std::vector<FrameRecord> frames;  ///< truth order
  EvaluationSummary summary;
};

Evaluation evaluate(const PinholeCamera& camera, const PolygonModel& model,
                    const std::vector<TruthPose>& truth, const std::vector<ReplayRow>& replay,
                    const EvaluationOptions& options);

/// Nullptr when the replay scored something; otherwise why there is nothing to score (an empty replay, or
/// none of its rows on a truth frame). Medians over nothing would read 0 and look perfect.
const char* nothingToScore(const EvaluationSummary& summary);

struct RequirementResult {
  std::string name;
  bool passed = true;
  std::string detail;
};

/// Index of `delta_px` in the evaluation's envelope sizes (-1 when not computed).
int envelopeIndex(const Evaluation& evaluation, double delta_px);

/// "inside 0.25 px envelope (all 6 axes): 99.70% (1994/2000)".
std::string insideLine(const EnvelopeSummary& s);

}  // namespace visnav::eval
