// REQUIREMENT (issue 13): dds_write runs off the cycle's thread. TelemetryWriter's publish calls put each
// sample into a bounded ring; its publisher thread drains the ring into dds_write. Shown here, with a
// stall the test controls (DdsAccess::holdPublisher parks the publisher thread between two samples and
// says when it is parked: no sleeps, no timing luck):
//   - a stalled publisher: the ring takes exactly kQueueSlots samples, then drops the newest, counts each
//     drop, and the cycle's publish calls neither block nor allocate; released, it writes what was queued, in
//     order, and the reader sees the drops as sample-number gaps;
//   - not stalled: every sample queued is written and a reliable reader in another process receives all;
//   - stop() drains the ring, even while held, and joins; a failed write is counted and reported.
// Each test runs on a DDS domain of its own (isolatedDomainId) and its own partition.
#include <gtest/gtest.h>
#include <signal.h>
#include <time.h>

#include <array>
#include <vector>

#include "../../support/alloc_counter.hpp"
#include "process_util.hpp"
#include "telemetry_test_data.hpp"
#include "visnav/telemetry/ground_link.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers, the publisher gate

namespace visnav::telemetry {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::uint64_t kSlots = TelemetryWriter::kQueueSlots;

/// Bounded wait for a condition (polled every ms; the bound only turns a hang into a failure).
template <typename Condition>
bool waitUntil(const Condition& condition, std::int64_t timeout_ns) {
  const std::int64_t end = monotonicNowNs() + timeout_ns;
  while (!condition()) {
    if (monotonicNowNs() > end) return false;
    const timespec ms{0, 1'000'000};
    nanosleep(&ms, nullptr);
  }
  return true;
}

/// Takes every sample number the reader holds of one topic, until `count` arrived (bounded).
template <typename Sample>
std::vector<std::uint64_t> sampleNumbers(GroundLink& ground,
                                         int (GroundLink::*take)(Sample*, dds_sample_info_t*, int),
                                         std::size_t count) {
  std::vector<std::uint64_t> numbers;
  std::vector<Sample> batch(kMaxTakeBatch);
  std::vector<dds_sample_info_t> infos(kMaxTakeBatch);
  const std::int64_t end = monotonicNowNs() + 10 * kSecond;
  while (numbers.size() < count && monotonicNowNs() < end) {
    ground.waitForData(20'000'000);
    const int n = (ground.*take)(batch.data(), infos.data(), kMaxTakeBatch);
    for (int i = 0; i < n; ++i)
      if (infos[i].valid_data) numbers.push_back(batch[i].sample_number);
  }
  return numbers;
}

std::vector<std::uint64_t> range(std::uint64_t first, std::uint64_t last) {
  std::vector<std::uint64_t> v;
  for (std::uint64_t i = first; i <= last; ++i) v.push_back(i);
  return v;
}

struct Flight {
  TelemetryParams params;
  Participant participant;
  TelemetryWriter writer;
  explicit Flight(const char* name) : params(test::isolatedLinkParams(name)) {
    EXPECT_TRUE(participant.init(params.domain_id, params.partitionName()).ok);
    EXPECT_TRUE(writer.init(participant, params, 200'000'000).ok);
  }
};

TEST(TelemetryPublisher, AStalledPublisherFillsTheRingThenDropsTheNewestAndCountsIt) {
  Flight flight("publisher-stall");
  GroundLink ground;
  ASSERT_TRUE(ground.init(flight.params, 2 * static_cast<int>(kSlots)).ok);
  Topic missing = Topic::kPose;
  ASSERT_TRUE(flight.writer.waitForReaders(1, 10 * kSecond, missing)) << topicName(missing);
  ASSERT_TRUE(waitUntil([&] { return ground.allReadersMatched(); }, 10 * kSecond));

  ASSERT_TRUE(DdsAccess::holdPublisher(flight.writer, 10 * kSecond));
  const WriterCounters before = flight.writer.counters();
  EXPECT_EQ(before.samples_queued, 0U);
  // 3 samples per cycle: 21 whole cycles fit in 64 slots; cycle 22's pose takes the last slot, its far-range
  // sample and health are dropped, and so is everything of cycles 23..30.
  constexpr std::uint64_t kCycles = 30;
  constexpr std::uint64_t kWholeCycles = kSlots / 3;
  std::array<bool, kCycles> nav_ok{};  // no allocation of the test's own among the counted calls
  std::array<bool, kCycles> health_ok{};
  const std::uint64_t thread_before = visnav::test::threadAllocationCount();
  for (std::uint64_t i = 1; i <= kCycles; ++i) {
    nav_ok[i - 1] = flight.writer.publishNav(test::makeNavSolution(i));
    health_ok[i - 1] = flight.writer.publishHealth(test::makeHealthRecord(i));
  }
  const std::uint64_t thread_allocations = visnav::test::threadAllocationCount() - thread_before;
  const WriterCounters held = flight.writer.counters();
  std::printf(
      "stalled publisher, %llu cycles: queued %llu, dropped %llu, written %llu; cycle thread %llu "
      "allocations\n",
      static_cast<unsigned long long>(kCycles), static_cast<unsigned long long>(held.samples_queued),
      static_cast<unsigned long long>(held.samples_dropped),
      static_cast<unsigned long long>(held.samples_written),
      static_cast<unsigned long long>(thread_allocations));
  EXPECT_EQ(held.samples_queued, kSlots);
  EXPECT_EQ(held.samples_dropped, 3 * kCycles - kSlots);
  EXPECT_EQ(held.samples_written, 0U);  // parked: nothing reached dds_write
  EXPECT_EQ(thread_allocations, 0U);
  for (std::uint64_t i = 1; i <= kCycles; ++i) {
    EXPECT_EQ(nav_ok[i - 1], i <= kWholeCycles) << "cycle " << i;
    EXPECT_EQ(health_ok[i - 1], i <= kWholeCycles) << "cycle " << i;
  }

  DdsAccess::releasePublisher(flight.writer);
  ASSERT_TRUE(flight.writer.flush(10 * kSecond));
  const WriterCounters after = flight.writer.counters();
  EXPECT_EQ(after.samples_written, kSlots);
  EXPECT_EQ(after.write_failures, 0U);
  EXPECT_EQ(after.samples_dropped, held.samples_dropped);
  // The reader gets what was queued, in order; the drops are gaps after it (numbers count every sample the
  // cycle handed over, so a ring drop looks like a loss in transport, and the counter tells them apart).
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takePose, kWholeCycles + 1), range(1, kWholeCycles + 1));
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takeFarRange, kWholeCycles), range(1, kWholeCycles));
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takeHealth, kWholeCycles), range(1, kWholeCycles));

  // Running again: the next cycle is queued and written; its numbers continue after the gap.
  ASSERT_TRUE(flight.writer.publishNav(test::makeNavSolution(kCycles + 1)));
  ASSERT_TRUE(flight.writer.flush(10 * kSecond));
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takePose, 1), std::vector<std::uint64_t>{kCycles + 1});
}

