// Real Cyclone DDS (loopback config from ctest), flight and ground sides in one process with separate
// participants: round trip of every type field by field, transient-local Health for a late reader, command
// validation and acknowledgment, the command queue bound, the pose deadline.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "telemetry_test_data.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/ground_link.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace visnav::telemetry {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::int64_t kPeriod = 200'000'000;  // 5 Hz

// Collects `count` data samples of one topic (bounded by `timeout_ns`).
template <typename Sample, typename Take>
std::vector<Sample> receive(GroundLink& ground, Take take, std::size_t count, std::int64_t timeout_ns) {
  std::vector<Sample> got;
  std::vector<Sample> batch(kMaxTakeBatch);
  std::vector<dds_sample_info_t> infos(kMaxTakeBatch);
  const std::int64_t end = monotonicNowNs() + timeout_ns;
  while (got.size() < count && monotonicNowNs() < end) {
    ground.waitForData(20'000'000);
    const int n = take(ground, batch.data(), infos.data(), kMaxTakeBatch);
    for (int i = 0; i < n; ++i)
      if (infos[i].valid_data) got.push_back(batch[i]);
  }
  return got;
}

std::vector<visnav_PoseEstimate> receivePose(GroundLink& g, std::size_t count, std::int64_t timeout_ns) {
  return receive<visnav_PoseEstimate>(
      g,
      [](GroundLink& l, visnav_PoseEstimate* o, dds_sample_info_t* i, int c) { return l.takePose(o, i, c); },
      count, timeout_ns);
}
std::vector<visnav_FarRangeEstimate> receiveFar(GroundLink& g, std::size_t count, std::int64_t timeout_ns) {
  return receive<visnav_FarRangeEstimate>(
      g,
      [](GroundLink& l, visnav_FarRangeEstimate* o, dds_sample_info_t* i, int c) {
        return l.takeFarRange(o, i, c);
      },
      count, timeout_ns);
}
std::vector<visnav_Health> receiveHealth(GroundLink& g, std::size_t count, std::int64_t timeout_ns) {
  return receive<visnav_Health>(
      g, [](GroundLink& l, visnav_Health* o, dds_sample_info_t* i, int c) { return l.takeHealth(o, i, c); },
      count, timeout_ns);
}

class TelemetryDds : public ::testing::Test {
 protected:
  void SetUp() override {
    params = test::uniqueLinkParams(::testing::UnitTest::GetInstance()->current_test_info()->name());
    ASSERT_TRUE(flight.init(params.domain_id, params.partitionName()).ok);
    ASSERT_TRUE(writer.init(flight, params, kPeriod).ok);
    ASSERT_TRUE(commands.init(flight, params).ok);
  }
  void connectGround() {
    const LoadError e = ground.init(params, 64);
    ASSERT_TRUE(e.ok) << e.message;
    for (Topic t : {Topic::kPose, Topic::kFarRange, Topic::kHealth})
      ASSERT_TRUE(waitForReaders(ddsWriter(writer, t), 1, 5 * kSecond)) << topicName(t);
    ASSERT_TRUE(waitForReaders(ground.commandWriter(), 1, 5 * kSecond));
    // Discovery is two-sided: until a reader has matched the writer too, it drops what that writer sends.
    for (Topic t : {Topic::kPose, Topic::kFarRange, Topic::kHealth})
      ASSERT_TRUE(waitForWriters(ground.reader(t), 1, 5 * kSecond)) << topicName(t);
    ASSERT_TRUE(waitForWriters(ddsReader(commands), 1, 5 * kSecond));
  }

  TelemetryParams params;
  Participant flight;
  TelemetryWriter writer;
  CommandReader commands;
  GroundLink ground;
};

