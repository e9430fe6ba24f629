// Small helpers shared by the two far-range tools: parameter loading and method names (numbers:
// visnav/cli/numbers.hpp).
#pragma once

#include <string>

#include "visnav/core/status.hpp"
#include "visnav/farrange/far_range_params.hpp"
#include "visnav/io/config_io.hpp"

namespace visnav::far_eval {

/// Table 1 defaults, then the [farrange] table of `config_path` (if given); other tables are ignored here
/// (visnav-params --check validates whole files).
inline LoadError loadFarParams(const std::string& config_path, far::FarRangeParams& params) {
  params = far::FarRangeParams{};
  if (config_path.empty()) return LoadError::success();
  io::ConfigFile config;
  LoadError e = config.open(config_path);
  if (e.ok) e = config.apply(params);
  return e;
}

/// "paper" / "robust" -> FarRangeMethod index, -1 otherwise.
inline int methodIndex(const std::string& name) {
  if (name == "paper") return static_cast<int>(far::FarRangeMethod::kPaper);
  if (name == "robust") return static_cast<int>(far::FarRangeMethod::kRobust);
  return -1;
}

}  // namespace visnav::far_eval
