// OpenCV FileStorage YAML calibration import: a strict hand-rolled reader of the subset that
// cv::FileStorage writes for calibrateCamera results (documented in fsw/io/README.md).
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io_util.hpp"
#include "visnav/io/camera_io.hpp"

namespace visnav::io {
namespace {

struct Line {
  int number = 0;
  int indent = 0;
  std::string text;  // without indentation, comment and trailing blanks
};

// A top-level "key: value" entry and the indented lines below it.
struct Entry {
  int line = 0;
  std::string value;
  std::vector<Line> children;
};

struct Matrix {
  int rows = 0;
  int cols = 0;
  std::vector<double> data;
};

std::string trim(const std::string& s) {
  const std::size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  const std::size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// YAML comments start at '#' preceded by a blank (or at the line start), outside quotes.
std::string stripComment(const std::string& s) {
  char quote = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t')) {
      return s.substr(0, i);
    }
  }
  return s;
}

std::vector<Line> splitLines(const std::string& text) {
  std::vector<Line> lines;
  std::size_t start = 0;
  int number = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++number;
    std::string raw = text.substr(start, end - start);
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    Line l;
    l.number = number;
    const std::size_t first = raw.find_first_not_of(" \t");
    l.indent = first == std::string::npos ? 0 : static_cast<int>(first);
    // The directive line may contain '#'-free text only, but keep it verbatim for the header check.
    l.text = number == 1 ? trim(raw) : trim(stripComment(raw));
    if (!l.text.empty()) lines.push_back(l);
    start = end + 1;
  }
  return lines;
}

class YamlReader {
 public:
  explicit YamlReader(std::string path) : m_path(std::move(path)) {}
  const LoadError& error() const { return m_error; }

  bool fail(int line, const std::string& problem) {
    if (m_error.ok) m_error = LoadError::failure(m_path + ":" + std::to_string(line) + ": " + problem);
    return false;
  }
  // A missing top-level key has no line of its own.
  bool missing(const char* key) {
    if (m_error.ok) m_error = LoadError::failure(m_path + ": missing key '" + key + "'");
    return false;
  }

