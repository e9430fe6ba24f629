// Shared by the visnavd tests: a temporary folder, a rendered sequence (visnav-synth, once per process) and
// configs written on the fly.
#pragma once

// Frames of approach_ci the visnavd tests share (one rendering for all of them).
#define VISNAV_APP_TEST_FRAMES 80

#include <string>

#include "visnav/app/visnav_config.hpp"

namespace visnav::app::test {

/// A fresh folder under $TMPDIR (or /tmp), removed with its contents on destruction.
class TempDir {
 public:
  explicit TempDir(const std::string& name);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return m_path; }
  /// Writes `text` to path()/name and returns the full path.
  std::string write(const std::string& name, const std::string& text) const;

 private:
  std::string m_path;
};

/// The first `frames` frames of config/scenarios/approach_ci.toml rendered by visnav-synth into the build
/// tree's test data (once per build: later calls and other test processes reuse it). Empty on failure.
/// 80 frames take the pipeline through every mode: far range until frame 63, acquisition, near range.
std::string renderedApproachCi(int frames);

/// tests/fsw/app/hover_15m.toml rendered (2 frames 1 cm apart at 15 m): looped, a near-range steady state.
std::string renderedHover();

/// Any scenario file, `frames` of it (-1: all), rendered like renderedApproachCi().
std::string renderedSequence(const std::string& scenario, int frames);

/// Loads a config from text (written to `dir`); fails the current test on error.
VisnavConfig configFromText(const TempDir& dir, const std::string& text);

}  // namespace visnav::app::test
