// Sequence directories (format: drivers/replay/README.md). Loading is strict and all-or-nothing: everything
// is parsed into a local Sequence and moved into the caller's only when every part checked out.
#include "visnav/replay/sequence.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/io/text_file.hpp"
#include "visnav/replay/toml_reader.hpp"

namespace visnav::replay {
namespace fs = std::filesystem;

namespace {

constexpr const char* kFramesHeader = "frame,timestamp_ns,file";
constexpr const char* kTruthHeader = "frame,timestamp_ns,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg";
constexpr double kYprConsistencyRad = 1e-4;  // the YPR columns are redundant; they must agree with q

std::string absolutePath(const fs::path& p) { return fs::absolute(p).lexically_normal().string(); }

LoadError lineError(const std::string& path, int line, const std::string& problem) {
  return LoadError::failure(path + ":" + std::to_string(line) + ": " + problem);
}

// Frame files stay inside the sequence directory: a relative path without any ".." component.
const char* pathEscapes(const std::string& file) {
  const fs::path p(file);
  if (p.is_absolute()) return "is an absolute path (frame files are relative to the sequence directory)";
  for (const fs::path& part : p)
    if (part == "..") return "contains '..' (frame files stay inside the sequence directory)";
  return nullptr;
}

bool parseInt64(const std::string& s, std::int64_t& out) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (errno != 0 || end != s.c_str() + s.size()) return false;
  out = v;
  return true;
}

bool parseDouble(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return false;
  out = v;
  return true;
}

void splitCsv(const std::string& line, std::vector<std::string>& fields) {
  fields.clear();
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
}

// Reads a CSV with an exact header; calls row(fields, line_number) for every data row.
template <typename RowFn>
LoadError readCsv(const std::string& path, const char* header, RowFn row) {
  std::string text;
  if (LoadError e = io::readTextFile(path, text); !e.ok) return e;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  std::vector<std::string> fields;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line_no == 1) {
      if (line != header) return lineError(path, 1, std::string("expected header '") + header + "'");
      continue;
    }
    if (line.empty()) return lineError(path, line_no, "empty line");
    splitCsv(line, fields);
    LoadError e = row(fields, line_no);
    if (!e.ok) return e;
  }
  if (line_no == 0) return LoadError::failure(path + ": empty file (no header)");
  return LoadError::success();
}

}  // namespace

LoadError loadTruthCsv(const std::string& path, std::vector<TruthRow>& out) {
  std::vector<TruthRow> rows;
  LoadError e = readCsv(path, kTruthHeader, [&](const std::vector<std::string>& f, int line) {
    if (f.size() != 12U) return lineError(path, line, "expected 12 fields, got " + std::to_string(f.size()));
    TruthRow r;
    if (!parseInt64(f[0], r.frame)) return lineError(path, line, "bad frame number '" + f[0] + "'");
    if (!parseInt64(f[1], r.timestamp_ns)) return lineError(path, line, "bad timestamp_ns '" + f[1] + "'");
    double v[10];
    for (int i = 0; i < 10; ++i) {
      if (!parseDouble(f[2 + i], v[i])) return lineError(path, line, "bad number '" + f[2 + i] + "'");
    }
    if (!rows.empty() && r.frame <= rows.back().frame) {
      return lineError(path, line, "frame numbers must increase");
    }
    const Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
    if (std::abs(q.norm() - 1.0) > 1e-6) return lineError(path, line, "quaternion is not unit length");
    r.pose = Pose::fromQuaternion(q.normalized(), Vec3(v[0], v[1], v[2]));
    const Mat3 r_ypr = rotationFromYpr({v[7] * kRadPerDeg, v[8] * kRadPerDeg, v[9] * kRadPerDeg});
    if (logSo3(r_ypr.transpose() * r.pose.R_c_m).norm() > kYprConsistencyRad) {
      return lineError(path, line, "yaw/pitch/roll columns disagree with the quaternion");
    }
    rows.push_back(r);
    return LoadError::success();
  });
  if (!e.ok) return e;
  out = std::move(rows);
  return LoadError::success();
}

