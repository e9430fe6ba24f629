// Per-stage executed arm64 instructions of the near-range and far-range steps at VGA, and the Cortex-A53
// time they estimate. Run under the counting plugin (scripts/arm-cost.sh does it):
//   qemu-aarch64 -plugin build/aarch64/lib/libinsncount.so build/aarch64/bin/visnav-arm-cost [--frames N]
//       [--ipc X] [--ipc-low X] [--clock-ghz G] [--cycle-ms T]
// The components' stage clocks are pointed at the instruction counter (insn_counter.hpp), so their timing
// fields give instructions per stage. Exit 1 when the plugin is absent or the counts are inconsistent
// (stages must add up to no more than the step; the step without clock must match the instrumented one).
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "../fsw/farrange/far_fixture.hpp"
#include "../fsw/nearrange/tracker_fixture.hpp"
#include "insn_counter.hpp"

namespace visnav::armcost {
namespace {

struct Options {
  int frames = 5;           // measured frames (after kWarmupFrames)
  double ipc = 0.8;         // central A53 estimate (README: rationale)
  double ipc_low = 0.5;     // pessimistic A53 estimate
  double clock_ghz = 1.2;   // flight computer's A53 clock
  double cycle_ms = 200.0;  // 5 Hz navigation cycle
};
constexpr int kWarmupFrames = 2;
constexpr int kMaxStages = 6;

struct StageTable {
  const char* names[kMaxStages] = {};
  double sum_insns[kMaxStages] = {};  // over the measured frames, clock overhead removed
  int stages = 0;
  double total_insns = 0.0;  // instrumented step, clock overhead removed
  double plain_insns = 0.0;  // step without a clock (loop of the same frames)
};

std::int64_t g_overhead = 0;  // instructions one clock read adds to an interval

double intervalInsns(double timing_us) {
  return std::round(timing_us * 1000.0) - static_cast<double>(g_overhead);
}

void printRow(const Options& o, const char* name, double insns) {
  const double per_s_central = o.ipc * o.clock_ghz * 1e9;
  const double per_s_low = o.ipc_low * o.clock_ghz * 1e9;
  const double ms = insns / per_s_central * 1e3;
  const double ms_low = insns / per_s_low * 1e3;
  std::printf("  %-28s %14.0f %12.3f %12.3f %9.2f %%\n", name, insns, ms, ms_low, 100.0 * ms / o.cycle_ms);
}

// Prints the table and returns false if it is inconsistent.
bool report(const Options& o, const char* title, const StageTable& t) {
  const double n = static_cast<double>(o.frames);
  std::printf("%s\n", title);
  double stage_sum = 0.0;
  for (int s = 0; s < t.stages; ++s) {
    printRow(o, t.names[s], t.sum_insns[s] / n);
    stage_sum += t.sum_insns[s] / n;
  }
  const double total = t.total_insns / n;
  printRow(o, "other (between stages)", total - stage_sum);
  printRow(o, "step (with stage clocks)", total);
  printRow(o, "step (no clock)", t.plain_insns);
  const double mismatch = std::fabs(t.plain_insns - total) / total;
  const bool ok = stage_sum <= total && total > 0.0 && mismatch < 0.02;
  if (!ok)
    std::printf("  INCONSISTENT: stages %.0f, step %.0f, no-clock step %.0f\n", stage_sum, total,
                t.plain_insns);
  return ok;
}

// Mean instructions of `frames` calls of `step(i)` with the component's clock unset.
template <typename Step>
double plainStep(int frames, Step&& step) {
  const std::int64_t before = insnCount();
  for (int i = 0; i < frames; ++i) step(i);
  const std::int64_t after = insnCount();
  return static_cast<double>(after - before - g_overhead) / frames;
}

bool nearRange(const Options& o) {
  const PolygonModel model = makeRectanglePlate(2.3, 1.8);
  const Pose truth = test::plateAt(12.0, 0.15, 2.0, -1.5);  // the bench_nearrange scene
  synthetic::Renderer renderer;
  renderer.init(test::vgaCamera(), model, synthetic::RenderOptions{});
  const test::RenderedFrame frame = test::renderFrame(renderer, truth, 42);
  NearRangeTracker tracker;
  tracker.init(test::vgaCamera(), model, NearRangeParams{});
  NearRangeResult r;
  std::uint64_t index = 0;
  for (int i = 0; i < kWarmupFrames; ++i) tracker.track(frame.image(), truth, index++, r);

  StageTable t;
  const char* names[] = {"project + visibility", "scanlines + edge points", "RANSAC lines", "pose (LM)"};
  t.stages = 4;
  for (int s = 0; s < t.stages; ++s) t.names[s] = names[s];
  tracker.setClock(&insnClock);
  for (int i = 0; i < o.frames; ++i) {
    const std::int64_t calls_before = insnClockCalls();
    tracker.track(frame.image(), truth, index++, r);
    const double calls = static_cast<double>(insnClockCalls() - calls_before);
    t.sum_insns[0] += intervalInsns(r.timing.project_us);
    t.sum_insns[1] += intervalInsns(r.timing.scan_us);
    t.sum_insns[2] += intervalInsns(r.timing.ransac_us);
    t.sum_insns[3] += intervalInsns(r.timing.pose_us);
    t.total_insns += std::round(r.timing.total_us * 1000.0) - (calls - 1.0) * static_cast<double>(g_overhead);
  }
  const bool tracked = r.status != TrackStatus::kLost;
  tracker.setClock(nullptr);
  const std::uint64_t first = index;
  t.plain_insns = plainStep(o.frames, [&](int i) {
    tracker.track(frame.image(), truth, first + static_cast<std::uint64_t>(i), r);
  });
  char title[160];
  std::snprintf(title, sizeof title,
                "near range: NearRangeTracker::track, plate at 12 m, VGA, vertex residual, %d edge points%s",
                r.edge_points, tracked ? "" : " (LOST)");
  return report(o, title, t) && tracked;
}

bool farRange(const Options& o, int method, bool roi, const char* label) {
  const PinholeCamera camera = test::farCamera(640, 480);
  synthetic::Renderer renderer;
  renderer.init(camera, test::smallsat(), test::farRender());
  const test::FarFrame frame =
      test::renderFar(renderer, test::satAt(300.0, 2.0, 1.0, 20.0), 7);  // bench scene
  far::FarRangeParams params;
  params.method = method;
  params.use_roi = roi;
  far::FarRangeEstimator estimator;
  estimator.init(camera, params);
  far::FarRangeResult r;
  for (int i = 0; i < kWarmupFrames; ++i) estimator.estimate(frame.image(), r);  // ROI: track established

  StageTable t;
  const char* names[] = {"edge filter (Sobel)", "histogram filter", "combine (eq. 13/14)", "clusters",
                         "select"};
  t.stages = 5;
  for (int s = 0; s < t.stages; ++s) t.names[s] = names[s];
  estimator.setClock(&insnClock);
  for (int i = 0; i < o.frames; ++i) {
    const std::int64_t calls_before = insnClockCalls();
    estimator.estimate(frame.image(), r);
    const double calls = static_cast<double>(insnClockCalls() - calls_before);
    t.sum_insns[0] += intervalInsns(r.timing.edge_us);
    t.sum_insns[1] += intervalInsns(r.timing.histogram_us);
    t.sum_insns[2] += intervalInsns(r.timing.combine_us);
    t.sum_insns[3] += intervalInsns(r.timing.cluster_us);
    t.sum_insns[4] += intervalInsns(r.timing.select_us);
    t.total_insns += std::round(r.timing.total_us * 1000.0) - (calls - 1.0) * static_cast<double>(g_overhead);
  }
  estimator.setClock(nullptr);
  t.plain_insns = plainStep(o.frames, [&](int) { estimator.estimate(frame.image(), r); });
  char title[160];
  std::snprintf(title, sizeof title,
                "far range: FarRangeEstimator::estimate, smallsat at 300 m, VGA, %s, roi %lld px%s", label,
                static_cast<long long>(r.roi.area()), r.valid ? "" : " (NOT VALID)");
  return report(o, title, t) && r.valid;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i + 1 < argc; i += 2) {
    const double v = std::atof(argv[i + 1]);
    if (std::strcmp(argv[i], "--frames") == 0)
      o.frames = static_cast<int>(v);
    else if (std::strcmp(argv[i], "--ipc") == 0)
      o.ipc = v;
    else if (std::strcmp(argv[i], "--ipc-low") == 0)
      o.ipc_low = v;
    else if (std::strcmp(argv[i], "--clock-ghz") == 0)
      o.clock_ghz = v;
    else if (std::strcmp(argv[i], "--cycle-ms") == 0)
      o.cycle_ms = v;
    else
      return false;
  }
  return argc % 2 == 1 && o.frames > 0 && o.frames <= 1000 && o.ipc > 0.0 && o.ipc_low > 0.0 &&
         o.clock_ghz > 0.0 && o.cycle_ms > 0.0;
}

}  // namespace
}  // namespace visnav::armcost

