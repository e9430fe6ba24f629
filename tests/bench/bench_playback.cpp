// Cost of one acquire() + release() of the playback cameras at VGA (what a replay or a synthetic "live" run
// spends in the acquire task): ReplayCamera reads a PGM from the page cache, SyntheticCamera renders the
// approach_ci scenario. Run: build/release/bin/bench_playback --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true ; read the *_median rows.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "visnav/replay/replay_camera.hpp"
#include "visnav/synthetic/scenario_camera.hpp"

namespace visnav {
namespace {

const std::string kScenario = std::string(VISNAV_SOURCE_DIR) + "/config/scenarios/approach_ci.toml";

// Eight VGA frames of the approach scenario, written once per process.
class VgaSequence {
 public:
  VgaSequence() {
    m_dir = (std::filesystem::temp_directory_path() / ("visnav_bench_playback_" + std::to_string(::getpid())))
                .string();
    synthetic::ScenarioCamera source({kScenario, camera::Pacing::kAsFastAsPossible, false, 2});
    if (!source.open().ok) return;
    replay::SequenceWriter writer;
    const synthetic::SyntheticCameraConfig& c = source.config();
    if (!writer.open(m_dir, "bench", c.camera, c.model, 8, 255, 5.0).ok) return;
    for (int i = 0; i < 8; ++i) {
      Frame f;
      if (source.acquire(0, f) != camera::AcquireResult::kFrame) return;
      replay::writePgm8(writer.framePath(i), f.image.u8);
      writer.addFrame(i, i * 200000000LL, nullptr);
      source.release(f);
    }
    m_ok = writer.close().ok;
  }
  ~VgaSequence() { std::filesystem::remove_all(m_dir); }
  const std::string& dir() const { return m_dir; }
  bool ok() const { return m_ok; }

 private:
  std::string m_dir;
  bool m_ok = false;
};

void BM_ReplayAcquireVga(benchmark::State& state) {
  static const VgaSequence sequence;
  replay::ReplayCamera cam({sequence.dir(), camera::Pacing::kAsFastAsPossible, true, 2});
  if (!sequence.ok() || !cam.open().ok) {
    state.SkipWithError("cannot build the sequence");
    return;
  }
  for (auto _ : state) {
    Frame f;
    if (cam.acquire(0, f) != camera::AcquireResult::kFrame) state.SkipWithError(cam.lastError());
    benchmark::DoNotOptimize(f.image.u8.at(320, 240));
    cam.release(f);
  }
}
BENCHMARK(BM_ReplayAcquireVga)->Unit(benchmark::kMicrosecond);

void BM_SyntheticAcquireVga(benchmark::State& state) {
  synthetic::ScenarioCamera cam({kScenario, camera::Pacing::kAsFastAsPossible, true, 2});
  if (!cam.open().ok) {
    state.SkipWithError("cannot open the scenario");
    return;
  }
  for (auto _ : state) {
    Frame f;
    if (cam.acquire(0, f) != camera::AcquireResult::kFrame) state.SkipWithError(cam.lastError());
    benchmark::DoNotOptimize(f.image.u8.at(320, 240));
    cam.release(f);
  }
}
BENCHMARK(BM_SyntheticAcquireVga)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace visnav

BENCHMARK_MAIN();
