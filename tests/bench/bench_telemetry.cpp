// CPU cost of the telemetry work inside a cycle: filling the samples, and publishing (mapping + dds_write)
// with no reader and with a reliable reader in this process. Run:
//   CYCLONEDDS_URI=file://$PWD/config/cyclonedds-loopback.xml build/release/bin/bench_telemetry
//     --benchmark_repetitions=10 --benchmark_report_aggregates_only=true ; read the *_median rows.
// The end-to-end latency at 5 Hz is measured with visnav-monitor instead (fsw/telemetry/README.md).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <string>

#include "../fsw/telemetry/telemetry_test_data.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/ground_link.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace visnav::telemetry {
namespace {

void BM_FillSamples(benchmark::State& state) {
  const nav::NavSolution nav = test::makeNavSolution(4);
  const nav::HealthRecord health = test::makeHealthRecord(4);
  visnav_PoseEstimate pose{};
  visnav_FarRangeEstimate far{};
  visnav_Health h{};
  std::uint64_t n = 0;
  for (auto _ : state) {
    fillPoseEstimate(nav, ++n, 0, pose);
    fillFarRangeEstimate(nav, n, 0, far);
    fillHealth(health, n, 0, h);
    benchmark::DoNotOptimize(pose);
    benchmark::DoNotOptimize(h);
  }
}
BENCHMARK(BM_FillSamples);

// One cycle's telemetry: poll commands, publishNav (pose + far range), publishHealth. Arg 1: a reliable
// reader (GroundLink, its own participant in this process) is matched and drained now and then.
void BM_TelemetryCycle(benchmark::State& state) {
  const TelemetryParams params = test::uniqueLinkParams("bench-" + std::to_string(state.range(0)));
  Participant participant;
  TelemetryWriter writer;
  CommandReader commands;
  participant.init(params.domain_id, params.partitionName());
  writer.init(participant, params, 200'000'000);
  commands.init(participant, params);
  GroundLink ground;
  if (state.range(0) == 1) {
    ground.init(params, 256);
    waitForReaders(ddsWriter(writer, Topic::kPose), 1, 5'000'000'000LL);
  }
  const nav::NavSolution nav = test::makeNavSolution(4);
  const nav::HealthRecord health = test::makeHealthRecord(4);
  ReceivedCommand batch[4];
  std::array<visnav_PoseEstimate, kMaxTakeBatch> drain_pose{};
  std::array<visnav_Health, kMaxTakeBatch> drain_health{};
  std::array<visnav_FarRangeEstimate, kMaxTakeBatch> drain_far{};
  std::array<dds_sample_info_t, kMaxTakeBatch> infos{};
  std::uint64_t n = 0;
  for (auto _ : state) {
    commands.poll(batch, 4);
    writer.publishNav(nav);
    writer.publishHealth(health);
    if (state.range(0) == 1 && ++n % 32 == 0) {
      state.PauseTiming();
      ground.takePose(drain_pose.data(), infos.data(), kMaxTakeBatch);
      ground.takeFarRange(drain_far.data(), infos.data(), kMaxTakeBatch);
      ground.takeHealth(drain_health.data(), infos.data(), kMaxTakeBatch);
      state.ResumeTiming();
    }
  }
  state.counters["write_failures"] = static_cast<double>(writer.counters().write_failures);
}
BENCHMARK(BM_TelemetryCycle)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace visnav::telemetry

BENCHMARK_MAIN();
