// Strict TOML reading for replay/synthetic configs: every value is fetched by a dotted key, wrong types and
// out-of-range values are reported with file and line, and keys nobody asked for are rejected at finish()
// (a typo in a config must never silently fall back to a default). Init-time only: allocates.
#pragma once

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"

namespace visnav::replay {

class TomlReader {
 public:
  TomlReader();
  ~TomlReader();
  TomlReader(const TomlReader&) = delete;
  TomlReader& operator=(const TomlReader&) = delete;

  /// Parses the file; a syntax error is reported as "file:line: problem".
  LoadError open(const std::string& path);

  /// Getters: `out` is only written when the key is present and valid. A missing optional key leaves the
  /// default in `out`. The first error is kept and returned by finish(); later calls are no-ops.
  void getDouble(const std::string& key, double& out, bool required = false);
  void getInt(const std::string& key, std::int64_t& out, bool required = false);
  void getInt(const std::string& key, int& out, bool required = false);
  void getBool(const std::string& key, bool& out, bool required = false);
  void getString(const std::string& key, std::string& out, bool required = false);
  /// Array of exactly n numbers.
  void getVector(const std::string& key, double* out, int n, bool required = false);
  /// Array of numbers of any length (at most max_size).
  void getArray(const std::string& key, std::vector<double>& out, std::size_t max_size,
                bool required = false);
  bool has(const std::string& key) const;
  /// True while no error has been recorded (use before value checks that depend on earlier keys).
  bool good() const { return m_error.ok; }

  /// Records "file:line: key: problem" unless an error is already recorded (for range checks).
  void fail(const std::string& key, const std::string& problem);
  /// Range check helper: fails with "must be in [lo, hi]" when value is outside.
  void checkRange(const std::string& key, double value, double lo, double hi);

  /// First error, or an "unknown key" error for any leaf key no getter asked for.
  LoadError finish();
  const std::string& path() const { return m_path; }

 private:
  struct Impl;  // hides toml++ from users of this header

  std::string m_path;
  std::unique_ptr<Impl> m_impl;
  std::set<std::string> m_used;
  LoadError m_error;
};

}  // namespace visnav::replay
