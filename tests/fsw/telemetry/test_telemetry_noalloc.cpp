// REQUIREMENT: publishing allocates nothing per cycle. Counts every allocation of this process (operator new
// always; malloc/calloc/realloc too outside ASan builds, which is where Cyclone's C allocations show up,
// including its background threads) over many publish cycles, without a reader and with a reliable reader
// in another process.
#include <gtest/gtest.h>
#include <signal.h>

#include "../../support/alloc_counter.hpp"
#include "process_util.hpp"
#include "telemetry_test_data.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"

namespace visnav::telemetry {
namespace {

constexpr int kCycles = 1000;

struct Flight {
  Participant participant;
  TelemetryWriter writer;
  CommandReader commands;
  std::vector<nav::NavSolution> navs;
  std::vector<nav::HealthRecord> healths;

  explicit Flight(const TelemetryParams& params) {
    EXPECT_TRUE(participant.init(params.domain_id, params.partitionName()).ok);
    EXPECT_TRUE(writer.init(participant, params, 200'000'000).ok);
    EXPECT_TRUE(commands.init(participant, params).ok);
    for (std::uint64_t i = 1; i <= 50; ++i) {
      navs.push_back(test::makeNavSolution(i));
      healths.push_back(test::makeHealthRecord(i));
    }
  }
  // One cycle's telemetry work: poll commands, publish the solution and the health record.
  void cycle(int i) {
    ReceivedCommand batch[4];
    commands.poll(batch, 4);
    writer.publishNav(navs[static_cast<std::size_t>(i) % navs.size()]);
    writer.publishHealth(healths[static_cast<std::size_t>(i) % healths.size()]);
  }
  // Allocations over kCycles cycles after `warmup` cycles; `spacing_us` between cycles lets acks flow.
  std::uint64_t count(int warmup, int spacing_us) {
    for (int i = 0; i < warmup; ++i) cycle(i);
    const std::uint64_t before = visnav::test::allocationCount();
    for (int i = 0; i < kCycles; ++i) {
      cycle(i);
      if (spacing_us > 0) dds_sleepfor(DDS_USECS(spacing_us));
    }
    return visnav::test::allocationCount() - before;
  }
};

TEST(TelemetryNoAlloc, PublishWithoutReaders) {
  Flight flight(test::uniqueLinkParams("noalloc-alone"));
  const std::uint64_t n = flight.count(50, 0);
  std::printf("allocations in %d cycles without readers: %llu (malloc counted: %d)\n", kCycles,
              static_cast<unsigned long long>(n), visnav::test::countsMalloc() ? 1 : 0);
  EXPECT_EQ(n, 0U);
  EXPECT_EQ(flight.writer.counters().write_failures, 0U);
}

TEST(TelemetryNoAlloc, PublishToAReliableReaderInAnotherProcess) {
  const TelemetryParams params = test::uniqueLinkParams("noalloc-reader");
  Flight flight(params);
  const pid_t monitor = test::spawnProcess(
      {VISNAV_MONITOR, "--partition", params.partitionName(), "--duration", "60", "--no-view"},
      test::tempPath("noalloc-monitor"));
  ASSERT_GT(monitor, 0);
  ASSERT_TRUE(waitForReaders(flight.writer.writer(Topic::kPose), 1, 10'000'000'000LL));
  ASSERT_TRUE(waitForReaders(flight.writer.writer(Topic::kHealth), 1, 10'000'000'000LL));
  const std::uint64_t n = flight.count(200, 1000);
  kill(monitor, SIGTERM);
  EXPECT_EQ(test::waitProcess(monitor, 10.0), 0);
  std::printf("allocations in %d cycles with a reliable remote reader: %llu (malloc counted: %d)\n", kCycles,
              static_cast<unsigned long long>(n), visnav::test::countsMalloc() ? 1 : 0);
  EXPECT_EQ(n, 0U);
}

TEST(TelemetryNoAlloc, CounterSeesAllocations) {
  const std::uint64_t before = visnav::test::allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(visnav::test::allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav::telemetry
