// Cost of acquisition per cycle (fsw/acquisition/README.md: bounded in time, spread over several frames).
// Run:
//   build/h-acq-rel/bin/bench_acquisition --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and read the *_median rows. The search step is the steady cost of the first frames (hypotheses_per_cycle
// hypotheses), the verify step the one frame that refines and tracker-checks the survivors, the whole
// acquisition the sum over every frame from start() to success.
#include <benchmark/benchmark.h>

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
  w.init(256, 2048);
  // 5 m: the largest window the defaults build (box factor 6, ~170 x 170 working px).
  w.setWindow(Vec2(320.0, 240.0), 500.0, 6);
  for (auto _ : state) {
    w.prepare(b.frames[0].image(), 2, 8, 4.0);
    benchmark::DoNotOptimize(w.stats());
  }
  state.counters["side_px"] = w.width();
}
BENCHMARK(BM_PrepareWindow)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace visnav

BENCHMARK_MAIN();