TEST_F(TelemetryDds, PoseAndFarRangeRoundTripFieldByField) {
  connectGround();
  constexpr std::uint64_t kCount = 22;  // covers tracking, degraded, lost and far-range solutions
  const std::int64_t before = monotonicNowNs();
  // Each acknowledged before the next: the writer keeps only the last history_depth (8) samples, and a reader
  // on a loaded machine can fall that far behind a burst.
  for (std::uint64_t i = 1; i <= kCount; ++i) {
    ASSERT_TRUE(writer.publishNav(test::makeNavSolution(i)));
    ASSERT_TRUE(writer.waitForAcks(10 * kSecond)) << i;
  }
  const std::int64_t after = monotonicNowNs();
  const auto poses = receivePose(ground, kCount, 10 * kSecond);
  const auto fars = receiveFar(ground, kCount, 10 * kSecond);
  ASSERT_EQ(poses.size(), kCount);
  ASSERT_EQ(fars.size(), kCount);
  for (std::uint64_t i = 1; i <= kCount; ++i) {
    const visnav_PoseEstimate& p = poses[i - 1];
    const nav::NavSolution n = test::makeNavSolution(i);
    EXPECT_EQ(p.sample_number, i);
    EXPECT_EQ(p.cycle_number, n.cycle_number);
    EXPECT_EQ(p.frame_number, 1000 + i);
    EXPECT_EQ(p.frame_received, n.frame_received);
    EXPECT_EQ(p.exposure_time_ns, n.exposure_time_ns);
    EXPECT_GE(p.publish_time_ns, before);
    EXPECT_LE(p.publish_time_ns, after);
    EXPECT_EQ(p.mode, static_cast<std::uint8_t>(n.mode));
    EXPECT_EQ(p.status, trackStatus(n));
    EXPECT_EQ(p.pose_valid, n.pose_valid);
    EXPECT_EQ(p.fault_bits, n.fault_bits);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(p.position_m[k], n.pose.t_c_m[k]);  // doubles travel bit-exact
    const Eigen::Quaterniond q(p.quaternion[0], p.quaternion[1], p.quaternion[2], p.quaternion[3]);
    EXPECT_LE((q.toRotationMatrix() - n.pose.R_c_m).norm(), 1e-12);
    EXPECT_LE((rotationFromYpr({p.yaw_rad, p.pitch_rad, p.roll_rad}) - n.pose.R_c_m).norm(), 1e-12);
    for (int k = 0; k < 36; ++k) EXPECT_EQ(p.covariance[k], n.covariance(k / 6, k % 6));
    EXPECT_EQ(p.quality, n.quality);
    EXPECT_EQ(p.tracked_surfaces, n.tracked_surfaces);
    EXPECT_EQ(p.lines_used, n.lines_used);
    EXPECT_EQ(p.lines_total, n.lines_total);
    EXPECT_EQ(p.symmetric_twins, n.symmetric_twins);
    EXPECT_EQ(p.twin_by_continuity, n.twin_by_continuity);
    EXPECT_EQ(p.withheld, n.withheld);

    const visnav_FarRangeEstimate& f = fars[i - 1];
    EXPECT_EQ(f.sample_number, i);
    EXPECT_EQ(f.cycle_number, n.cycle_number);
    EXPECT_EQ(f.frame_number, 1000 + i);
    EXPECT_EQ(f.frame_received, n.frame_received);
    EXPECT_EQ(f.exposure_time_ns, n.exposure_time_ns);
    EXPECT_EQ(f.publish_time_ns, p.publish_time_ns);
    EXPECT_EQ(f.mode, static_cast<std::uint8_t>(n.mode));
    EXPECT_EQ(f.valid, n.far.valid);
    EXPECT_EQ(f.fault_bits, n.fault_bits);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(f.direction_c[k], n.far.direction_c[k]);
    EXPECT_EQ(f.azimuth_rad, n.far.azimuth_rad);
    EXPECT_EQ(f.elevation_rad, n.far.elevation_rad);
    EXPECT_EQ(f.distance_m, n.far.distance_m);
    EXPECT_EQ(f.cluster_pixels, static_cast<std::uint32_t>(n.far.cluster_pixels));
    EXPECT_EQ(f.circularity, n.far.circularity);
    EXPECT_EQ(f.cluster_count, n.far.cluster_count);
    EXPECT_EQ(f.quality, n.far.quality);
  }
  ASSERT_TRUE(writer.flush(5 * kSecond));  // counted after dds_write returns, maybe after the reader got it
  EXPECT_EQ(writer.counters().samples_queued, 2 * kCount);
  EXPECT_EQ(writer.counters().samples_written, 2 * kCount);
  EXPECT_EQ(writer.counters().samples_dropped, 0U);
  EXPECT_EQ(writer.counters().write_failures, 0U);
}