TEST(TelemetryPublisher, NothingIsLostWhenThePublisherKeepsUp) {
  constexpr int kCycles = 300;
  constexpr int kBurst = 10;  // 30 samples, less than the ring holds: the ring cannot drop
  static_assert(3 * kBurst < static_cast<int>(TelemetryWriter::kQueueSlots), "a burst fits in the ring");
  Flight flight("publisher-keepup");
  const std::string ready = test::tempPath("keepup-ready");
  const std::string monitor_out = test::tempPath("keepup-monitor");
  const pid_t monitor =
      test::spawnProcess({VISNAV_MONITOR, "--domain", std::to_string(flight.params.domain_id), "--partition",
                          flight.params.partitionName(), "--samples", std::to_string(kCycles), "--duration",
                          "60", "--no-view", "--ready-file", ready},
                         monitor_out);
  ASSERT_GT(monitor, 0);
  Topic missing = Topic::kPose;
  ASSERT_TRUE(flight.writer.waitForReaders(1, 20 * kSecond, missing)) << topicName(missing);
  ASSERT_TRUE(waitForFile(ready.c_str(), 20 * kSecond));  // the monitor's readers matched our writers
  // Bursts of kBurst cycles back to back, each burst then waits until the reliable reader acknowledged it
  // (a condition, not a pause): the ring starts every burst empty, and the reader keeps up. Cycle 1 is
  // acknowledged alone first: the monitor's just-matched readers start out of sync with our writers and
  // take the first samples through a heartbeat round trip (Cyclone's volatile-reader start; under load,
  // a burst written before it completes pushed sample 1 out of the writer history: the CI failure).
  for (int i = 1; i <= kCycles; ++i) {
    ASSERT_TRUE(flight.writer.publishNav(test::makeNavSolution(static_cast<std::uint64_t>(i))));
    ASSERT_TRUE(flight.writer.publishHealth(test::makeHealthRecord(static_cast<std::uint64_t>(i))));
    if (i == 1 || i % kBurst == 0) {
      ASSERT_TRUE(flight.writer.waitForAcks(10 * kSecond)) << "cycle " << i;
    }
  }
  ASSERT_EQ(test::waitProcess(monitor, 30.0), 0) << test::readText(monitor_out);
  const WriterCounters c = flight.writer.counters();
  const std::string summary = test::readText(monitor_out);
  std::printf("publisher keeping up, %d cycles: queued %llu, written %llu, dropped %llu, failures %llu\n%s",
              kCycles, static_cast<unsigned long long>(c.samples_queued),
              static_cast<unsigned long long>(c.samples_written),
              static_cast<unsigned long long>(c.samples_dropped),
              static_cast<unsigned long long>(c.write_failures), summary.c_str());
  EXPECT_EQ(c.samples_queued, 3U * kCycles);
  EXPECT_EQ(c.samples_written, 3U * kCycles);
  EXPECT_EQ(c.samples_dropped, 0U);
  EXPECT_EQ(c.write_failures, 0U);
  EXPECT_NE(summary.find("pose: samples " + std::to_string(kCycles) + ", "), std::string::npos) << summary;
  EXPECT_NE(summary.find("health: samples " + std::to_string(kCycles) + ", "), std::string::npos) << summary;
  EXPECT_NE(summary.find("lost samples 0, "), std::string::npos) << summary;
  EXPECT_EQ(summary.find("lost samples 1"), std::string::npos) << summary;
}