int main(int argc, char** argv) {
  using namespace visnav::armcost;
  Options o;
  if (!parse(argc, argv, o)) {
    std::fprintf(
        stderr,
        "usage: visnav-arm-cost [--frames N] [--ipc X] [--ipc-low X] [--clock-ghz G] [--cycle-ms T]\n");
    return 2;
  }
  if (!initInsnCounter()) {
    std::fprintf(stderr,
                 "visnav-arm-cost: no instruction counter; run under qemu-aarch64 -plugin libinsncount.so\n");
    return 1;
  }
  g_overhead = insnCounterOverhead();
  std::printf(
      "arm64 executed instructions per call (qemu-aarch64 TCG plugin, exact), mean of %d frames after %d "
      "warm-up\n"
      "estimated Cortex-A53 time at %.2f GHz with IPC %.2f (and %.2f pessimistic), share of the %.0f ms "
      "cycle\n"
      "(one counter read = %" PRId64 " instructions, removed from every interval)\n",
      o.frames, kWarmupFrames, o.clock_ghz, o.ipc, o.ipc_low, o.cycle_ms, g_overhead);
  std::printf("  %-28s %14s %12s %12s %11s\n", "stage", "instructions", "ms @IPC", "ms @IPC low", "share");
  bool ok = nearRange(o);
  ok = farRange(o, 0, false, "paper method, full frame") && ok;
  ok = farRange(o, 1, false, "robust method, full frame") && ok;
  ok = farRange(o, 1, true, "robust method, tracked ROI") && ok;
  return ok ? 0 : 1;
}
