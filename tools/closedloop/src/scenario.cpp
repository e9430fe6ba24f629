#include "visnav/closedloop/scenario.hpp"

namespace visnav::closedloop {

bool presetScenario(const std::string& name, const std::string& config_dir, ScenarioParams& out) {
  ScenarioParams p;
  p.name = name;
  if (name == "ci") {
    p.start_range_m = 60.0;
    p.max_time_s = 300.0;
  } else if (name == "200") {
    p.start_range_m = 200.0;
    p.max_time_s = 600.0;
  } else if (name == "750") {
    p.start_range_m = 750.0;
    p.max_time_s = 1200.0;
  } else {
    return false;
  }
  p.config_path = config_dir + "/closedloop.toml";
  p.camera_path = config_dir + "/cameras/vga_6mm.toml";
  p.model_path = config_dir + "/models/plate_2300x1800.toml";
  out = p;
  return true;
}

}  // namespace visnav::closedloop
