// Loads parameter tables (structs with `visit(ParamVisitor&)`, e.g. NearRangeParams) from one TOML config
// file. Missing keys keep their defaults; a wrong type, an out-of-range value or an unknown key (a typo must
// never be silently ignored) is an error naming file, line and key. Init-time only.
#pragma once

#include <memory>
#include <string>

#include "visnav/core/param_visitor.hpp"
#include "visnav/core/status.hpp"

namespace visnav::io {

class ConfigFile {
 public:
  ConfigFile();
  ~ConfigFile();
  ConfigFile(const ConfigFile&) = delete;
  ConfigFile& operator=(const ConfigFile&) = delete;

  LoadError open(const std::string& path);
  /// Reads every parameter the struct lists into a copy; assigns to `params` only when all are valid.
  template <typename Params>
  LoadError apply(Params& params) {
    Params copy = params;
    LoadError error = applyVisitor([&copy](ParamVisitor& v) { copy.visit(v); });
    if (!error.ok) return error;
    if (const char* problem = copy.crossCheck()) return LoadError::failure(m_path + ": " + problem);
    params = copy;
    return LoadError::success();
  }
  /// After every apply(): fails on any key that no parameter table claimed.
  LoadError checkNoUnknownKeys() const;
  /// Raw access for non-parameter settings (file names and the like): empty string when absent.
  std::string stringValue(const char* section, const char* key) const;
  /// Same, telling an absent key (present = false) from an empty string; a non-string value is an error.
  LoadError stringValue(const char* section, const char* key, std::string& out, bool& present) const;

 private:
  template <typename F>
  LoadError applyVisitor(F&& visit_all) {
    return applyErased(
        +[](void* f, ParamVisitor& v) { (*static_cast<F*>(f))(v); }, &visit_all);
  }
  LoadError applyErased(void (*call)(void*, ParamVisitor&), void* fn);

  struct Impl;
  std::unique_ptr<Impl> m_impl;
  std::string m_path;
};

}  // namespace visnav::io
