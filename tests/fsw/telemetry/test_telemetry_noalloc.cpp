// REQUIREMENT: publishing allocates nothing per cycle on the cycle's thread. Counts allocations (operator
// new always; malloc, calloc, realloc too outside ASan builds, which is where Cyclone's own C allocations
// show up) over many telemetry cycles, without a reader and with a reliable reader in another process.
//
// Cyclone DDS 0.10.2's default sertype allocates twice per dds_write of a sample whose CDR payload exceeds
// 256 bytes (its serdata pool keeps only buffers up to 256 bytes): PoseEstimate and Health. TelemetryWriter's
// writers use the pooled sertype (pooled_sertype.hpp) instead. With a remote reliable reader Cyclone still
// allocates inside dds_write on 0.2-1 % of the writes (test_soak traced them to ddsrt_malloc under
// dds_write); dds_write therefore runs on the writer's publisher thread, never on the cycle's (issue 13).
// The tests prove: (1) the cycle's thread makes exactly 0 allocations, with and without the remote reader;
// (2) the process total (the publisher thread's dds_write and Cyclone's own threads: heartbeats,
// acknowledgments) stays within a bound and the heap does not grow; (3) the control: the same sample
// through a writer of Cyclone's default sertype allocates on the writing thread, so the counter sees what
// the pool removes; (4) the pool itself: blocks reused, an empty pool counted as a miss and still served,
// bytes round-trip.
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>
#include <malloc.h>
#include <signal.h>

