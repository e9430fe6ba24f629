#include "visnav/eval/replay_csv.hpp"

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <unordered_map>
#include <unordered_set>

namespace visnav::eval {
namespace {

std::string trim(const std::string& s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
  return s.substr(b, e - b);
}

std::string where(const std::string& name, int line) { return name + ":" + std::to_string(line) + ": "; }

// Whole-field parse: "12abc" is rejected, unlike a bare strtod. A cell, not a command-line value, so not
// visnav::cli::parseNumber: "nan" is a number here (a lost row's pose) and each caller says where a
// non-finite value is allowed.
bool parseDouble(const std::string& text, double& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE;
}

bool parseInt64(const std::string& text, std::int64_t& out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return false;
  out = static_cast<std::int64_t>(v);
  return true;
}

constexpr std::array<const char*, 7> kPoseColumns = {"x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"};
constexpr std::array<const char*, 3> kFarColumns = {"far_azimuth_deg", "far_elevation_deg", "far_distance_m"};
// Indexed by ReplayMode (kUnknown last).
constexpr std::array<const char*, kReplayModeCount + 1> kModeNames = {"standby", "far_range", "acquisition",
                                                                      "near_range", "unknown"};

// A headed CSV read line by line: header lookup, rows with enough fields, and unique frame numbers, with
// every problem named "name:line: ". Shared by the replay CSV and the far-range recording.
class HeadedCsv {
 public:
  HeadedCsv(std::istream& in, const std::string& name) : m_in(in), m_name(name) {}

  /// The first non-empty line is the header; an empty file is an error.
  LoadError readHeader() {
    std::string line;
    while (m_header.empty() && std::getline(m_in, line)) {
      ++m_line;
      if (!trim(line).empty()) m_header = splitCsvLine(line);
    }
    if (m_header.empty()) return LoadError::failure(m_name + ": empty file, expected a header row");
    return LoadError::success();
  }
  /// Index of a header name, -1 when absent.
  int column(const char* col) const {
    for (std::size_t i = 0; i < m_header.size(); ++i)
      if (m_header[i] == col) return static_cast<int>(i);
    return -1;
  }
  /// The next non-empty row into `fields` (false at the end of the file); a row shorter than the header sets
  /// `error` and returns false.
  bool next(std::vector<std::string>& fields, LoadError& error) {
    std::string line;
    while (std::getline(m_in, line)) {
      ++m_line;
      if (trim(line).empty()) continue;
      fields = splitCsvLine(line);
      if (fields.size() >= m_header.size()) return true;
      error = failure("expected " + std::to_string(m_header.size()) + " fields, found " +
                      std::to_string(fields.size()));
      return false;
    }
    return false;
  }
  /// The frame number in column `col` of this row; not an integer, or seen before: an error.
  LoadError frame(const std::vector<std::string>& fields, int col, std::int64_t& out) {
    if (!parseInt64(fields[static_cast<std::size_t>(col)], out))
      return failure("column 'frame': bad integer '" + fields[static_cast<std::size_t>(col)] + "'");
    if (!m_frames.insert(out).second) return failure("duplicate frame " + std::to_string(out));
    return LoadError::success();
  }
  /// A failure at the current line.
  LoadError failure(const std::string& problem) const {
    return LoadError::failure(where(m_name, m_line) + problem);
  }

