// ViSP .cao polygon model import, format V1 (subset documented in fsw/io/README.md).
#include <Eigen/Geometry>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
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

// Whitespace-separated tokens with their line; '#' starts a comment anywhere. A double-quoted part of a token
// (name="rear panel") may contain spaces.
std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
    } else {
      Token t;
      t.line = line;
      while (i < text.size() && text[i] != '\n' && text[i] != '#' && text[i] != ' ' && text[i] != '\t' &&
             text[i] != '\r') {
        if (text[i] == '"') {
          t.text += text[i++];
          while (i < text.size() && text[i] != '"' && text[i] != '\n') t.text += text[i++];
          if (i < text.size() && text[i] == '"') t.text += text[i++];
        } else {
          t.text += text[i++];
        }
      }
      tokens.push_back(std::move(t));
    }
  }
  return tokens;
}

class CaoParser {
 public:
  CaoParser(std::string path, std::vector<Token> tokens)
      : m_path(std::move(path)), m_tokens(std::move(tokens)) {}

  const LoadError& error() const { return m_error; }
  bool atEnd() const { return m_pos >= m_tokens.size(); }
  int lastLine() const { return m_tokens.empty() ? 1 : m_tokens.back().line; }
  const Token& peek() const { return m_tokens[m_pos]; }

  bool fail(int line, const std::string& problem) {
    if (m_error.ok) m_error = LoadError::failure(m_path + ":" + std::to_string(line) + ": " + problem);
    return false;
  }

  bool next(const std::string& what, Token& out) {
    if (atEnd()) return fail(lastLine(), "unexpected end of file, expected " + what);
    out = m_tokens[m_pos++];
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
      const Token& t = m_tokens[m_pos];
      const std::size_t eq = t.text.find('=');
      if (eq == std::string::npos || eq == 0) return fail(t.line, "unexpected extra value '" + t.text + "'");
      if (name != nullptr && t.text.compare(0, eq, "name") == 0) {
        std::string value = t.text.substr(eq + 1);
        if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
          value = value.substr(1, value.size() - 2);
        *name = value;
      }
      ++m_pos;
    }
    return true;
  }

 private:
  std::string m_path;
  std::vector<Token> m_tokens;
  std::size_t m_pos = 0;
  LoadError m_error;
};

constexpr long kMaxCount = 1000000;  // sanity bound: a corrupt count must not trigger a huge allocation

// Lines -> ordered vertex loop: start with the first line, then repeatedly follow the unused line that
// shares the current end point (ViSP files list a face's lines in any order and direction).
bool chainLines(CaoParser& p, int line, std::size_t face, const std::vector<std::pair<int, int>>& segments,
                std::vector<int>& loop) {
  std::vector<bool> used(segments.size(), false);
  const int start = segments[0].first;
  int cur = segments[0].second;
  used[0] = true;
  loop.push_back(start);
  for (std::size_t step = 1; step < segments.size(); ++step) {
    loop.push_back(cur);
    std::size_t j = 0;
    while (j < segments.size() && (used[j] || (segments[j].first != cur && segments[j].second != cur))) ++j;
    if (j == segments.size())
      return p.fail(line, "lines of face " + std::to_string(face) + " are not connected at point " +
                              std::to_string(cur) + " (not a closed loop)");
    used[j] = true;
    cur = segments[j].first == cur ? segments[j].second : segments[j].first;
  }
  if (cur != start)
    return p.fail(line, "lines of face " + std::to_string(face) + " do not form a closed loop");
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
  if (!p.integer("number of 3D points", 3, kMaxCount, count, &line) || !p.trailingParams(line, nullptr))
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
  if (!p.integer("number of 3D lines", 0, kMaxCount, num_lines, &line) || !p.trailingParams(line, nullptr))
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
  if (!p.integer("number of faces from lines", 0, kMaxCount, num_faces, &line) ||
      !p.trailingParams(line, nullptr))
    return false;
  for (long f = 0; f < num_faces; ++f) {
    long n = 0;
    if (!p.integer("number of lines of face " + std::to_string(f), 3, kMaxCount, n, &line)) return false;
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

  if (!p.integer("number of faces from points", 0, kMaxCount, num_faces, &line) ||
      !p.trailingParams(line, nullptr))
    return false;
  for (long f = 0; f < num_faces; ++f) {
    long n = 0;
    if (!p.integer("number of points of face " + std::to_string(f), 3, kMaxCount, n, &line)) return false;
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
    if (!p.integer(std::string("number of ") + shape, 0, kMaxCount, count, &line)) return false;
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
  if (!detail::readFile(path, text)) return LoadError::failure(path + ": cannot open file for reading");
  CaoParser parser(path, tokenize(text));
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