TEST_F(TelemetryDds, HealthRoundTripFieldByField) {
  connectGround();
  for (std::uint64_t i = 1; i <= 3; ++i) ASSERT_TRUE(writer.publishHealth(test::makeHealthRecord(i)));
  const auto got = receiveHealth(ground, 3, 10 * kSecond);
  ASSERT_EQ(got.size(), 3U);
  for (std::uint64_t i = 1; i <= 3; ++i) {
    const visnav_Health& s = got[i - 1];
    const nav::HealthRecord h = test::makeHealthRecord(i);
    EXPECT_EQ(s.sample_number, i);
    EXPECT_EQ(s.mode, static_cast<std::uint8_t>(h.mode));
    EXPECT_EQ(s.fault_bits, h.fault_bits);
    for (int b = 0; b < nav::kFaultBitCount; ++b) EXPECT_EQ(s.fault_counts[b], h.fault_counts[b]);
    EXPECT_EQ(s.frames_processed, h.frames_processed);
    EXPECT_EQ(s.frames_dropped, h.frames_dropped);
    EXPECT_EQ(s.cycle_slips, h.cycle_slips);
    EXPECT_EQ(s.mode_transitions, h.mode_transitions);
    for (int t = 0; t < nav::kTaskCount; ++t) {
      EXPECT_EQ(s.task_timing[t].min_us, h.task_timing[t].min_us);
      EXPECT_EQ(s.task_timing[t].mean_us, h.task_timing[t].mean_us);
      EXPECT_EQ(s.task_timing[t].max_us, h.task_timing[t].max_us);
      EXPECT_EQ(s.task_timing[t].p99_us, h.task_timing[t].p99_us);
    }
    EXPECT_EQ(s.last_transition.from_mode, static_cast<std::uint8_t>(h.last_transition.from));
    EXPECT_EQ(s.last_transition.to_mode, static_cast<std::uint8_t>(h.last_transition.to));
    EXPECT_EQ(s.last_transition.frame_number, h.last_transition.frame_number);
    EXPECT_STREQ(s.last_transition.reason, h.last_transition.reason.data());
    EXPECT_EQ(s.last_command.command_id, h.last_command.command_id);
    EXPECT_EQ(s.last_command.kind, static_cast<std::uint8_t>(h.last_command.kind));
    EXPECT_EQ(s.last_command.accepted, h.last_command.accepted);
    EXPECT_STREQ(s.last_command.reason, h.last_command.reason.data());
  }
}

TEST_F(TelemetryDds, LateReaderGetsTheLastHealthButNoOldPose) {
  for (std::uint64_t i = 1; i <= 5; ++i) {
    ASSERT_TRUE(writer.publishHealth(test::makeHealthRecord(i)));
    ASSERT_TRUE(writer.publishNav(test::makeNavSolution(i)));
  }
  ASSERT_TRUE(writer.flush(5 * kSecond));  // the publisher thread has written all of it
  connectGround();                         // joins after everything was written
  const auto health = receiveHealth(ground, 1, 5 * kSecond);
  ASSERT_EQ(health.size(), 1U);
  EXPECT_EQ(health[0].sample_number, 5U);  // keep-last 1: the current state only
  EXPECT_EQ(health[0].frames_processed, 50U);
  EXPECT_TRUE(receiveHealth(ground, 1, kSecond / 2).empty());  // and nothing older follows
  EXPECT_TRUE(receivePose(ground, 1, kSecond / 2).empty());    // pose is volatile: history is not replayed
}

