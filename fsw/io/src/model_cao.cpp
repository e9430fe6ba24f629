// ViSP .cao polygon model import, format V1 (subset documented in fsw/io/README.md).
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io_util.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::io {
namespace {

struct Token {
  std::string text;
  int line = 0;
};

// Whitespace-separated tokens with their line, read one at a time (a 16 MiB file of one-character tokens
// must not become millions of strings at once); '#' starts a comment anywhere. A double-quoted part of a
// token (name="rear panel") may contain spaces.
class Tokenizer {
 public:
  explicit Tokenizer(const std::string& text) : m_text(text) { advance(); }

  bool atEnd() const { return !m_has_next; }
  const Token& peek() const { return m_next; }
  int lastLine() const { return m_last_line; }
  Token take() {
    Token t = std::move(m_next);
    advance();
    return t;
  }

 private:
  void advance() {
    const std::string& text = m_text;
    m_has_next = false;
    while (m_pos < text.size()) {
      const char c = text[m_pos];
      if (c == '\n') {
        ++m_line;
        ++m_pos;
      } else if (c == '#') {
        while (m_pos < text.size() && text[m_pos] != '\n') ++m_pos;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++m_pos;
      } else {
        m_next.text.clear();
        m_next.line = m_line;
        std::size_t& i = m_pos;
        while (i < text.size() && text[i] != '\n' && text[i] != '#' && text[i] != ' ' && text[i] != '\t' &&
               text[i] != '\r') {
          if (text[i] == '"') {
            m_next.text += text[i++];
            while (i < text.size() && text[i] != '"' && text[i] != '\n') m_next.text += text[i++];
            if (i < text.size() && text[i] == '"') m_next.text += text[i++];
          } else {
            m_next.text += text[i++];
          }
        }
        m_has_next = true;
        m_last_line = m_line;
        return;
      }
    }
  }

  const std::string& m_text;
  std::size_t m_pos = 0;
  int m_line = 1;
  int m_last_line = 1;
  Token m_next;
  bool m_has_next = false;
};

class CaoParser {
 public:
  CaoParser(std::string path, const std::string& text) : m_path(std::move(path)), m_tokens(text) {}

  const LoadError& error() const { return m_error; }
  bool atEnd() const { return m_tokens.atEnd(); }
  int lastLine() const { return m_tokens.lastLine(); }
  const Token& peek() const { return m_tokens.peek(); }

  bool fail(int line, const std::string& problem) {
    if (m_error.ok) m_error = LoadError::failure(m_path + ":" + std::to_string(line) + ": " + problem);
    return false;
  }

  bool next(const std::string& what, Token& out) {
    if (atEnd()) return fail(lastLine(), "unexpected end of file, expected " + what);
    out = m_tokens.take();
    return true;
  }

  bool integer(const std::string& what, long min_value, long max_value, long& out, int* line = nullptr) {
    Token t;
    if (!next(what, t)) return false;
    if (line != nullptr) *line = t.line;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(t.text.c_str(), &end, 10);
    if (t.text.empty() || *end != '\0' || errno != 0)
      return fail(t.line, "expected an integer " + what + ", got '" + t.text + "'");
    if (v < min_value || v > max_value)
      return fail(t.line, what + " " + std::to_string(v) + " out of range [" + std::to_string(min_value) +
                              ", " + std::to_string(max_value) + "]");
    out = v;
    return true;
  }

  bool real(const std::string& what, double& out, int* line = nullptr) {
    Token t;
    if (!next(what, t)) return false;
    if (line != nullptr) *line = t.line;
    char* end = nullptr;
    const double v = std::strtod(t.text.c_str(), &end);
    if (t.text.empty() || *end != '\0')
      return fail(t.line, "expected a number " + what + ", got '" + t.text + "'");
    if (!std::isfinite(v)) return fail(t.line, what + " is not finite");
    out = v;
    return true;
  }

  // ViSP allows key=value parameters at the end of a record's line (name=..., useLod=...). Only name is used;
  // any other leftover on that line is an error rather than silently misread data.
  bool trailingParams(int line, std::string* name) {
    while (!atEnd() && peek().line == line) {
      const Token t = m_tokens.take();
      const std::size_t eq = t.text.find('=');
      if (eq == std::string::npos || eq == 0) return fail(t.line, "unexpected extra value '" + t.text + "'");
      if (name != nullptr && t.text.compare(0, eq, "name") == 0) {
        std::string value = t.text.substr(eq + 1);
        if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
          value = value.substr(1, value.size() - 2);
        *name = value;
      }
    }
    return true;
  }

 private:
  std::string m_path;
  Tokenizer m_tokens;
  LoadError m_error;
};

// Count bounds (fsw/io/README.md, "Limits"): the model's own bounds, and lines at most two per surface
// side. A corrupt count fails at once instead of driving an allocation or a loop.
constexpr long kMaxPoints = static_cast<long>(PolygonModel::kMaxVertices);
constexpr long kMaxLines = 2 * static_cast<long>(PolygonModel::kMaxVertices);
constexpr long kMaxFaces = static_cast<long>(PolygonModel::kMaxSurfaces);
constexpr long kMaxFaceEntries = static_cast<long>(PolygonModel::kMaxSurfaceVertices);

// Lines -> ordered vertex loop (ViSP files list a face's lines in any order and direction). A simple
// polygon meets every one of its points exactly twice, so each point keeps its two lines and the walk is
// linear in the number of lines (the search for the next line had made a long face quadratic).
bool chainLines(CaoParser& p, int line, std::size_t face, const std::vector<std::pair<int, int>>& segments,
                std::vector<int>& loop) {
  const std::string label = "lines of face " + std::to_string(face);
  std::unordered_map<int, std::array<int, 2>> touching;  // point -> the (up to) two segments that meet it
  touching.reserve(2 * segments.size());
  for (std::size_t j = 0; j < segments.size(); ++j) {
    for (const int point : {segments[j].first, segments[j].second}) {
      auto [it, added] = touching.try_emplace(point, std::array<int, 2>{-1, -1});
      std::array<int, 2>& slots = it->second;
      if (!added && slots[1] >= 0)
        return p.fail(line, label + " meet at point " + std::to_string(point) +
                                " more than twice (not one closed loop)");
      slots[added ? 0 : 1] = static_cast<int>(j);
    }
  }
  for (const auto& [point, slots] : touching)
    if (slots[1] < 0)
      return p.fail(line,
                    label + " are not connected at point " + std::to_string(point) + " (not a closed loop)");
  const int start = segments[0].first;
  int cur = segments[0].second;
  int via = 0;
  loop.push_back(start);
  for (std::size_t step = 1; step < segments.size(); ++step) {
    if (cur == start)
      return p.fail(line, label + " form more than one loop (" + std::to_string(step) + " of " +
                              std::to_string(segments.size()) + " lines closed the first)");
    loop.push_back(cur);
    const std::array<int, 2>& slots = touching.at(cur);
    via = slots[0] == via ? slots[1] : slots[0];
    const auto& seg = segments[static_cast<std::size_t>(via)];
    cur = seg.first == cur ? seg.second : seg.first;
  }
  if (cur != start) return p.fail(line, label + " do not form a closed loop");
  return true;
}

// ViSP files are not consistent about orientation, so the order is decided geometrically: a face whose
// order-implied normal points towards the model centroid is reversed. Faces whose plane holds the centroid
// (a lone plate) keep the file order.
void orientOutwards(const std::vector<Vec3>& points, std::vector<ModelSurface>& surfaces) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double scale = 0.0;
  for (const Vec3& p : points) scale = std::max(scale, (p - centroid).norm());
  for (ModelSurface& s : surfaces) {
    Vec3 newell = Vec3::Zero();
    Vec3 face_centroid = Vec3::Zero();
    const auto& idx = s.vertex_indices;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      newell += points[idx[k]].cross(points[idx[(k + 1) % idx.size()]]);
      face_centroid += points[idx[k]];
    }
    face_centroid /= static_cast<double>(idx.size());
    if (newell.norm() == 0.0) continue;  // degenerate: PolygonModel::build reports it
    if (newell.normalized().dot(face_centroid - centroid) < -1e-9 * scale)
      std::reverse(s.vertex_indices.begin() + 1, s.vertex_indices.end());
  }
}

