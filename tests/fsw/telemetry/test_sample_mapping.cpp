// Flight records -> DDS samples and command validation, without a network: every field against values
// derived independently (Eigen rotations for the attitude, the test data recipe for the rest).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "telemetry_test_data.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::telemetry {
namespace {

TEST(SampleMapping, PoseEstimateEveryField) {
  const std::uint64_t i = 4;  // near range, valid pose, no fault
  const nav::NavSolution nav = test::makeNavSolution(i);
  visnav_PoseEstimate s;
  std::memset(&s, 0xA5, sizeof(s));  // every field must be overwritten
  fillPoseEstimate(nav, 17, 123456789, s);
  EXPECT_EQ(s.sample_number, 17U);
  EXPECT_EQ(s.cycle_number, 2008U);
  EXPECT_EQ(s.frame_number, 1004U);
  EXPECT_TRUE(s.frame_received);
  EXPECT_EQ(s.exposure_time_ns, 5'000'000'000LL + 4 * 200'000'000LL);
  EXPECT_EQ(s.publish_time_ns, 123456789);
  EXPECT_EQ(s.mode, visnav_NAV_MODE_NEAR_RANGE);
  EXPECT_EQ(s.status, visnav_TRACK_TRACKING);
  EXPECT_TRUE(s.pose_valid);
  EXPECT_EQ(s.fault_bits, 0U);
  // The recipe's pose: yaw 0.04, pitch -0.188, roll 2.492 rad; t = (0.096, -0.05, 24.96) m.
  const double yaw = 0.04, pitch = -0.2 + 0.012, roll = 2.5 - 0.008;
  EXPECT_DOUBLE_EQ(s.position_m[0], 0.1 - 0.004);
  EXPECT_DOUBLE_EQ(s.position_m[1], -0.05);
  EXPECT_DOUBLE_EQ(s.position_m[2], 25.0 - 0.04);
  Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                         Eigen::AngleAxisd(roll, Vec3::UnitX());
  if (q.w() < 0) q.coeffs() *= -1.0;
  EXPECT_GE(s.quaternion[0], 0.0);
  EXPECT_NEAR(s.quaternion[0], q.w(), 1e-12);
  EXPECT_NEAR(s.quaternion[1], q.x(), 1e-12);
  EXPECT_NEAR(s.quaternion[2], q.y(), 1e-12);
  EXPECT_NEAR(s.quaternion[3], q.z(), 1e-12);
  EXPECT_NEAR(s.yaw_rad, yaw, 1e-12);
  EXPECT_NEAR(s.pitch_rad, pitch, 1e-12);
  EXPECT_NEAR(s.roll_rad, roll, 1e-12);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      EXPECT_DOUBLE_EQ(s.covariance[6 * r + c], 1e-6 * (1 + r * 6 + c) + 4e-9) << r << c;
  EXPECT_DOUBLE_EQ(s.quality, 0.5 + 0.4 * 4.0 / 4.0);
  EXPECT_EQ(s.tracked_surfaces, 1U);
  EXPECT_EQ(s.lines_used, 5U);
  EXPECT_EQ(s.lines_total, 9U);
  EXPECT_EQ(s.symmetric_twins, 1U);
  EXPECT_TRUE(s.twin_by_continuity);
  EXPECT_EQ(s.withheld, 0U);  // a valid pose
  visnav_PoseEstimate withheld{};
  fillPoseEstimate(test::makeNavSolution(7), 1, 0, withheld);  // near range, its pose withheld
  EXPECT_FALSE(withheld.pose_valid);
  EXPECT_EQ(withheld.withheld, 0x82U) << "the WithheldReason bits as NavSolution gives them";
}

TEST(SampleMapping, TrackStatusFollowsPoseFaultsAndMode) {
  EXPECT_EQ(trackStatus(test::makeNavSolution(4)), visnav_TRACK_TRACKING);
  EXPECT_EQ(trackStatus(test::makeNavSolution(3)), visnav_TRACK_DEGRADED);  // fault bits, pose valid
  EXPECT_EQ(trackStatus(test::makeNavSolution(7)), visnav_TRACK_LOST);      // near range, no pose
  EXPECT_EQ(trackStatus(test::makeNavSolution(11)), visnav_TRACK_INIT);     // far range
  EXPECT_STREQ(trackStatusName(visnav_TRACK_DEGRADED), "degraded");
  EXPECT_STREQ(trackStatusName(9), "unknown");
  EXPECT_STREQ(modeName(visnav_NAV_MODE_ACQUISITION), "acquisition");
  EXPECT_STREQ(commandKindName(visnav_COMMAND_FORCE_FAR_RANGE), "force_far_range");
}

TEST(SampleMapping, CountsAreClampedToTheFieldRange) {
  nav::NavSolution nav = test::makeNavSolution(1);
  nav.lines_total = 70000;
  nav.lines_used = -3;
  visnav_PoseEstimate s{};
  fillPoseEstimate(nav, 1, 0, s);
  EXPECT_EQ(s.lines_total, 65535U);
  EXPECT_EQ(s.lines_used, 0U);
  nav.symmetric_twins = 300;  // more than a uint8 holds
  nav.twin_by_continuity = true;
  fillPoseEstimate(nav, 1, 0, s);
  EXPECT_EQ(s.symmetric_twins, 255U);
  EXPECT_TRUE(s.twin_by_continuity);
  nav.symmetric_twins = -1;
  fillPoseEstimate(nav, 1, 0, s);
  EXPECT_EQ(s.symmetric_twins, 0U);
}

TEST(SampleMapping, FarRangeEstimateEveryField) {
  const nav::NavSolution nav = test::makeNavSolution(22);  // far range, valid
  visnav_FarRangeEstimate s;
  std::memset(&s, 0xA5, sizeof(s));
  fillFarRangeEstimate(nav, 9, 42, s);
  EXPECT_EQ(s.sample_number, 9U);
  EXPECT_EQ(s.cycle_number, 2044U);
  EXPECT_EQ(s.frame_number, 1022U);
  EXPECT_TRUE(s.frame_received);
  EXPECT_EQ(s.exposure_time_ns, 5'000'000'000LL + 22 * 200'000'000LL);
  EXPECT_EQ(s.publish_time_ns, 42);
  EXPECT_EQ(s.mode, visnav_NAV_MODE_FAR_RANGE);
  EXPECT_TRUE(s.valid);
  const double norm = std::sqrt(0.22 * 0.22 + 0.02 * 0.02 + 1.0);
  EXPECT_NEAR(s.direction_c[0], 0.22 / norm, 1e-15);
  EXPECT_NEAR(s.direction_c[1], -0.02 / norm, 1e-15);
  EXPECT_NEAR(s.direction_c[2], 1.0 / norm, 1e-15);
  EXPECT_DOUBLE_EQ(s.azimuth_rad, 0.022);
  EXPECT_DOUBLE_EQ(s.elevation_rad, -0.044);
  EXPECT_DOUBLE_EQ(s.distance_m, 278.0);
  EXPECT_EQ(s.cluster_pixels, 72U);
  EXPECT_DOUBLE_EQ(s.circularity, 0.9 - 0.022);
  EXPECT_EQ(s.cluster_count, 2U);
  EXPECT_DOUBLE_EQ(s.quality, 0.25);
  EXPECT_EQ(s.fault_bits, 0U);
}

TEST(SampleMapping, HealthEveryField) {
  const nav::HealthRecord h = test::makeHealthRecord(5);
  visnav_Health s;
  std::memset(&s, 0xA5, sizeof(s));
  fillHealth(h, 3, 77, s);
  EXPECT_EQ(s.sample_number, 3U);
  EXPECT_EQ(s.publish_time_ns, 77);
  EXPECT_EQ(s.mode, visnav_NAV_MODE_ACQUISITION);
  EXPECT_EQ(s.fault_bits, 5U);
  for (int b = 0; b < visnav_FAULT_BIT_COUNT; ++b) EXPECT_EQ(s.fault_counts[b], 500U + b);
  EXPECT_EQ(s.frames_processed, 50U);
  EXPECT_EQ(s.frames_dropped, 2U);
  EXPECT_EQ(s.cycle_slips, 1U);
  EXPECT_EQ(s.mode_transitions, 1U);
  for (int t = 0; t < visnav_TASK_COUNT; ++t) {
    const double base = 10.0 * (t + 1) + 5.0;
    EXPECT_DOUBLE_EQ(s.task_timing[t].min_us, base);
    EXPECT_DOUBLE_EQ(s.task_timing[t].mean_us, base + 1.5);
    EXPECT_DOUBLE_EQ(s.task_timing[t].max_us, base + 9.0);
    EXPECT_DOUBLE_EQ(s.task_timing[t].p99_us, base + 7.25);
  }
  EXPECT_EQ(s.last_transition.from_mode, visnav_NAV_MODE_ACQUISITION);
  EXPECT_EQ(s.last_transition.to_mode, visnav_NAV_MODE_NEAR_RANGE);
  EXPECT_EQ(s.last_transition.frame_number, 995U);
  EXPECT_STREQ(s.last_transition.reason, "acquired, transition 5");
  EXPECT_EQ(s.last_command.command_id, 45U);
  EXPECT_EQ(s.last_command.kind, visnav_COMMAND_REACQUIRE);
  EXPECT_TRUE(s.last_command.accepted);
  EXPECT_STREQ(s.last_command.reason, "reason 5");
  // Bytes after the terminator are zeroed (deterministic samples on the wire).
  for (std::size_t k = std::strlen(s.last_command.reason); k < sizeof(s.last_command.reason); ++k)
    EXPECT_EQ(s.last_command.reason[k], '\0');
}

TEST(SampleMapping, CopyBoundedTruncatesAndTerminates) {
  char out[8];
  copyBounded("0123456789", out, sizeof(out));
  EXPECT_STREQ(out, "0123456");
  copyBounded("ab", out, sizeof(out));
  EXPECT_STREQ(out, "ab");
}

TEST(CommandValidation, KnownKindsAreValid) {
  for (std::uint8_t kind = 0; kind <= visnav_COMMAND_RESUME; ++kind) {
    const ReceivedCommand c = validateCommand(visnav_ModeCommand{7, kind});
    EXPECT_TRUE(c.valid) << int{kind};
    EXPECT_EQ(c.command_id, 7U);
    EXPECT_EQ(static_cast<int>(c.kind), kind);
    EXPECT_STREQ(c.reason.data(), "ok");
  }
}

TEST(CommandValidation, UnknownKindAndReservedIdAreRejectedWithAReason) {
  const ReceivedCommand unknown = validateCommand(visnav_ModeCommand{12, 200});
  EXPECT_FALSE(unknown.valid);
  EXPECT_EQ(unknown.raw_kind, 200);
  EXPECT_STREQ(unknown.reason.data(), "unknown command kind 200");
  const ReceivedCommand zero = validateCommand(visnav_ModeCommand{0, visnav_COMMAND_STANDBY});
  EXPECT_FALSE(zero.valid);
  EXPECT_NE(std::string(zero.reason.data()).find("command_id 0 is reserved"), std::string::npos);
}

TEST(CommandValidation, AckCarriesTheDecisionButNeverAcceptsAnInvalidCommand) {
  const ReceivedCommand good = validateCommand(visnav_ModeCommand{5, visnav_COMMAND_REACQUIRE});
  nav::CommandAck a = good.ack(false, "no far-range cue yet");
  EXPECT_EQ(a.command_id, 5U);
  EXPECT_EQ(a.kind, nav::ModeCommandKind::kReacquire);
  EXPECT_FALSE(a.accepted);
  EXPECT_STREQ(a.reason.data(), "no far-range cue yet");
  EXPECT_TRUE(good.ack(true, "ok").accepted);
  const ReceivedCommand bad = validateCommand(visnav_ModeCommand{6, 4});
  a = bad.ack(true, "ok");
  EXPECT_FALSE(a.accepted);
  EXPECT_STREQ(a.reason.data(), "unknown command kind 4");
  EXPECT_STREQ(bad.rejection().reason.data(), "unknown command kind 4");
}

}  // namespace
}  // namespace visnav::telemetry
