#include "visnav/synthetic/scenario_camera.hpp"

#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::synthetic {

LoadError ScenarioCamera::open() {
  m_camera.close();
  synth::Scenario scenario;
  SyntheticCameraConfig config;
  LoadError e = synth::loadScenario(m_options.scenario_path, scenario);
  if (e.ok) e = io::loadCamera(scenario.camera_path, config.camera);
  if (e.ok) e = io::loadModel(scenario.model_path, config.model);
  if (!e.ok) return e;
  m_scenario = std::move(scenario);
  m_trajectory.trajectory = m_scenario.trajectory;
  config.render = m_scenario.render;
  config.trajectory = &m_trajectory;
  config.seed = m_scenario.seed;
  config.bit_depth = m_scenario.bit_depth;
  config.max_code = m_scenario.max_code;
  config.pacing = m_options.pacing;
  config.loop = m_options.loop;
  config.ring_size = m_options.ring_size;
  m_config = config;
  m_camera.configure(m_config);
  return m_camera.open();
}

}  // namespace visnav::synthetic
