// Speed of the far-range step (targets: < 0.5 ms median at VGA, < 1 ms at 1024x768, one core) and of
// each stage. Run: build/release/bin/bench_farrange --benchmark_repetitions=10
//   --benchmark_report_aggregates_only=true ; read the *_median rows. The scene: the far_range satellite at
// 300 m with the scenario's noise (full-frame search unless the name says roi).
#include <benchmark/benchmark.h>

#include "../fsw/farrange/far_fixture.hpp"
#include "visnav/executive/clock.hpp"

namespace visnav {
namespace {

struct Scene {
  PinholeCamera camera;
  test::FarFrame frame;
  Scene(int w, int h) : camera(test::farCamera(w, h)) {
    synthetic::Renderer renderer;
    renderer.init(camera, test::smallsat(), test::farRender());
    frame = test::renderFar(renderer, test::satAt(300.0, 2.0, 1.0, 20.0), 7);
  }
};

const Scene& scene(int w) {
  static const Scene vga(640, 480);
  static const Scene xga(1024, 768);
  return w == 640 ? vga : xga;
}

far::FarRangeParams paramsFor(int method, bool roi) {
  far::FarRangeParams p;
  p.method = method;
  p.use_roi = roi;
  return p;
}

// Args: width, height, method (0 paper, 1 robust), roi (robust: tracked target, region of interest).
void BM_FarRangeStep(benchmark::State& state) {
  const Scene& s = scene(static_cast<int>(state.range(0)));
  far::FarRangeEstimator estimator;
  estimator.init(s.camera, paramsFor(static_cast<int>(state.range(2)), state.range(3) != 0));
  estimator.setClock(&exec::monotonicNowNs);
  far::FarRangeResult r;
  estimator.estimate(s.frame.image(), r);  // establishes the track for the ROI variant
  far::FarRangeTiming sum;
  for (auto _ : state) {
    estimator.estimate(s.frame.image(), r);
    benchmark::DoNotOptimize(r);
    sum.edge_us += r.timing.edge_us;
    sum.histogram_us += r.timing.histogram_us;
    sum.combine_us += r.timing.combine_us;
    sum.cluster_us += r.timing.cluster_us;
    sum.select_us += r.timing.select_us;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["edge_us"] = sum.edge_us / n;
  state.counters["histogram_us"] = sum.histogram_us / n;
  state.counters["combine_us"] = sum.combine_us / n;
  state.counters["cluster_us"] = sum.cluster_us / n;
  state.counters["select_us"] = sum.select_us / n;
  state.counters["valid"] = r.valid ? 1 : 0;
  state.counters["roi_px"] = static_cast<double>(r.roi.area());
  state.SetLabel(std::string(state.range(2) == 0 ? "paper" : "robust") +
                 (state.range(3) != 0 ? " roi" : " full"));
}
BENCHMARK(BM_FarRangeStep)
    ->Args({640, 480, 0, 0})
    ->Args({640, 480, 1, 0})
    ->Args({640, 480, 1, 1})
    ->Args({1024, 768, 1, 0})
    ->Args({1024, 768, 1, 1})
    ->Unit(benchmark::kMicrosecond);

// Per-filter cost on the full VGA frame.
void BM_EdgeFilter(benchmark::State& state) {
  const Scene& s = scene(640);
  far::EdgeFilter filter;
  far::EdgeFilterSettings settings;
  settings.kernel = static_cast<far::EdgeKernel>(state.range(0));
  settings.percentile = state.range(1) != 0 ? 99.5 : 100.0;
  filter.init(640, 480, settings);
  far::ResponseImage out;
  out.init(640, 480);
  const far::Roi roi = far::Roi::full(640, 480);
  out.setRoi(roi);
  for (auto _ : state) {
    filter.apply(s.frame.image(), roi, out);
    benchmark::DoNotOptimize(out.row(0));
  }
  state.SetLabel(std::string(state.range(0) == 0 ? "sobel" : "prewitt") +
                 (state.range(1) != 0 ? " percentile" : " max"));
}
BENCHMARK(BM_EdgeFilter)->Args({0, 0})->Args({0, 1})->Args({1, 0})->Unit(benchmark::kMicrosecond);

// Arg: [farrange] background_block_px (0: eq. 11 over the grey level as printed).
void BM_HistogramFilter(benchmark::State& state) {
  const Scene& s = scene(640);
  far::HistogramFilter filter;
  filter.init(100.0);
  filter.setBackgroundBlock(static_cast<int>(state.range(0)), 640, 480);
  far::ResponseImage out;
  out.init(640, 480);
  const far::Roi roi = far::Roi::full(640, 480);
  out.setRoi(roi);
  for (auto _ : state) {
    filter.apply(s.frame.image(), roi, out);
    benchmark::DoNotOptimize(out.row(0));
  }
}
BENCHMARK(BM_HistogramFilter)->Arg(0)->Arg(128)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace visnav

BENCHMARK_MAIN();