  bool parseEntries(const std::vector<Line>& lines, std::map<std::string, Entry>& entries) {
    if (lines.empty() || lines[0].number != 1 || lines[0].text.compare(0, 8, "%YAML:1.") != 0)
      return fail(1, "missing header '%YAML:1.0' (not an OpenCV FileStorage YAML file)");
    std::string current;
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const Line& l = lines[i];
      if (l.indent > 0) {
        if (current.empty()) return fail(l.number, "unexpected indented line '" + l.text + "'");
        entries[current].children.push_back(l);
        continue;
      }
      if (l.text == "---" || l.text == "...") continue;
      const std::size_t colon = l.text.find(':');
      const std::string key = colon == std::string::npos ? std::string() : l.text.substr(0, colon);
      if (key.empty() || key.find_first_of(" \t\"'{}[],") != std::string::npos ||
          (colon + 1 < l.text.size() && l.text[colon + 1] != ' '))
        return fail(l.number, "expected 'key: value', got '" + l.text + "'");
      if (entries.count(key) != 0U) return fail(l.number, "duplicate key '" + key + "'");
      Entry e;
      e.line = l.number;
      e.value = trim(l.text.substr(colon + 1));
      entries[key] = e;
      current = key;
    }
    return true;
  }

  bool integer(const std::string& text, int line, const std::string& what, long min_value, long max_value,
               int& out) {
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0)
      return fail(line, what + " has the wrong type: expected an integer, got '" + text + "'");
    if (v < min_value || v > max_value)
      return fail(line, what + " = " + text + " out of range [" + std::to_string(min_value) + ", " +
                            std::to_string(max_value) + "]");
    out = static_cast<int>(v);
    return true;
  }

  bool requiredInt(const std::map<std::string, Entry>& entries, const char* key, int& out) {
    const auto it = entries.find(key);
    if (it == entries.end()) return missing(key);
    if (!it->second.children.empty())
      return fail(it->second.children[0].number, std::string("unexpected indented line under '") + key + "'");
    return integer(it->second.value, it->second.line, key, 1, 1 << 20, out);
  }

  // !!opencv-matrix: rows, cols, dt (d or f), data: [ ... ] possibly over several lines.
  bool matrix(const std::map<std::string, Entry>& entries, const char* key, Matrix& m,
              std::vector<int>& lines) {
    const auto it = entries.find(key);
    if (it == entries.end()) return missing(key);
    const Entry& e = it->second;
    const std::string name(key);
    if (e.value != "!!opencv-matrix")
      return fail(e.line, name + " has the wrong type: expected '!!opencv-matrix', got '" + e.value + "'");
    bool has_rows = false;
    bool has_cols = false;
    bool has_dt = false;
    bool has_data = false;
    std::string data;
    std::vector<std::pair<std::size_t, int>> data_line_starts;  // offset in `data` -> file line
    bool in_data = false;
    for (const Line& l : e.children) {
      if (in_data) {
        data_line_starts.emplace_back(data.size(), l.number);
        data += " " + l.text;
        in_data = l.text.find(']') == std::string::npos;
        continue;
      }
      const std::size_t colon = l.text.find(':');
      const std::string field = colon == std::string::npos ? l.text : l.text.substr(0, colon);
      const std::string value = colon == std::string::npos ? std::string() : trim(l.text.substr(colon + 1));
      if (field == "rows" && !has_rows) {
        has_rows = integer(value, l.number, name + " rows", 1, 64, m.rows);
        if (!has_rows) return false;
      } else if (field == "cols" && !has_cols) {
        has_cols = integer(value, l.number, name + " cols", 1, 64, m.cols);
        if (!has_cols) return false;
      } else if (field == "dt" && !has_dt) {
        if (value != "d" && value != "f")
          return fail(l.number, std::string(name).append(" dt '").append(value).append(
                                    "' not supported (only d or f)"));
        has_dt = true;
      } else if (field == "data" && !has_data) {
        if (value.empty() || value[0] != '[') return fail(l.number, name + " data must be a list '[ ... ]'");
        has_data = true;
        data_line_starts.emplace_back(0, l.number);
        data = value.substr(1);
        in_data = value.find(']') == std::string::npos;
      } else {
        return fail(l.number, name + ": unexpected line '" + l.text + "'");
      }
    }
    const char* missing = !has_rows   ? "rows"
                          : !has_cols ? "cols"
                          : !has_dt   ? "dt"
                          : !has_data ? "data"
                                      : nullptr;
    if (missing != nullptr) return fail(e.line, name + ": missing key '" + missing + "'");
    const int last_line = data_line_starts.back().second;
    if (in_data) return fail(last_line, name + " data: missing closing ']'");
    const std::size_t close = data.find(']');
    if (!trim(data.substr(close + 1)).empty())
      return fail(last_line, name + " data: unexpected text after ']'");
    data.resize(close);
    // Split on commas; each value gets the line it started on.
    std::size_t pos = 0;
    std::size_t line_index = 0;  // moves forward with pos: linear in the number of lines
    const bool any_data = !trim(data).empty();
    while (pos <= data.size() && any_data) {
      if (static_cast<int>(m.data.size()) >= m.rows * m.cols)
        return fail(last_line, name + " data has more than rows x cols = " + std::to_string(m.rows * m.cols) +
                                   " values");
      std::size_t comma = data.find(',', pos);
      if (comma == std::string::npos) comma = data.size();
      while (line_index + 1 < data_line_starts.size() && data_line_starts[line_index + 1].first <= pos)
        ++line_index;
      const int line = data_line_starts[line_index].second;
      const std::string token = trim(data.substr(pos, comma - pos));
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (token.empty() || *end != '\0')
        return fail(line, std::string(name)
                              .append(" data[")
                              .append(std::to_string(m.data.size()))
                              .append("] is not a number: '")
                              .append(token)
                              .append("'"));
      if (!std::isfinite(v))
        return fail(line, name + " data[" + std::to_string(m.data.size()) + "] is not finite");
      m.data.push_back(v);
      lines.push_back(line);
      pos = comma + 1;
    }
    if (static_cast<int>(m.data.size()) != m.rows * m.cols)
      return fail(last_line, name + " data has " + std::to_string(m.data.size()) +
                                 " values, rows x cols = " + std::to_string(m.rows * m.cols));
    return true;
  }

 private:
  std::string m_path;
  LoadError m_error;
};

