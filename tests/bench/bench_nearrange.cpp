// Speed of the near-range step (targets: whole step < 0.1 ms median at VGA with the 4-edge plate,
// LM solve < 20 us). Run: build/release/bin/bench_nearrange --benchmark_repetitions=10
//   --benchmark_report_aggregates_only=true ; read the *_median rows. Counters give the per-stage split.
#include <benchmark/benchmark.h>

#include <ctime>

#include "../fsw/nearrange/tracker_fixture.hpp"

namespace visnav {
namespace {

std::int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

struct Scene {
  PolygonModel model = makeRectanglePlate(2.3, 1.8);
  Pose truth = test::plateAt(12.0, 0.15, 2.0, -1.5);
  test::RenderedFrame frame;
  Scene() {
    synthetic::Renderer renderer;
    renderer.init(test::vgaCamera(), model, synthetic::RenderOptions{});
    frame = test::renderFrame(renderer, truth, 42);
  }
};

const Scene& scene() {
  static const Scene s;
  return s;
}

void BM_NearRangeStep(benchmark::State& state) {
  const Scene& s = scene();
  NearRangeParams params;
  params.pose_residual = static_cast<int>(state.range(0));
  NearRangeTracker tracker;
  tracker.init(test::vgaCamera(), s.model, params);
  tracker.setClock(&monotonicNs);
  NearRangeResult r;
  NearRangeTiming sum;
  std::uint64_t frame = 0;
  for (auto _ : state) {
    tracker.track(s.frame.image(), s.truth, frame++, r);
    benchmark::DoNotOptimize(r);
    sum.project_us += r.timing.project_us;
    sum.scan_us += r.timing.scan_us;
    sum.ransac_us += r.timing.ransac_us;
    sum.pose_us += r.timing.pose_us;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["project_us"] = sum.project_us / n;
  state.counters["scan_us"] = sum.scan_us / n;
  state.counters["ransac_us"] = sum.ransac_us / n;
  state.counters["pose_us"] = sum.pose_us / n;
  state.counters["edge_points"] = r.edge_points;
  state.counters["tracked"] = r.status == TrackStatus::kLost ? 0 : 1;
  state.SetLabel(params.pose_residual == 0 ? "vertex residual" : "point-to-line residual");
}
BENCHMARK(BM_NearRangeStep)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_LmSolveVertices(benchmark::State& state) {
  const Scene& s = scene();
  const PinholeCamera cam = test::vgaCamera();
  VertexObservation obs[4];
  for (int i = 0; i < 4; ++i) {
    obs[i].vertex = i;
    cam.projectIdeal(s.truth.transform(s.model.vertices()[i]), obs[i].px_ideal);
    obs[i].px_ideal += Vec2(0.1 * (i % 2), -0.1 * (i / 2));
  }
  Vec6 offset;
  offset << 0.002, -0.002, 0.003, 0.01, -0.01, 0.05;  // a typical inter-frame prediction error
  PoseFitResult result;
  for (auto _ : state) {
    Pose pose = s.truth.boxPlus(offset);
    fitPoseToVertices(cam, s.model, obs, 4, LmOptions{}, 0.1, pose, result);
    benchmark::DoNotOptimize(pose);
  }
  state.counters["lm_iterations"] = result.lm.iterations;
}
BENCHMARK(BM_LmSolveVertices)->Unit(benchmark::kMicrosecond);

void BM_EdgeOnScanline(benchmark::State& state) {
  const Scene& s = scene();
  double samples[kMaxScanlineSamples];
  const Vec2 centre(320.0, 240.0);
  EdgeHit hit;
  for (auto _ : state) {
    sampleScanline(s.frame.image(), centre, Vec2(1.0, 0.0), 7, samples);
    hit = findEdge(samples, 15, EdgeSearchParams{}, 0);
    benchmark::DoNotOptimize(hit);
  }
}
BENCHMARK(BM_EdgeOnScanline)->Unit(benchmark::kNanosecond);

}  // namespace
}  // namespace visnav

BENCHMARK_MAIN();
