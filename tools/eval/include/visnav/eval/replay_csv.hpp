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

struct ReplayRow {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  TrackStatus status = TrackStatus::kLost;
  bool has_pose = false;  ///< false when a lost/init row leaves the pose columns empty or non-finite
  Pose pose;              ///< T_c_m from (x_m, y_m, z_m) and the normalised quaternion (qw, qx, qy, qz)
};

/// Parses a replay CSV. Required columns: frame, status, x_m, y_m, z_m, qw, qx, qy, qz (timestamp_ns is
/// optional). `name` is used in messages ("name:line: problem"). Tracked rows must hold finite numbers;
/// lost/init rows may leave the pose empty. Duplicate frames are an error.
LoadError parseReplayCsv(std::istream& in, const std::string& name, std::vector<ReplayRow>& out);
LoadError loadReplayCsv(const std::string& path, std::vector<ReplayRow>& out);

/// Splits one CSV line on commas (no quoting: the replay CSV never quotes) and trims blanks and a trailing
/// CR.
std::vector<std::string> splitCsvLine(const std::string& line);

}  // namespace visnav::eval