bool intrinsicsFromK(YamlReader& r, const Matrix& m, const std::vector<int>& lines, int key_line,
                     CameraIntrinsics& k) {
  if (m.rows != 3 || m.cols != 3)
    return r.fail(key_line,
                  "camera_matrix must be 3x3, got " + std::to_string(m.rows) + "x" + std::to_string(m.cols));
  const std::vector<double>& a = m.data;
  if (!(a[0] > 0.0)) return r.fail(lines[0], "camera_matrix fx (data[0]) out of range (must be > 0)");
  if (!(a[4] > 0.0)) return r.fail(lines[4], "camera_matrix fy (data[4]) out of range (must be > 0)");
  // Third row and K(1,0) are fixed in a pinhole camera matrix: anything else is not a calibration.
  const int fixed[] = {3, 6, 7, 8};
  for (const int i : fixed) {
    const double expected = i == 8 ? 1.0 : 0.0;
    if (std::fabs(a[i] - expected) > 1e-12)
      return r.fail(lines[i], "camera_matrix data[" + std::to_string(i) +
                                  "] = " + detail::formatDouble(a[i]) + " out of range (must be " +
                                  (i == 8 ? "1" : "0") + ")");
  }
  k.fx_px = a[0];
  k.fy_px = a[4];
  k.skew = a[1] / a[0];
  // OpenCV puts pixel centres on integers, visnav at +0.5 (CONVENTIONS.md).
  k.cx_px = a[2] + 0.5;
  k.cy_px = a[5] + 0.5;
  return true;
}

bool distortionFrom(YamlReader& r, const Matrix& m, const std::vector<int>& lines, int key_line,
                    Distortion& d) {
  const int n = m.rows * m.cols;
  if ((m.rows != 1 && m.cols != 1) || (n != 4 && n != 5 && n != 8 && n != 12 && n != 14))
    return r.fail(key_line, "distortion_coefficients must be 1xN or Nx1 with N = 4, 5, 8, 12 or 14, got " +
                                std::to_string(m.rows) + "x" + std::to_string(m.cols));
  for (int i = 5; i < n; ++i)
    if (m.data[i] != 0.0)
      return r.fail(lines[i], "distortion_coefficients data[" + std::to_string(i) +
                                  "] is non-zero: rational/thin-prism model not supported");
  // OpenCV's order: k1, k2, p1, p2[, k3, ...].
  d.k1 = m.data[0];
  d.k2 = m.data[1];
  d.p1 = m.data[2];
  d.p2 = m.data[3];
  d.k3 = n >= 5 ? m.data[4] : 0.0;
  return true;
}

}  // namespace

LoadError loadCameraOpenCvYaml(const std::string& path, CameraIntrinsics& out) {
  std::string text;
  if (LoadError e = readTextFile(path, text); !e.ok) return e;
  YamlReader r(path);
  std::map<std::string, Entry> entries;
  CameraIntrinsics k;
  Matrix km;
  Matrix dm;
  std::vector<int> k_lines;
  std::vector<int> d_lines;
  const bool ok = r.parseEntries(splitLines(text), entries) &&
                  r.requiredInt(entries, "image_width", k.width_px) &&
                  r.requiredInt(entries, "image_height", k.height_px) &&
                  r.matrix(entries, "camera_matrix", km, k_lines) &&
                  intrinsicsFromK(r, km, k_lines, entries["camera_matrix"].line, k) &&
                  r.matrix(entries, "distortion_coefficients", dm, d_lines) &&
                  distortionFrom(r, dm, d_lines, entries["distortion_coefficients"].line, k.distortion);
  if (!ok) return r.error();
  std::string problem;
  if (!checkIntrinsics(k, problem)) return LoadError::failure(path + ": " + problem);
  out = k;
  return LoadError::success();
}

}  // namespace visnav::io
