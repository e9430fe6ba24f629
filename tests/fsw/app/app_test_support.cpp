#include "app_test_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace visnav::app::test {

TempDir::TempDir(const std::string& name) {
  const char* base = std::getenv("TMPDIR");
  std::string pattern = std::string(base != nullptr ? base : "/tmp") + "/visnav-" + name + "-XXXXXX";
  if (mkdtemp(pattern.data()) != nullptr) m_path = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;  // a temporary folder left behind is not a test failure
  if (!m_path.empty()) std::filesystem::remove_all(m_path, ignored);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  std::string path = m_path + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string renderedSequence(const std::string& scenario, int frames) {
  // Rendered once per build tree: a debug frame costs ~0.1 s. Rendered into a private folder first and then
  // renamed into place, so concurrent test processes never see half a sequence.
  const std::size_t slash = scenario.rfind('/');
  const std::string stem = scenario.substr(slash + 1, scenario.size() - slash - 1 - 5);  // without ".toml"
  std::string out =
      std::string(VISNAV_TEST_DATA_DIR) + "/" + stem + (frames > 0 ? "_" + std::to_string(frames) : "");
  if (access((out + "/sequence.toml").c_str(), R_OK) == 0) return out;
  std::error_code exists;  // created by a concurrent test process: fine
  std::filesystem::create_directories(VISNAV_TEST_DATA_DIR, exists);
  const std::string staging = out + ".tmp-" + std::to_string(getpid());
  const std::string command = std::string(VISNAV_SYNTH) + " --scenario " + scenario + " --out " + staging +
                              (frames > 0 ? " --frames " + std::to_string(frames) : std::string()) +
                              " > /dev/null";
  if (std::system(command.c_str()) != 0) return "";
  if (std::rename(staging.c_str(), out.c_str()) != 0)  // another process was first: use its copy
    std::filesystem::remove_all(staging, exists);
  return access((out + "/sequence.toml").c_str(), R_OK) == 0 ? out : "";
}

std::string renderedApproachCi(int frames) {
  return renderedSequence(std::string(VISNAV_SOURCE_DIR) + "/config/scenarios/approach_ci.toml", frames);
}

std::string renderedHover() {
  return renderedSequence(std::string(VISNAV_SOURCE_DIR) + "/tests/fsw/app/hover_15m.toml", -1);
}

VisnavConfig configFromText(const TempDir& dir, const std::string& text) {
  static int count = 0;
  VisnavConfig config;
  const std::string path = dir.write("config" + std::to_string(count++) + ".toml", text);
  const LoadError e = loadVisnavConfig(path, config);
  EXPECT_TRUE(e.ok) << e.message;
  return config;
}

}  // namespace visnav::app::test