LoadError loadSequence(const std::string& directory, Sequence& out) {
  const fs::path dir(directory);
  const std::string toml_path = (dir / "sequence.toml").string();
  TomlReader r;
  LoadError e = r.open(toml_path);
  if (!e.ok) return e;

  Sequence seq;
  seq.directory = absolutePath(dir);
  std::string format;
  std::int64_t version = 0;
  std::int64_t frame_count = 0;
  std::int64_t max_code = 0;
  std::string camera_file;
  std::string model_file;
  std::string frames_file;
  std::string truth_file;
  r.getString("format", format, true);
  if (r.good() && format != "visnav-sequence") r.fail("format", "expected \"visnav-sequence\"");
  r.getInt("version", version, true);
  if (r.good() && version != 1) r.fail("version", "unsupported version (this reader knows 1)");
  r.getString("name", seq.name, true);
  r.getInt("frame_count", frame_count, true);
  r.checkRange("frame_count", static_cast<double>(frame_count), 1.0, 1e9);  // nothing to replay in 0 frames
  r.getInt("bit_depth", seq.bit_depth, true);
  if (r.good() && seq.bit_depth != 8 && seq.bit_depth != 16) r.fail("bit_depth", "must be 8 or 16");
  r.getInt("max_code", max_code, true);
  r.checkRange("max_code", static_cast<double>(max_code), 1.0, seq.bit_depth == 8 ? 255.0 : 65535.0);
  r.getDouble("rate_hz", seq.rate_hz, true);
  if (r.good() && !(seq.rate_hz > 0.0)) r.fail("rate_hz", "must be > 0");
  r.getString("camera", camera_file, true);
  r.getString("model", model_file, true);
  r.getString("frames", frames_file, true);
  r.getString("truth", truth_file, false);
  e = r.finish();
  if (!e.ok) return e;
  seq.max_code = static_cast<std::uint16_t>(max_code);

  seq.camera_path = absolutePath(dir / camera_file);
  seq.model_path = absolutePath(dir / model_file);
  e = io::loadCamera(seq.camera_path, seq.camera);
  if (!e.ok) return e;
  e = io::loadModel(seq.model_path, seq.model);
  if (!e.ok) return e;

  const std::string frames_path = absolutePath(dir / frames_file);
  e = readCsv(frames_path, kFramesHeader, [&](const std::vector<std::string>& f, int line) {
    if (f.size() != 3U)
      return lineError(frames_path, line, "expected 3 fields, got " + std::to_string(f.size()));
    FrameEntry fe;
    if (!parseInt64(f[0], fe.frame)) return lineError(frames_path, line, "bad frame number '" + f[0] + "'");
    if (!parseInt64(f[1], fe.timestamp_ns))
      return lineError(frames_path, line, "bad timestamp_ns '" + f[1] + "'");
    if (f[2].empty()) return lineError(frames_path, line, "empty file name");
    if (const char* problem = pathEscapes(f[2]))
      return lineError(frames_path, line, "frame file '" + f[2] + "' " + problem);
    if (!seq.frames.empty()) {
      if (fe.frame <= seq.frames.back().frame)
        return lineError(frames_path, line, "frame numbers must increase");
      if (fe.timestamp_ns <= seq.frames.back().timestamp_ns) {
        return lineError(frames_path, line, "timestamps must increase");
      }
    }
    fe.file = absolutePath(dir / f[2]);
    std::error_code ec;
    if (!fs::is_regular_file(fe.file, ec))
      return lineError(frames_path, line, "missing frame file '" + f[2] + "'");
    seq.frames.push_back(std::move(fe));
    return LoadError::success();
  });
  if (!e.ok) return e;
  if (seq.frames.empty())
    return LoadError::failure(frames_path + ": no frames (a sequence needs at least one)");
  if (static_cast<std::int64_t>(seq.frames.size()) != frame_count) {
    return LoadError::failure(frames_path + ": has " + std::to_string(seq.frames.size()) +
                              " frames but sequence.toml says frame_count = " + std::to_string(frame_count));
  }

  if (!truth_file.empty()) {
    const std::string truth_path = absolutePath(dir / truth_file);
    e = loadTruthCsv(truth_path, seq.truth);
    if (!e.ok) return e;
    // Every truth row must name a recorded frame with the same timestamp (both lists are sorted).
    std::size_t k = 0;
    for (std::size_t i = 0; i < seq.truth.size(); ++i) {
      const TruthRow& t = seq.truth[i];
      while (k < seq.frames.size() && seq.frames[k].frame < t.frame) ++k;
      const int line = static_cast<int>(i) + 2;
      if (k == seq.frames.size() || seq.frames[k].frame != t.frame) {
        return lineError(truth_path, line, "frame " + std::to_string(t.frame) + " is not in frames.csv");
      }
      if (seq.frames[k].timestamp_ns != t.timestamp_ns) {
        return lineError(truth_path, line, "timestamp differs from frames.csv");
      }
    }
  }
  out = std::move(seq);
  return LoadError::success();
}