#include "../../support/alloc_counter.hpp"
#include "process_util.hpp"
#include "telemetry_test_data.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/pooled_sertype.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace visnav::telemetry {
namespace {

constexpr int kCycles = 1000;
constexpr int kReaderCycles = 5000;  // with the remote reader: 15000 writes, so Cyclone's rare ones do occur
// On the cycle's thread: none, ever (it only fills ring slots; dds_write runs on the publisher thread).
// Before the publisher thread it was 0-10 per 1000 cycles with a remote reader, all inside dds_write.
constexpr std::uint64_t kCycleThreadAllocations = 0;
// Every other thread: Cyclone's own (heartbeats, acks, leases; 25 seen under a loaded parallel ctest) plus,
// with a remote reliable reader, its allocations inside dds_write on the publisher thread, bounded at 2 % of
// the writes as in test_soak. One allocation per cycle of ours would add kCycles: the bound still catches it.
constexpr std::uint64_t kBackgroundSlack = 100;
std::uint64_t processBound(int cycles, bool remote_reader) {
  return kBackgroundSlack + (remote_reader ? 3U * static_cast<std::uint64_t>(cycles) / 50U : 0U);
}

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
  struct Count {
    std::uint64_t thread = 0;   ///< this (the cycle's) thread
    std::uint64_t process = 0;  ///< every thread
  };
  // Between cycles the test waits until the publisher thread has written the cycle's samples (a condition,
  // as at 5 Hz, where it has 200 ms): back to back, 3000 samples would overrun the ring in a millisecond.
  // The wait runs on this thread and is counted with the cycle: it allocates nothing either.
  Count count(int cycles, int spacing_us) {
    const std::uint64_t before = visnav::test::allocationCount();
    const std::uint64_t thread_before = visnav::test::threadAllocationCount();
    for (int i = 0; i < cycles; ++i) {
      cycle(i);
      writer.flush(1'000'000'000);
      if (spacing_us > 0) dds_sleepfor(DDS_USECS(spacing_us));
    }
    return {visnav::test::threadAllocationCount() - thread_before, visnav::test::allocationCount() - before};
  }
};

void measure(Flight& flight, const char* what, int cycles, int spacing_us, bool remote_reader) {
  for (int i = 0; i < 100; ++i) {  // warm-up: first matches, the instance map's entry
    flight.cycle(i);
    ASSERT_TRUE(flight.writer.flush(10'000'000'000LL));
  }
  const std::size_t heap_before = mallinfo2().uordblks;
  const Flight::Count n = flight.count(cycles, spacing_us);
  const std::size_t heap_after = mallinfo2().uordblks;
  const WriterCounters c = flight.writer.counters();
  std::printf(
      "%s, %d cycles (%d writes): cycle thread %llu allocations, whole process %llu (malloc counted: %d), "
      "pool misses %llu, samples queued %llu written %llu dropped %llu\n",
      what, cycles, 3 * cycles, static_cast<unsigned long long>(n.thread),
      static_cast<unsigned long long>(n.process), visnav::test::countsMalloc() ? 1 : 0,
      static_cast<unsigned long long>(flight.writer.samplePoolMisses()),
      static_cast<unsigned long long>(c.samples_queued), static_cast<unsigned long long>(c.samples_written),
      static_cast<unsigned long long>(c.samples_dropped));
  EXPECT_EQ(c.write_failures, 0U);
  EXPECT_EQ(c.samples_dropped, 0U);
  EXPECT_EQ(c.samples_written, c.samples_queued);
  EXPECT_EQ(n.thread, kCycleThreadAllocations);
  if (remote_reader) {
    // A reliable reader that falls behind (spaced by 500 us here, where flight gives it 200 ms; on a loaded
    // machine it lagged) keeps more samples unacknowledged than the pool has blocks: the publisher thread
    // then takes them from the heap and counts them (18 of 15300 in one loaded run). That is the documented
    // fallback, off the cycle thread; it is bounded like the process's other allocations.
    EXPECT_LE(flight.writer.samplePoolMisses(), processBound(cycles, remote_reader));
  } else {
    EXPECT_EQ(flight.writer.samplePoolMisses(), 0U);
  }
  EXPECT_LE(n.process, processBound(cycles, remote_reader));
  if (visnav::test::countsMalloc()) {
    EXPECT_LT(heap_after, heap_before + 64 * 1024);
  }
}

TEST(TelemetryNoAlloc, PublishWithoutReaders) {
  Flight flight(test::isolatedLinkParams("noalloc-alone"));
  measure(flight, "no reader", kCycles, 0, false);
}

TEST(TelemetryNoAlloc, PublishToAReliableReaderInAnotherProcess) {
  const TelemetryParams params = test::isolatedLinkParams("noalloc-reader");
  Flight flight(params);
  const pid_t monitor =
      test::spawnProcess({VISNAV_MONITOR, "--domain", std::to_string(params.domain_id), "--partition",
                          params.partitionName(), "--duration", "120", "--no-view"},
                         test::tempPath("noalloc-monitor"));
  ASSERT_GT(monitor, 0);
  ASSERT_TRUE(waitForReaders(ddsWriter(flight.writer, Topic::kPose), 1, 10'000'000'000LL));
  ASSERT_TRUE(waitForReaders(ddsWriter(flight.writer, Topic::kHealth), 1, 10'000'000'000LL));
  measure(flight, "reliable remote reader", kReaderCycles, 500, true);  // spaced: acknowledgments flow back
  kill(monitor, SIGTERM);
  EXPECT_EQ(test::waitProcess(monitor, 10.0), 0);
}

TEST(TelemetryNoAlloc, DefaultSertypeAllocatesWhereThePoolDoesNot) {
  // Control: a writer on the participant's topic (Cyclone's default sertype) with the same QoS and sample.
  const TelemetryParams params = test::isolatedLinkParams("noalloc-control");
  Flight flight(params);
  dds_qos_t* qos = makeWriterQos(Topic::kPose, params, 200'000'000);
  const dds_entity_t plain =
      dds_create_writer(flight.participant.publisher(), flight.participant.topic(Topic::kPose), qos, nullptr);
  dds_delete_qos(qos);
  ASSERT_GT(plain, 0);
  for (int i = 0; i < 100; ++i) dds_write(plain, &flight.pose);
  const std::uint64_t before = visnav::test::threadAllocationCount();
  for (int i = 0; i < kCycles; ++i) dds_write(plain, &flight.pose);
  const std::uint64_t plain_count = visnav::test::threadAllocationCount() - before;
  std::printf("default sertype, %d PoseEstimate writes: %llu allocations on the writing thread\n", kCycles,
              static_cast<unsigned long long>(plain_count));
  if (visnav::test::countsMalloc()) {
    EXPECT_GE(plain_count, 2U * kCycles);  // the 2 per write of a sample over 256 bytes
  }
  for (int i = 0; i < 100; ++i) dds_write(ddsWriter(flight.writer, Topic::kPose), &flight.pose);  // warm-up
  const std::uint64_t pooled_before = visnav::test::threadAllocationCount();
  for (int i = 0; i < kCycles; ++i) dds_write(ddsWriter(flight.writer, Topic::kPose), &flight.pose);
  EXPECT_EQ(visnav::test::threadAllocationCount() - pooled_before, 0U);
}

TEST(TelemetryNoAlloc, PoolReusesBlocksCountsMissesAndRoundTrips) {
  TelemetryParams params = test::isolatedLinkParams("noalloc-pool");
  params.history_depth = 1;  // a pool of 2 holds a history of 1 and the write in progress
  params.sample_pool_blocks = 2;
  Flight flight(params);
  const PooledSertype* pooled = flight.writer.sertype(Topic::kHealth);
  const ddsi_sertype* type = cycloneSertype(pooled);
  ASSERT_NE(type, nullptr);
  const PooledSertypeStats start = pooledSertypeStats(pooled);
  EXPECT_EQ(start.blocks, 2U);
  EXPECT_EQ(start.blocks_in_use, 0U);
  // Three samples held at once from a pool of two: the third is served from the heap and counted.
  ddsi_serdata* held[3];
  for (ddsi_serdata*& d : held) d = ddsi_serdata_from_sample(type, SDK_DATA, &flight.health);
  for (ddsi_serdata* d : held) ASSERT_NE(d, nullptr);
  PooledSertypeStats s = pooledSertypeStats(pooled);
  EXPECT_EQ(s.blocks_in_use, 2U);
  EXPECT_EQ(s.pool_misses, 1U);
  // Each one holds the sample: header CDR little-endian XCDR1, payload a multiple of 4, and it reads back.
  for (ddsi_serdata* d : held) {
    const std::uint32_t size = ddsi_serdata_size(d);
    EXPECT_EQ(size % 4U, 0U);
    unsigned char header[4];
    ddsi_serdata_to_ser(d, 0, 4, header);
    EXPECT_EQ(header[0], 0x00);
    EXPECT_EQ(header[1], 0x01);
    visnav_Health back{};
    ASSERT_TRUE(ddsi_serdata_to_sample(d, &back, nullptr, nullptr));
    EXPECT_EQ(back.sample_number, flight.health.sample_number);
    EXPECT_EQ(back.fault_counts[3], flight.health.fault_counts[3]);
    EXPECT_EQ(back.task_timing[2].p99_us, flight.health.task_timing[2].p99_us);
    EXPECT_STREQ(back.last_transition.reason, flight.health.last_transition.reason);
    EXPECT_STREQ(back.last_command.reason, flight.health.last_command.reason);
  }
  for (ddsi_serdata* d : held) ddsi_serdata_unref(d);
  s = pooledSertypeStats(pooled);
  EXPECT_EQ(s.blocks_in_use, 0U);
  // Released blocks come back: two more samples, no new miss, nothing allocated.
  const std::uint64_t before = visnav::test::threadAllocationCount();
  ddsi_serdata* again[2];
  for (ddsi_serdata*& d : again) d = ddsi_serdata_from_sample(type, SDK_DATA, &flight.health);
  for (ddsi_serdata* d : again) ddsi_serdata_unref(d);
  EXPECT_EQ(visnav::test::threadAllocationCount() - before, 0U);
  EXPECT_EQ(pooledSertypeStats(pooled).pool_misses, 1U);
}

TEST(TelemetryNoAlloc, CounterSeesAllocations) {
  const std::uint64_t before = visnav::test::allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(visnav::test::allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav::telemetry