bool parseCao(CaoParser& p, std::vector<Vec3>& points, std::vector<ModelSurface>& surfaces,
              std::vector<int>& surface_lines) {
  Token header;
  if (!p.next("header 'V1'", header)) return false;
  if (header.text != "V1")
    return p.fail(header.line, "unsupported header '" + header.text + "' (only ViSP .cao format 'V1')");
  if (!p.atEnd() && p.peek().text.compare(0, 4, "load") == 0)
    return p.fail(p.peek().line, "load() of other .cao files is not supported");

  long count = 0;
  int line = 0;
  if (!p.integer("number of 3D points", 3, kMaxPoints, count, &line) || !p.trailingParams(line, nullptr))
    return false;
  for (long k = 0; k < count; ++k) {
    Vec3 v;
    const std::string what = "coordinate of point " + std::to_string(k);
    if (!p.real("x " + what, v.x()) || !p.real("y " + what, v.y()) || !p.real("z " + what, v.z(), &line) ||
        !p.trailingParams(line, nullptr))
      return false;
    points.push_back(v);
  }

  long num_lines = 0;
  if (!p.integer("number of 3D lines", 0, kMaxLines, num_lines, &line) || !p.trailingParams(line, nullptr))
    return false;
  std::vector<std::pair<int, int>> segments;
  const long last_point = static_cast<long>(points.size()) - 1;
  for (long k = 0; k < num_lines; ++k) {
    long a = 0;
    long b = 0;
    const std::string what = "point index of line " + std::to_string(k);
    if (!p.integer(what, 0, last_point, a) || !p.integer(what, 0, last_point, b, &line)) return false;
    if (a == b)
      return p.fail(line, "line " + std::to_string(k) + " joins point " + std::to_string(a) + " to itself");
    if (!p.trailingParams(line, nullptr)) return false;
    segments.emplace_back(static_cast<int>(a), static_cast<int>(b));
  }

  long num_faces = 0;
  if (!p.integer("number of faces from lines", 0, kMaxFaces, num_faces, &line) ||
      !p.trailingParams(line, nullptr))
    return false;
  for (long f = 0; f < num_faces; ++f) {
    long n = 0;
    if (!p.integer("number of lines of face " + std::to_string(f), 3, kMaxFaceEntries, n, &line))
      return false;
    const int face_line = line;
    std::vector<std::pair<int, int>> face_segments;
    for (long k = 0; k < n; ++k) {
      long index = 0;
      if (!p.integer("line index of face " + std::to_string(f), 0, num_lines - 1, index, &line)) return false;
      face_segments.push_back(segments[static_cast<std::size_t>(index)]);
    }
    ModelSurface s;
    if (!p.trailingParams(line, &s.name)) return false;
    if (!chainLines(p, face_line, surfaces.size(), face_segments, s.vertex_indices)) return false;
    surfaces.push_back(std::move(s));
    surface_lines.push_back(face_line);
  }

  if (!p.integer("number of faces from points", 0, kMaxFaces - static_cast<long>(surfaces.size()), num_faces,
                 &line) ||
      !p.trailingParams(line, nullptr))
    return false;
  for (long f = 0; f < num_faces; ++f) {
    long n = 0;
    if (!p.integer("number of points of face " + std::to_string(f), 3, kMaxFaceEntries, n, &line))
      return false;
    surface_lines.push_back(line);
    ModelSurface s;
    for (long k = 0; k < n; ++k) {
      long index = 0;
      if (!p.integer("point index of face " + std::to_string(f), 0, last_point, index, &line)) return false;
      s.vertex_indices.push_back(static_cast<int>(index));
    }
    if (!p.trailingParams(line, &s.name)) return false;
    surfaces.push_back(std::move(s));
  }

  // ViSP treats the cylinder and circle sections as optional at the end of the file.
  for (const char* shape : {"cylinders", "circles"}) {
    if (p.atEnd()) break;
    if (!p.integer(std::string("number of ") + shape, 0, kMaxFaces, count, &line)) return false;
    if (count != 0) return p.fail(line, std::string(shape) + " are not polygons, not supported");
    if (!p.trailingParams(line, nullptr)) return false;
  }
  if (!p.atEnd()) return p.fail(p.peek().line, "unexpected '" + p.peek().text + "' after the last section");
  if (surfaces.empty()) return p.fail(p.lastLine(), "model has no faces");
  return true;
}

}  // namespace

LoadError loadModelCao(const std::string& path, PolygonModel& out) {
  std::string text;
  if (LoadError e = readTextFile(path, text); !e.ok) return e;
  CaoParser parser(path, text);
  std::vector<Vec3> points;
  std::vector<ModelSurface> surfaces;
  std::vector<int> surface_lines;
  if (!parseCao(parser, points, surfaces, surface_lines)) return parser.error();
  orientOutwards(points, surfaces);
  PolygonModel built;
  if (LoadError e = PolygonModel::build(points, std::move(surfaces), built); !e.ok)
    return detail::buildError(path, e.message, surface_lines);
  out = std::move(built);
  return LoadError::success();
}

}  // namespace visnav::io