TEST_F(TelemetryDds, CommandsAreValidatedAndAcknowledgedInHealth) {
  connectGround();
  ASSERT_EQ(ground.sendCommand(101, visnav_COMMAND_FORCE_FAR_RANGE), DDS_RETCODE_OK);
  ASSERT_EQ(ground.sendCommand(102, 9), DDS_RETCODE_OK);  // garbage kind
  ASSERT_EQ(ground.sendCommand(0, visnav_COMMAND_RESUME), DDS_RETCODE_OK);
  std::vector<ReceivedCommand> got;
  ReceivedCommand batch[kMaxCommandDepth];
  const std::int64_t end = monotonicNowNs() + 5 * kSecond;
  while (got.size() < 3 && monotonicNowNs() < end) {  // the flight side polls once per (short) cycle
    const int n = commands.poll(batch, kMaxCommandDepth);
    got.insert(got.end(), batch, batch + n);
    dds_sleepfor(DDS_MSECS(10));
  }
  ASSERT_EQ(got.size(), 3U);
  EXPECT_TRUE(got[0].valid);
  EXPECT_EQ(got[0].command_id, 101U);
  EXPECT_EQ(got[0].kind, nav::ModeCommandKind::kForceFarRange);
  EXPECT_FALSE(got[1].valid);
  EXPECT_STREQ(got[1].reason.data(), "unknown command kind 9");
  EXPECT_FALSE(got[2].valid);
  EXPECT_EQ(commands.counters().received, 3U);
  EXPECT_EQ(commands.counters().rejected, 2U);
  EXPECT_EQ(commands.poll(batch, kMaxCommandDepth), 0);  // taken: never delivered twice

  // The flight side acknowledges the rejected one; the ground sees the reason in Health.
  nav::HealthRecord health = test::makeHealthRecord(1);
  health.last_command = got[1].rejection();
  ASSERT_TRUE(writer.publishHealth(health));
  const auto acks = receiveHealth(ground, 1, 5 * kSecond);
  ASSERT_EQ(acks.size(), 1U);
  EXPECT_EQ(acks[0].last_command.command_id, 102U);
  EXPECT_FALSE(acks[0].last_command.accepted);
  EXPECT_STREQ(acks[0].last_command.reason, "unknown command kind 9");
}

TEST_F(TelemetryDds, CommandQueueIsBoundedByItsDepth) {
  connectGround();
  const int sent = params.command_depth + 5;
  for (int k = 1; k <= sent; ++k)
    ASSERT_EQ(ground.sendCommand(static_cast<std::uint32_t>(k), visnav_COMMAND_STANDBY), DDS_RETCODE_OK);
  ASSERT_EQ(dds_wait_for_acks(ground.commandWriter(), DDS_SECS(5)), DDS_RETCODE_OK);
  ReceivedCommand batch[kMaxCommandDepth];
  const int n = commands.poll(batch, kMaxCommandDepth);
  ASSERT_EQ(n, params.command_depth);  // keep-last depth: the newest ones, oldest first
  for (int k = 0; k < n; ++k) EXPECT_EQ(batch[k].command_id, static_cast<std::uint32_t>(sent - n + 1 + k));
}

TEST(TelemetryDeadline, MissedOnlyWhenACycleIsSkipped) {
  const TelemetryParams params = test::uniqueLinkParams("deadline");
  Participant flight;
  ASSERT_TRUE(flight.init(params.domain_id, params.partitionName()).ok);
  TelemetryWriter writer;
  constexpr std::int64_t kShortPeriod = 100'000'000;  // deadline 150 ms
  ASSERT_TRUE(writer.init(flight, params, kShortPeriod).ok);
  for (std::uint64_t i = 1; i <= 6; ++i) {
    ASSERT_TRUE(writer.publishNav(test::makeNavSolution(i)));
    dds_sleepfor(kShortPeriod);
  }
  EXPECT_EQ(writer.poseDeadlineMisses(), 0U);
  dds_sleepfor(5 * kShortPeriod);  // the pipeline stalls: nothing published for 5 periods
  EXPECT_GE(writer.poseDeadlineMisses(), 1U);
}

}  // namespace
}  // namespace visnav::telemetry
