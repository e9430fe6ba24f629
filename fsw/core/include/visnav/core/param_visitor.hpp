// One parameter table, many uses: each parameter struct exposes `visit(Visitor&)` listing every field with
// its section, key, unit, range and description. The same list drives TOML loading with range checks
// (fsw/io/config_io), the generated table in config/PARAMETERS.md (visnav-params) and the defaults
// (the struct's initialisers). PX4's parameter yaml, without a code generator.
#pragma once

#include <cstdint>
#include <string>

namespace visnav {

struct ParamInfo {
  const char* section;
  const char* key;
  const char* unit;  ///< "px", "m", "deg", "-" (dimensionless), "count" ...
  double min;        ///< inclusive
  double max;        ///< inclusive
  const char* description;
};

/// Implemented by loaders and documenters. Enumerations are passed as an int index into a
/// '|'-separated list of names (e.g. "vertex|point_to_line"). Text values (device paths, ids) take their
/// length range from ParamInfo min/max; they are init-time settings (a std::string copy allocates).
class ParamVisitor {
 public:
  virtual ~ParamVisitor() = default;
  virtual void real(const ParamInfo& info, double& value) = 0;
  virtual void integer(const ParamInfo& info, int& value) = 0;
  virtual void boolean(const ParamInfo& info, bool& value) = 0;
  virtual void enumeration(const ParamInfo& info, const char* names, int& value) = 0;
  virtual void text(const ParamInfo& info, std::string& value) = 0;
};

}  // namespace visnav