LoadError SequenceWriter::open(const std::string& directory, const std::string& name,
                               const CameraIntrinsics& camera, const PolygonModel& model, int bit_depth,
                               std::uint16_t max_code, double rate_hz) {
  if (bit_depth != 8 && bit_depth != 16) return LoadError::failure(directory + ": bit_depth must be 8 or 16");
  if (max_code == 0U || (bit_depth == 8 && max_code > 255U)) {
    return LoadError::failure(directory + ": max_code out of range for the bit depth");
  }
  if (!(rate_hz > 0.0)) return LoadError::failure(directory + ": rate_hz must be > 0");
  std::error_code ec;
  fs::create_directories(fs::path(directory) / "frames", ec);
  if (ec) return LoadError::failure(directory + ": cannot create directory: " + ec.message());
  LoadError e = io::writeCameraToml((fs::path(directory) / "camera.toml").string(), camera);
  if (!e.ok) return e;
  e = io::writeModelToml((fs::path(directory) / "model.toml").string(), model);
  if (!e.ok) return e;
  m_directory = directory;
  m_name = name;
  m_bit_depth = bit_depth;
  m_max_code = max_code;
  m_rate_hz = rate_hz;
  m_frames.clear();
  m_truth.clear();
  m_has_truth = false;
  return LoadError::success();
}

std::string SequenceWriter::framePath(std::int64_t frame) const {
  char name[48];
  std::snprintf(name, sizeof name, "frames/%06" PRId64 ".pgm", frame);
  return (fs::path(m_directory) / name).string();
}

void SequenceWriter::addFrame(std::int64_t frame, std::int64_t timestamp_ns, const Pose* truth) {
  char name[48];
  std::snprintf(name, sizeof name, "frames/%06" PRId64 ".pgm", frame);
  m_frames.push_back({frame, timestamp_ns, name});
  if (truth != nullptr) {
    m_has_truth = true;
    m_truth.push_back({frame, timestamp_ns, *truth});
  }
}

LoadError SequenceWriter::close() {
  const fs::path dir(m_directory);
  {
    toml::table t{{"format", "visnav-sequence"},
                  {"version", 1},
                  {"name", m_name},
                  {"frame_count", static_cast<std::int64_t>(m_frames.size())},
                  {"bit_depth", m_bit_depth},
                  {"max_code", static_cast<std::int64_t>(m_max_code)},
                  {"rate_hz", m_rate_hz},
                  {"camera", "camera.toml"},
                  {"model", "model.toml"},
                  {"frames", "frames.csv"}};
    if (m_has_truth) t.insert("truth", "truth.csv");
    std::ofstream f(dir / "sequence.toml");
    f << "# visnav sequence (format: drivers/replay/README.md)\n" << t << "\n";
    if (!f) return LoadError::failure((dir / "sequence.toml").string() + ": write failed");
  }
  {
    std::ofstream f(dir / "frames.csv");
    f << kFramesHeader << "\n";
    for (const FrameEntry& fe : m_frames) f << fe.frame << "," << fe.timestamp_ns << "," << fe.file << "\n";
    if (!f) return LoadError::failure((dir / "frames.csv").string() + ": write failed");
  }
  if (m_has_truth) {
    std::FILE* f = std::fopen((dir / "truth.csv").string().c_str(), "w");
    if (f == nullptr) return LoadError::failure((dir / "truth.csv").string() + ": cannot create file");
    std::fprintf(f, "%s\n", kTruthHeader);
    for (const TruthRow& t : m_truth) {
      Eigen::Quaterniond q = t.pose.quaternion().normalized();
      if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // CONVENTIONS.md: w >= 0
      const YawPitchRoll ypr = t.pose.ypr();
      const Vec3& p = t.pose.t_c_m;
      std::fprintf(f, "%" PRId64 ",%" PRId64 ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                   t.frame, t.timestamp_ns, p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z(),
                   ypr.yaw_rad * kDegPerRad, ypr.pitch_rad * kDegPerRad, ypr.roll_rad * kDegPerRad);
    }
    const bool ok = std::ferror(f) == 0;
    if (std::fclose(f) != 0 || !ok)
      return LoadError::failure((dir / "truth.csv").string() + ": write failed");
  }
  return LoadError::success();
}

}  // namespace visnav::replay