 private:
  std::istream& m_in;
  const std::string& m_name;
  std::vector<std::string> m_header;
  std::unordered_set<std::int64_t> m_frames;
  int m_line = 0;
};

}  // namespace

const char* toString(TrackStatus status) {
  switch (status) {
    case TrackStatus::kTracking: return "tracking";
    case TrackStatus::kDegraded: return "degraded";
    case TrackStatus::kLost: return "lost";
    case TrackStatus::kInit: return "init";
    case TrackStatus::kMissing: return "missing";
  }
  return "?";
}

bool parseTrackStatus(const std::string& text, TrackStatus& out) {
  if (text == "tracking") {
    out = TrackStatus::kTracking;
  } else if (text == "degraded") {
    out = TrackStatus::kDegraded;
  } else if (text == "lost") {
    out = TrackStatus::kLost;
  } else if (text == "init") {
    out = TrackStatus::kInit;
  } else {
    return false;
  }
  return true;
}

const char* toString(ReplayMode mode) {
  const auto i = static_cast<std::size_t>(mode);
  const char* const name = i < kModeNames.size() ? kModeNames[i] : "?";
  return name;
}

bool parseReplayMode(const std::string& text, ReplayMode& out) {
  for (int i = 0; i < kReplayModeCount; ++i) {
    if (text == kModeNames[static_cast<std::size_t>(i)]) {
      out = static_cast<ReplayMode>(i);
      return true;
    }
  }
  return false;
}

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(
        trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

LoadError parseReplayCsv(std::istream& in, const std::string& name, std::vector<ReplayRow>& out) {
  HeadedCsv csv(in, name);
  if (LoadError e = csv.readHeader(); !e.ok) return e;
  const int frame_col = csv.column("frame");
  const int status_col = csv.column("status");
  const int time_col = csv.column("timestamp_ns");
  std::array<int, 7> pose_cols{};
  for (std::size_t k = 0; k < kPoseColumns.size(); ++k) pose_cols[k] = csv.column(kPoseColumns[k]);
  for (const char* required : {"frame", "status", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"}) {
    if (csv.column(required) < 0)
      return csv.failure(std::string("missing column '") + required + "' in the header");
  }
  const int mode_col = csv.column("mode");
  const int nis_col = csv.column("nis");
  const int far_valid_col = csv.column("far_valid");
  std::array<int, 3> far_cols{};
  for (std::size_t k = 0; k < kFarColumns.size(); ++k) {
    far_cols[k] = csv.column(kFarColumns[k]);
    if (far_valid_col >= 0 && far_cols[k] < 0)
      return csv.failure(std::string("column 'far_valid' needs column '") + kFarColumns[k] +
                         "' in the header");
  }

  std::vector<ReplayRow> rows;
  std::vector<std::string> f;
  LoadError row_error = LoadError::success();
  while (csv.next(f, row_error)) {
    ReplayRow row;
    if (LoadError e = csv.frame(f, frame_col, row.frame); !e.ok) return e;
    if (time_col >= 0 && !parseInt64(f[time_col], row.timestamp_ns))
      return csv.failure("column 'timestamp_ns': bad integer '" + f[time_col] + "'");
    if (!parseTrackStatus(f[status_col], row.status)) {
      return csv.failure("column 'status': unknown status '" + f[status_col] +
                         "' (expected tracking, degraded, lost or init)");
    }
    if (mode_col >= 0 && !parseReplayMode(f[mode_col], row.mode)) {
      return csv.failure("column 'mode': unknown mode '" + f[mode_col] +
                         "' (expected standby, far_range, acquisition or near_range)");
    }
    if (nis_col >= 0 && !f[nis_col].empty()) {
      if (!parseDouble(f[nis_col], row.nis) || !std::isfinite(row.nis) || row.nis < 0.0)
        return csv.failure("column 'nis': expected a number >= 0, got '" + f[nis_col] + "'");
      row.has_nis = true;
    }
    if (far_valid_col >= 0) {
      const std::string& flag = f[far_valid_col];
      if (flag != "" && flag != "0" && flag != "1")
        return csv.failure("column 'far_valid': expected 0 or 1, got '" + flag + "'");
      row.far_valid = flag == "1";
      std::array<double*, 3> far_values = {&row.far_azimuth_deg, &row.far_elevation_deg, &row.far_distance_m};
      for (std::size_t k = 0; row.far_valid && k < kFarColumns.size(); ++k) {
        const std::string& text = f[far_cols[k]];
        if (!parseDouble(text, *far_values[k]) || !std::isfinite(*far_values[k])) {
          return csv.failure(std::string("column '") + kFarColumns[k] + "': bad number '" + text +
                             "' in a far_valid row");
        }
      }
    }
    std::array<double, 7> v{};
    bool all_finite = true;
    for (std::size_t k = 0; k < kPoseColumns.size(); ++k) {
      const std::string& text = f[pose_cols[k]];
      // Lost/init rows may carry no pose at all; a tracked row must.
      if (text.empty() && !isTracked(row.status)) {
        all_finite = false;
        continue;
      }
      if (!parseDouble(text, v[k])) {
        return csv.failure(std::string("column '") + kPoseColumns[k] + "': bad number '" + text + "'");
      }
      if (!std::isfinite(v[k])) all_finite = false;
    }
    if (all_finite) {
      Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
      const double norm = q.norm();
      // A grossly non-unit quaternion means a column mix-up, not rounding.
      if (norm < 0.5 || norm > 1.5) return csv.failure("quaternion (qw, qx, qy, qz) is not unit length");
      q.coeffs() /= norm;
      row.pose = Pose::fromQuaternion(q, Vec3(v[0], v[1], v[2]));
      row.has_pose = true;
    } else if (isTracked(row.status)) {
      return csv.failure(std::string("non-finite pose in a '") + toString(row.status) + "' row");
    }
    rows.push_back(row);
  }
  if (!row_error.ok) return row_error;
  out = std::move(rows);
  return LoadError::success();
}

LoadError parseFarRangeCsv(std::istream& in, const std::string& name, std::vector<ReplayRow>& rows,
                           int& unmatched) {
  HeadedCsv csv(in, name);
  if (LoadError e = csv.readHeader(); !e.ok) return e;
  constexpr std::array<const char*, 5> kColumns = {"frame", "valid", "azimuth_deg", "elevation_deg",
                                                   "distance_m"};
  std::array<int, kColumns.size()> col{};
  for (std::size_t k = 0; k < kColumns.size(); ++k) {
    col[k] = csv.column(kColumns[k]);
    if (col[k] < 0) return csv.failure(std::string("missing column '") + kColumns[k] + "' in the header");
  }
  std::unordered_map<std::int64_t, std::size_t> row_of_frame;
  for (std::size_t i = 0; i < rows.size(); ++i) row_of_frame[rows[i].frame] = i;
  std::vector<ReplayRow> joined = rows;  // the caller's rows change only when the whole file is good
  int missing = 0;
  std::vector<std::string> f;
  LoadError row_error = LoadError::success();
  while (csv.next(f, row_error)) {
    std::int64_t frame = 0;
    if (LoadError e = csv.frame(f, col[0], frame); !e.ok) return e;
    const std::string& flag = f[col[1]];
    if (flag != "0" && flag != "1") return csv.failure("column 'valid': expected 0 or 1, got '" + flag + "'");
    std::array<double, 3> values{};
    for (std::size_t k = 0; flag == "1" && k < values.size(); ++k) {
      const std::string& text = f[col[k + 2]];
      if (!parseDouble(text, values[k]) || !std::isfinite(values[k]))
        return csv.failure(std::string("column '") + kColumns[k + 2] + "': bad number '" + text +
                           "' in a valid row");
    }
    const auto it = row_of_frame.find(frame);
    if (it == row_of_frame.end()) {
      ++missing;
      continue;
    }
    ReplayRow& row = joined[it->second];
    row.far_valid = flag == "1";
    row.far_azimuth_deg = values[0];
    row.far_elevation_deg = values[1];
    row.far_distance_m = values[2];
  }
  if (!row_error.ok) return row_error;
  rows = std::move(joined);
  unmatched = missing;
  return LoadError::success();
}

LoadError joinFarRangeCsv(const std::string& path, std::vector<ReplayRow>& rows, int& unmatched) {
  std::ifstream in(path);
  if (!in) return LoadError::failure(path + ": cannot open for reading");
  return parseFarRangeCsv(in, path, rows, unmatched);
}

LoadError loadReplayCsv(const std::string& path, std::vector<ReplayRow>& out) {
  std::ifstream in(path);
  if (!in) return LoadError::failure(path + ": cannot open for reading");
  return parseReplayCsv(in, path, out);
}

}  // namespace visnav::eval
