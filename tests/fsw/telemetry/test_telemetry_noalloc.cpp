// REQUIREMENT: publishing allocates nothing per cycle. Counts every allocation of this process (operator new
// always; malloc/calloc/realloc too outside ASan builds, which is where Cyclone's own C allocations show up,
// including its background threads) over many telemetry cycles, without a reader and with a reliable reader
// in another process.
//
// Measured fact (Cyclone DDS 0.10.2): dds_write() itself allocates for samples whose CDR payload exceeds 256
// bytes (its serdata pool keeps only buffers up to 256 bytes): PoseEstimate and Health cost 2 allocations per
// write (serdata + its growth), FarRangeEstimate and ModeCommand none. So the tests prove: (1) our code adds
// no allocation to what the bare dds_write() calls make; (2) Cyclone's share stays at that known bound and is
// returned (the heap does not grow); (3) in the ASan build, where only operator new is counted, exactly 0.
#include <gtest/gtest.h>
#include <malloc.h>
#include <signal.h>

#include "../../support/alloc_counter.hpp"
#include "process_util.hpp"
#include "telemetry_test_data.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"

namespace visnav::telemetry {
namespace {

constexpr int kCycles = 1000;
constexpr std::uint64_t kCycloneAllocationsPerCycle = 4;  // 2 per write of PoseEstimate and of Health
constexpr std::uint64_t kBackgroundSlack = 100;  // Cyclone's own threads (heartbeats, acks, leases); 25 seen under
                                                 // a loaded parallel ctest. One allocation per cycle of ours
                                                 // would add 1000: the bound still catches it.

struct Flight {
  Participant participant;
  TelemetryWriter writer;
  CommandReader commands;
  std::vector<nav::NavSolution> navs;
  std::vector<nav::HealthRecord> healths;
  // The same samples, filled once, for the bare-dds_write control.
  visnav_PoseEstimate pose{};
  visnav_FarRangeEstimate far{};
  visnav_Health health{};

  explicit Flight(const TelemetryParams& params) {
    EXPECT_TRUE(participant.init(params.domain_id, params.partitionName()).ok);
    EXPECT_TRUE(writer.init(participant, params, 200'000'000).ok);
    EXPECT_TRUE(commands.init(participant, params).ok);
    for (std::uint64_t i = 1; i <= 50; ++i) {
      navs.push_back(test::makeNavSolution(i));
      healths.push_back(test::makeHealthRecord(i));
    }
    fillPoseEstimate(navs[0], 1, 0, pose);
    fillFarRangeEstimate(navs[0], 1, 0, far);
    fillHealth(healths[0], 1, 0, health);
  }
  // One cycle's telemetry work: poll commands, publish the solution and the health record.
  void cycle(int i) {
    ReceivedCommand batch[4];
    commands.poll(batch, 4);
    writer.publishNav(navs[static_cast<std::size_t>(i) % navs.size()]);
    writer.publishHealth(healths[static_cast<std::size_t>(i) % healths.size()]);
  }
  // The middleware alone: the three writes of a cycle with samples filled beforehand.
  void bareWrites(int) {
    dds_write(writer.writer(Topic::kPose), &pose);
    dds_write(writer.writer(Topic::kFarRange), &far);
    dds_write(writer.writer(Topic::kHealth), &health);
  }
  template <typename Step>
  std::uint64_t count(Step step, int spacing_us) {
    const std::uint64_t before = visnav::test::allocationCount();
    for (int i = 0; i < kCycles; ++i) {
      (this->*step)(i);
      if (spacing_us > 0) dds_sleepfor(DDS_USECS(spacing_us));
    }
    return visnav::test::allocationCount() - before;
  }
};

/// `exact_share`: compare the counts (deterministic without a remote reader). With a reliable reader in another
/// process Cyclone's own count depends on the reader's pace (acknowledgments, retransmits): +0.73 per cycle
/// was seen under a loaded parallel ctest, so there only the heap bound and the count of operator new apply.
void measure(Flight& flight, const char* what, int spacing_us, bool exact_share = true) {
  for (int i = 0; i < 100; ++i) flight.cycle(i);  // warm-up: pools, first matches
  const std::size_t heap_before = mallinfo2().uordblks;
  const std::uint64_t ours = flight.count(&Flight::cycle, spacing_us);
  const std::uint64_t bare = flight.count(&Flight::bareWrites, spacing_us);
  const std::size_t heap_after = mallinfo2().uordblks;
  std::printf("%s, %d cycles: telemetry cycle %llu allocations, bare dds_write of the same samples %llu "
              "(malloc counted: %d)\n",
              what, kCycles, static_cast<unsigned long long>(ours), static_cast<unsigned long long>(bare),
              visnav::test::countsMalloc() ? 1 : 0);
  EXPECT_EQ(flight.writer.counters().write_failures, 0U);
  if (!visnav::test::countsMalloc()) {
    EXPECT_EQ(ours, 0U);  // operator new only: nothing of ours allocates
    return;
  }
  EXPECT_LT(heap_after, heap_before + 64 * 1024);  // whatever is allocated is freed again
  if (!exact_share) return;
  // What our code adds on top of the middleware (mapping, polling): nothing beyond background noise.
  EXPECT_LE(ours, bare + kBackgroundSlack);
  // Cyclone's share: the known 2 allocations per large sample, freed again.
  EXPECT_LE(ours, kCycloneAllocationsPerCycle * kCycles + kBackgroundSlack);
}

TEST(TelemetryNoAlloc, PublishWithoutReaders) {
  Flight flight(test::uniqueLinkParams("noalloc-alone"));
  measure(flight, "no reader", 0);
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
  measure(flight, "reliable remote reader", 500, false);  // spaced so acknowledgments flow back meanwhile
  kill(monitor, SIGTERM);
  EXPECT_EQ(test::waitProcess(monitor, 10.0), 0);
}

TEST(TelemetryNoAlloc, SmallSamplesAreWrittenWithoutAllocation) {
  // Far range (payload < 256 B) alone: Cyclone's serdata pool serves it, so the whole path is allocation-free.
  Flight flight(test::uniqueLinkParams("noalloc-small"));
  for (int i = 0; i < 100; ++i) dds_write(flight.writer.writer(Topic::kFarRange), &flight.far);
  const std::uint64_t before = visnav::test::allocationCount();
  for (int i = 0; i < kCycles; ++i) dds_write(flight.writer.writer(Topic::kFarRange), &flight.far);
  EXPECT_LE(visnav::test::allocationCount() - before, kBackgroundSlack);
}

TEST(TelemetryNoAlloc, CounterSeesAllocations) {
  const std::uint64_t before = visnav::test::allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(visnav::test::allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav::telemetry
