// Shared by the libvisnav tests: the shortened 750 m -> 5 m approach (config/scenarios/full_approach_ci.toml)
// rendered once into memory (every mode: far range, acquisition, near range), and the files it flies with.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace visnav::test {

struct RenderedFrame {
  std::vector<std::uint8_t> pixels;  ///< tightly packed 8-bit rows
  std::int64_t exposure_time_ns = 0;
};

struct RenderedSequence {
  int width = 0;
  int height = 0;
  std::vector<RenderedFrame> frames;
};

/// Renders config/scenarios/full_approach_ci.toml (198 VGA frames) through the synthetic camera.
const RenderedSequence& fullApproachFrames();

inline std::string sourcePath(const char* relative) {
  return std::string(VISNAV_SOURCE_DIR) + "/" + relative;
}
inline std::string configPath() { return sourcePath("config/full_approach.toml"); }
inline std::string cameraPath() { return sourcePath("config/cameras/vga_6mm.toml"); }
inline std::string modelPath() { return sourcePath("config/models/plate_2300x1800.toml"); }

}  // namespace visnav::test
