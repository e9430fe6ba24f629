// What the pipeline returns per frame (NavSolution) and the health record FDIR keeps (HealthRecord). These
// are the only navigation types telemetry sees: fsw/telemetry maps them to the idl/ samples, so nothing
// upstream knows DDS exists. Fixed-size members only (no heap): copied by value every cycle.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "visnav/core/stage_interfaces.hpp"
#include "visnav/core/types.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::nav {

/// Copies a NUL-terminated string into a bounded char array, truncating; always NUL-terminates and zeroes the
/// rest (deterministic bytes in fixed-size records and on the wire). The one copy used by navigation and
/// telemetry.
void copyBounded(const char* text, char* out, std::size_t capacity);

enum class NavMode : std::uint8_t { kStandby = 0, kFarRange = 1, kAcquisition = 2, kNearRange = 3 };
const char* toString(NavMode mode);

/// Ground commands (ModeCommand topic).
enum class ModeCommandKind : std::uint8_t { kForceFarRange = 0, kReacquire = 1, kStandby = 2, kResume = 3 };
const char* toString(ModeCommandKind kind);

// The stage interfaces (FarRangeSolution, FaultBit and its names) live in core
// (visnav/core/stage_interfaces.hpp) so far range and acquisition need not include navigation; these keep the
// nav:: spellings working.
using visnav::FarRangeSolution;
using visnav::FaultBit;
using visnav::kFaultAcquisitionFailed;
using visnav::kFaultBitCount;
using visnav::kFaultCycleSlip;
using visnav::kFaultFarRangeNoTarget;
using visnav::kFaultFrameAge;
using visnav::kFaultImplausible;
using visnav::kFaultInlierRatio;
using visnav::kFaultInnovation;
using visnav::kFaultNoFrame;
using visnav::kFaultNotConverged;
using visnav::kFaultResidual;
using visnav::kFaultTooFewLines;

/// Why a pose computed this cycle is not valid (NavSolution::withheld): every gate that withheld it, not
/// only the first (fsw/navigation/README.md, "One frame", item 4). A pose may be withheld by several.
enum WithheldReason : std::uint32_t {
  kWithheldUncertain = 1U << 0,        ///< its own 1-sigma above [navigation] max_valid_attitude/position
  kWithheldDoubted = 1U << 1,          ///< doubted, attitude 1-sigma above doubted_max_attitude_sigma_deg
  kWithheldFindDoubted = 1U << 2,      ///< its track began with a find not yet cleared (doubt_clear_frames)
  kWithheldEdgeOn = 1U << 3,           ///< no face seen more than edge-on (max_valid_view_angle_deg)
  kWithheldJumped = 1U << 4,           ///< disputed by the filter and turned or moved in range in one frame
  kWithheldMissesOutline = 1U << 5,    ///< a 4-line fit missing lines (minimal_fit_max_missing_lines)
  kWithheldAwaitsNearRange = 1U << 6,  ///< an acquisition's own pose (acquisition_awaits_near_range)
  kWithheldBranchUnknown = 1U << 7,  ///< the track's branch is still to be confirmed (branch_confirm_frames)
};

/// Per-stage time of this frame [us].
struct StageTimes {
  double acquire_us = 0.0;
  double process_us = 0.0;
  double publish_us = 0.0;
  double health_us = 0.0;
};

struct NavSolution {
  /// Cycles the pipeline ran (process() calls), from 1: monotonic, one per cycle, frame or not.
  std::uint64_t cycle_number = 0;
  /// The camera's sequence number of the frame this cycle processed; on a cycle without a frame, that of the
  /// last frame processed (a gap between frames is a frame the camera or driver dropped, nothing else).
  std::uint64_t frame_number = 0;
  bool frame_received = false;        ///< this cycle processed a frame (false: missing or unusable)
  std::int64_t exposure_time_ns = 0;  ///< from the Frame
  NavMode mode = NavMode::kStandby;
  bool pose_valid = false;         ///< a 6-DOF pose is reported (near range, or acquisition's first pose)
  Pose pose;                       ///< T_c_m (CONVENTIONS.md)
  Mat6 covariance = Mat6::Zero();  ///< over (omega, dt)
  double quality = 0.0;            ///< [0, 1]
  int tracked_surfaces = 0;
  int lines_used = 0;
  int lines_total = 0;
  /// With a valid pose: other attitudes the image cannot tell from it at this range (the model's exact
  /// symmetries, and its near twins closer than [acquisition] near_twin_min_separation_px). 0: unique. The
  /// pose reported is the one continuous with the track; the ambiguity is flagged, not resolved.
  int symmetric_twins = 0;
  /// With a valid pose: its track began with an acquisition that chose between near twins the image could
  /// not tell apart by their continuity with a track lost a few frames before (AcquisitionResult). Set on
  /// every pose of that track: each rests on that choice.
  bool twin_by_continuity = false;
  /// With a pose computed (near range, a find, an acquisition) but pose_valid false: the WithheldReason bits
  /// that withheld it; 0 with a valid pose or without one. PoseEstimate.withheld on the wire
  /// (idl/visnav.idl); not in the C ABI's visnav_solution (ABI 2).
  std::uint32_t withheld = 0;
  FarRangeSolution far;
  std::uint32_t fault_bits = 0;  ///< FaultBit set this frame
  StageTimes timing;
};

/// A 6-DOF pose's own 1-sigma uncertainties from its covariance over (omega, dt): the square root of the
/// trace of the attitude block [deg] (the rms of the total rotation error), and that of the position block
/// over the range. What `[navigation] max_valid_*` judge, and what the campaign records for its offline
/// replay.
struct PoseSigmas {
  double attitude_deg = 0.0;
  double position_rel = 0.0;
};
PoseSigmas poseSigmas(const Pose& pose, const Mat6& covariance);

/// Timing statistics of one executive task, from fixed storage [us].
struct TaskTimingSummary {
  double min_us = 0.0;
  double mean_us = 0.0;
  double max_us = 0.0;
  double p99_us = 0.0;
};
constexpr int kTaskCount = kCycleStageCount;  ///< acquire, process, publish, health (CycleStage order)

struct ModeTransition {
  NavMode from = NavMode::kStandby;
  NavMode to = NavMode::kStandby;
  std::uint64_t frame_number = 0;
  std::array<char, 64> reason{};  ///< NUL-terminated
};

struct CommandAck {
  std::uint32_t command_id = 0;  ///< echoed from the ModeCommand
  ModeCommandKind kind = ModeCommandKind::kResume;
  bool accepted = false;
  std::array<char, 64> reason{};  ///< NUL-terminated: why rejected, or "ok"
};

struct HealthRecord {
  NavMode mode = NavMode::kStandby;
  std::uint32_t fault_bits = 0;                              ///< faults active now
  std::array<std::uint32_t, kFaultBitCount> fault_counts{};  ///< frames each fault was raised
  std::uint64_t frames_processed = 0;
  std::uint64_t frames_dropped = 0;
  std::uint64_t cycle_slips = 0;
  std::uint64_t mode_transitions = 0;
  ModeTransition last_transition;
  CommandAck last_command;
  std::array<TaskTimingSummary, kTaskCount> task_timing{};
};

}  // namespace visnav::nav
