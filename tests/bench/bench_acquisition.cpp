// Cost of acquisition per cycle (fsw/acquisition/README.md: bounded in time, spread over several frames).
// Run:
//   build/h-acq-rel/bin/bench_acquisition --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and read the *_median rows. The search step is the steady cost of the first frames (hypotheses_per_cycle
// hypotheses), the verify step the one frame that refines and tracker-checks the survivors, the whole
// acquisition the sum over every frame from start() to success.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "../fsw/acquisition/acquisition_fixture.hpp"

namespace visnav {
namespace {

struct Bench {
  test::Scene scene;
  Pose truth;
  std::vector<test::RenderedFrame> frames;
  FarRangeSolution cue;
  explicit Bench(test::Target target) : scene(test::makeScene(target)) {
    truth = Pose{test::tiltedAttitude(20.0, 30.0, 40.0), Vec3(0.2, -0.1, 12.0)};
    synthetic::Renderer renderer;
    renderer.init(test::vgaCamera(), scene.model, scene.render);
    frames = test::renderStatic(renderer, truth, 2, 42);
    cue = test::perturbedCue(truth, 1.0, 30.0, 0.2);
  }
};

const Bench& bench(int target) {
  static const Bench plate(test::Target::kPlate);
  static const Bench box(test::Target::kBox);
  return target == 0 ? plate : box;
}

void label(benchmark::State& state, const acq::Acquisition& a) {
  state.SetLabel(state.range(0) == 0 ? "plate" : "shaded box");
  state.counters["hypotheses"] = a.hypothesisCount();
}

void BM_AcquisitionSearchStep(benchmark::State& state) {
  const Bench& b = bench(static_cast<int>(state.range(0)));
  acq::Acquisition a;
  a.init(test::vgaCamera(), b.scene.model, acq::AcquisitionParams{}, NearRangeParams{});
  acq::AcquisitionResult r;
  for (auto _ : state) {
    state.PauseTiming();
    a.start(b.cue);
    state.ResumeTiming();
    a.step(b.frames[0].image(), 0, r);
    benchmark::DoNotOptimize(r);
  }
  label(state, a);
  state.counters["scored"] = r.hypotheses_scored;
}
BENCHMARK(BM_AcquisitionSearchStep)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_AcquisitionVerifyStep(benchmark::State& state) {
  const Bench& b = bench(static_cast<int>(state.range(0)));
  acq::Acquisition a;
  a.init(test::vgaCamera(), b.scene.model, acq::AcquisitionParams{}, NearRangeParams{});
  acq::AcquisitionResult r;
  for (auto _ : state) {
    state.PauseTiming();
    a.start(b.cue);
    for (int i = 0; a.state() == acq::AcquisitionState::kSearching && i < 100; ++i)
      a.step(b.frames[0].image(), 0, r);
    state.ResumeTiming();
    a.step(b.frames[1].image(), 1, r);
    benchmark::DoNotOptimize(r);
  }
  label(state, a);
  state.counters["score_evaluations"] = r.score_evaluations;
  state.counters["tracker_calls"] = r.tracker_calls;
}
BENCHMARK(BM_AcquisitionVerifyStep)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_WholeAcquisition(benchmark::State& state) {
  const Bench& b = bench(static_cast<int>(state.range(0)));
  acq::Acquisition a;
  a.init(test::vgaCamera(), b.scene.model, acq::AcquisitionParams{}, NearRangeParams{});
  test::AcquisitionRun run;
  for (auto _ : state) {
    run = test::runAcquisition(a, b.scene, b.frames, b.cue);
    benchmark::DoNotOptimize(run);
  }
  label(state, a);
  state.counters["frames"] = run.steps;
  state.counters["succeeded"] = run.succeeded() ? 1 : 0;
}
BENCHMARK(BM_WholeAcquisition)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_PrepareWindow(benchmark::State& state) {
  const Bench& b = bench(0);
  acq::WorkingImage w;
  w.init(256, 2048, 1280);
  // 5 m: the largest window the defaults build (box factor 6, ~170 x 170 working px).
  w.setWindow(Vec2(320.0, 240.0), 500.0, 6);
  for (auto _ : state) {
    w.prepare(b.frames[0].image(), 2, 8, 4.0);
    benchmark::DoNotOptimize(w.stats());
  }
  state.counters["side_px"] = w.width();
}
BENCHMARK(BM_PrepareWindow)->Unit(benchmark::kMicrosecond);

// What the close-range reacquisition's outline cue adds to a search frame (fsw/navigation/README.md): the
// window over the searched disc (radius = the argument, px; box-averaged to <= 160 working px a side, as
// LocalReacquisition::findCues does) and the plate's outline slid over it (3 peaks).
void BM_OutlineCue(benchmark::State& state) {
  const Bench& b = bench(0);
  const double radius_px = static_cast<double>(state.range(0));
  acq::WorkingImage window;
  window.init(160, 256, 1280);
  acq::EdgeScorer scorer;
  scorer.init(test::vgaCamera(), b.scene.model, acq::ScorerSettings{64, 0.5});
  Vec2 centre;
  test::vgaCamera().project(b.truth.t_c_m, centre);
  const double target_radius_px = 1000.0 * b.scene.model.boundingRadius() / b.truth.t_c_m.z();
  const double half_px = radius_px + 1.2 * target_radius_px;
  const int scale = std::max({1, static_cast<int>(std::ceil(2.0 * half_px / 160.0)),
                              static_cast<int>(target_radius_px / 32.0 + 0.5)});
  std::array<acq::ShiftPeak, 3> peaks{};
  int found = 0;
  for (auto _ : state) {
    const int used = window.setWindow(centre, half_px, scale);
    window.prepare(b.frames[0].image(), 2, 8, 4.0);
    found = scorer.bestShifts(b.truth, window, radius_px / used, 4.0, 8.0, peaks.data(), 3);
    benchmark::DoNotOptimize(peaks);
  }
  state.counters["peaks"] = found;
}
BENCHMARK(BM_OutlineCue)->Arg(100)->Arg(300)->Arg(600)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace visnav

BENCHMARK_MAIN();