TEST(TelemetryPublisher, StopWritesWhatIsQueuedEvenWhenHeldThenRefusesMore) {
  Flight flight("publisher-stop");
  GroundLink ground;
  ASSERT_TRUE(ground.init(flight.params, 64).ok);
  Topic missing = Topic::kPose;
  ASSERT_TRUE(flight.writer.waitForReaders(1, 10 * kSecond, missing)) << topicName(missing);
  ASSERT_TRUE(waitUntil([&] { return ground.allReadersMatched(); }, 10 * kSecond));
  ASSERT_TRUE(DdsAccess::holdPublisher(flight.writer, 10 * kSecond));
  for (std::uint64_t i = 1; i <= 10; ++i) {
    ASSERT_TRUE(flight.writer.publishNav(test::makeNavSolution(i)));
    ASSERT_TRUE(flight.writer.publishHealth(test::makeHealthRecord(i)));
  }
  EXPECT_EQ(flight.writer.counters().samples_written, 0U);
  flight.writer.stop();  // stop wins over the hold: the 30 queued samples are written, then the thread ends
  EXPECT_EQ(flight.writer.counters().samples_written, 30U);
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takePose, 10), range(1, 10));
  EXPECT_EQ(sampleNumbers(ground, &GroundLink::takeHealth, 10), range(1, 10));
  EXPECT_FALSE(flight.writer.publishNav(test::makeNavSolution(11)));  // stopped: nothing queued
  EXPECT_EQ(flight.writer.counters().samples_queued, 30U);
  EXPECT_TRUE(flight.writer.flush(0));
  flight.writer.stop();  // idempotent
}

TEST(TelemetryPublisher, AFailedWriteIsCountedAndReportedByTheNextPublish) {
  Flight flight("publisher-fail");
  ASSERT_TRUE(flight.writer.publishNav(test::makeNavSolution(1)));
  ASSERT_TRUE(flight.writer.flush(10 * kSecond));
  ASSERT_EQ(dds_delete(ddsWriter(flight.writer, Topic::kPose)), DDS_RETCODE_OK);  // writes now fail
  // Held, so the write (and its failure) certainly comes after this call returned.
  ASSERT_TRUE(DdsAccess::holdPublisher(flight.writer, 10 * kSecond));
  EXPECT_TRUE(flight.writer.publishNav(test::makeNavSolution(2)));  // queued; the failure comes later
  DdsAccess::releasePublisher(flight.writer);
  ASSERT_TRUE(flight.writer.flush(10 * kSecond));
  WriterCounters c = flight.writer.counters();
  EXPECT_EQ(c.write_failures, 1U);
  EXPECT_NE(c.last_error, 0);
  EXPECT_EQ(c.samples_written, 3U);                                     // 2 far range + the first pose
  EXPECT_FALSE(flight.writer.publishNav(test::makeNavSolution(3)));     // reports the failure of cycle 2
  EXPECT_TRUE(flight.writer.publishHealth(test::makeHealthRecord(1)));  // Health writes still succeed
  ASSERT_TRUE(flight.writer.flush(10 * kSecond));
  c = flight.writer.counters();
  EXPECT_EQ(c.write_failures, 2U);
  EXPECT_EQ(c.samples_queued, c.samples_written + c.write_failures);
}

}  // namespace
}  // namespace visnav::telemetry
