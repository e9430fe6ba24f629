// Reader for the per-frame CSV written by visnav-replay. Columns are located by header name so the replay
// tool may add or reorder columns without breaking the evaluation; unknown columns are ignored.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::eval {

enum class TrackStatus : std::uint8_t { kTracking, kDegraded, kLost, kInit, kMissing };

const char* toString(TrackStatus status);
/// "tracking", "degraded", "lost", "init" (the replay CSV spellings). False for anything else.
bool parseTrackStatus(const std::string& text, TrackStatus& out);
/// Tracking or degraded: the row carries a pose estimate that is scored.
inline bool isTracked(TrackStatus s) { return s == TrackStatus::kTracking || s == TrackStatus::kDegraded; }

/// Navigation mode column `mode` (the spellings of nav::toString(NavMode)); kUnknown: the CSV has no such
/// column (replays written before the navigation pipeline).
enum class ReplayMode : std::uint8_t { kStandby, kFarRange, kAcquisition, kNearRange, kUnknown };
constexpr int kReplayModeCount = 4;  ///< the known modes (kUnknown excluded), in enum order

const char* toString(ReplayMode mode);
/// "standby", "far_range", "acquisition", "near_range". False for anything else.
bool parseReplayMode(const std::string& text, ReplayMode& out);

struct ReplayRow {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  TrackStatus status = TrackStatus::kLost;
  bool has_pose = false;  ///< false when a lost/init row leaves the pose columns empty or non-finite
  Pose pose;              ///< T_c_m from (x_m, y_m, z_m) and the normalised quaternion (qw, qx, qy, qz)
  ReplayMode mode = ReplayMode::kUnknown;
  bool far_valid = false;  ///< far_valid = 1: the three far-range values below are finite
  double far_azimuth_deg = 0.0;
  double far_elevation_deg = 0.0;
  double far_distance_m = 0.0;  ///< eq. 16, along the boresight
  bool has_nis = false;         ///< the optional `nis` column holds a number on this row
  double nis = 0.0;             ///< the Kalman filter's NIS of this frame's 6-DOF update (chi-square, 6 dof)
};

/// Parses a replay CSV. Required columns: frame, status, x_m, y_m, z_m, qw, qx, qy, qz. Optional:
/// timestamp_ns, mode, nis (empty or a finite number >= 0), and far_valid (0/1, empty = 0) which then needs
/// far_azimuth_deg, far_elevation_deg, far_distance_m, finite on far_valid = 1 rows. `name` is used in
/// messages ("name:line: problem"). Tracked rows must hold finite numbers; lost/init rows may leave the pose
/// empty. Duplicate frames are an error.
LoadError parseReplayCsv(std::istream& in, const std::string& name, std::vector<ReplayRow>& out);
LoadError loadReplayCsv(const std::string& path, std::vector<ReplayRow>& out);

/// Joins a far-range recording into `rows` by frame: the `_far_range.csv` that visnav-monitor writes next to
/// its pose CSV (columns found by name: frame, valid, azimuth_deg, elevation_deg, distance_m; others
/// ignored). Each far-range row sets far_valid and the three values of the replay row with the same frame,
/// replacing what that row had. Far-range rows without a replay row are counted in `unmatched` (a pose sample
/// lost on the way) and otherwise ignored. Errors (name:line: problem): missing column, bad number in a valid
/// row, a valid other than 0/1, a duplicate frame. `rows` is unchanged on error.
LoadError parseFarRangeCsv(std::istream& in, const std::string& name, std::vector<ReplayRow>& rows,
                           int& unmatched);
LoadError joinFarRangeCsv(const std::string& path, std::vector<ReplayRow>& rows, int& unmatched);

/// Splits one CSV line on commas (no quoting: the replay CSV never quotes) and trims blanks and a trailing
/// CR.
std::vector<std::string> splitCsvLine(const std::string& line);

}  // namespace visnav::eval
