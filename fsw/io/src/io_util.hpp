// Helpers shared by the fsw/io loaders (internal, not installed): error text, number formatting and the
// TOML access layer that turns every problem into "<path>:<line>: <problem>".
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/io/text_file.hpp"

namespace visnav::io::detail {

/// Lower-case extension with its dot ("".toml"), empty if none.
std::string extensionOf(const std::string& path);
/// Shortest of 15..17 significant digits that reads back to the same double; always a TOML/YAML float
/// (has a '.' or an exponent). Only for finite values.
std::string formatDouble(double value);
/// Writes `text` to `path` (truncating). Failure message names the file.
LoadError writeTextFile(const std::string& path, const std::string& text);

/// Prefixes a PolygonModel::build message with the file and, when it starts with "surface <i>", with the
/// line where that surface is defined (`surface_lines[i]`, 0 if unknown).
LoadError buildError(const std::string& path, const std::string& message,
                     const std::vector<int>& surface_lines);

/// Reads (bounded, regular files only), checks (checkTomlAscii) and parses a TOML file; a syntax error
/// becomes "<path>:<line>:<column>: <problem>".
LoadError parseTomlFile(const std::string& path, toml::table& root);

/// First-error collector for TOML semantic checks. Every getter returns false after recording an error.
class TomlChecker {
 public:
  explicit TomlChecker(std::string path) : m_path(std::move(path)) {}

  const std::string& path() const { return m_path; }
  const LoadError& error() const { return m_error; }

  bool fail(const toml::node& where, const std::string& problem);
  bool fail(const toml::source_region& where, const std::string& problem);
  bool failNoLine(const std::string& problem);

  /// Rejects keys not in `allowed` (catches typos such as "albeod" instead of silently using defaults).
  bool onlyKeys(const toml::table& table, const std::string& table_name,
                std::initializer_list<const char*> allowed);
  /// Sub-table `key` of `parent`; missing -> error when `required`, else `out` = nullptr and true.
  bool table(const toml::table& parent, const std::string& parent_name, const char* key, bool required,
             const toml::table*& out);
  /// Finite number (TOML integer or float). `present` tells whether the key was there when optional.
  bool number(const toml::table& table, const std::string& table_name, const char* key, bool required,
              double& out, bool* present = nullptr);
  bool number(const toml::node& node, const std::string& what, double& out);
  bool integer(const toml::table& table, const std::string& table_name, const char* key, bool required,
               std::int64_t& out, bool* present = nullptr);
  bool integer(const toml::node& node, const std::string& what, std::int64_t& out);
  bool string(const toml::table& table, const std::string& table_name, const char* key, bool required,
              std::string& out, bool* present = nullptr);
  bool array(const toml::table& table, const std::string& table_name, const char* key, bool required,
             const toml::array*& out);
  /// [x, y, z] of finite numbers.
  bool vec3(const toml::node& node, const std::string& what, Vec3& out);

 private:
  const toml::node* find(const toml::table& table, const std::string& table_name, const char* key,
                         bool required, bool* present);

  std::string m_path;
  LoadError m_error;
};

}  // namespace visnav::io::detail
