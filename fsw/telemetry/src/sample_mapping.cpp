#include "visnav/telemetry/sample_mapping.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace visnav::telemetry {
namespace {

constexpr const char* kModeNames[] = {"standby", "far_range", "acquisition", "near_range"};
constexpr const char* kTrackNames[] = {"tracking", "degraded", "lost", "init"};
constexpr const char* kCommandNames[] = {"force_far_range", "reacquire", "standby", "resume"};
template <std::size_t N>
const char* lookup(const char* const (&names)[N], std::uint8_t value) {
  return value < N ? names[value] : "unknown";
}

std::uint8_t modeValue(nav::NavMode mode) { return static_cast<std::uint8_t>(mode); }

std::uint16_t clampCount(int count) {
  if (count < 0) return 0;
  return count > 0xFFFF ? std::uint16_t{0xFFFF} : static_cast<std::uint16_t>(count);
}

void copyVec3(const Vec3& v, double* out) {
  for (int i = 0; i < 3; ++i) out[i] = v[i];
}

}  // namespace

static_assert(static_cast<int>(nav::NavMode::kStandby) == visnav_NAV_MODE_STANDBY &&
                  static_cast<int>(nav::NavMode::kFarRange) == visnav_NAV_MODE_FAR_RANGE &&
                  static_cast<int>(nav::NavMode::kAcquisition) == visnav_NAV_MODE_ACQUISITION &&
                  static_cast<int>(nav::NavMode::kNearRange) == visnav_NAV_MODE_NEAR_RANGE,
              "idl/visnav.idl NAV_MODE_* must equal visnav::nav::NavMode");
static_assert(static_cast<int>(nav::ModeCommandKind::kForceFarRange) == visnav_COMMAND_FORCE_FAR_RANGE &&
                  static_cast<int>(nav::ModeCommandKind::kReacquire) == visnav_COMMAND_REACQUIRE &&
                  static_cast<int>(nav::ModeCommandKind::kStandby) == visnav_COMMAND_STANDBY &&
                  static_cast<int>(nav::ModeCommandKind::kResume) == visnav_COMMAND_RESUME,
              "idl/visnav.idl COMMAND_* must equal visnav::nav::ModeCommandKind");
static_assert(nav::kFaultBitCount == visnav_FAULT_BIT_COUNT, "idl FAULT_BIT_COUNT != nav::kFaultBitCount");
static_assert(nav::kTaskCount == visnav_TASK_COUNT, "idl TASK_COUNT != nav::kTaskCount");
static_assert(sizeof(visnav_Health{}.last_command.reason) == sizeof(nav::CommandAck{}.reason),
              "reason strings must have the same capacity on both sides");

std::uint8_t trackStatus(const nav::NavSolution& nav) {
  if (nav.pose_valid) return nav.fault_bits == 0 ? visnav_TRACK_TRACKING : visnav_TRACK_DEGRADED;
  return nav.mode == nav::NavMode::kNearRange ? visnav_TRACK_LOST : visnav_TRACK_INIT;
}

const char* trackStatusName(std::uint8_t status) { return lookup(kTrackNames, status); }
const char* modeName(std::uint8_t mode) { return lookup(kModeNames, mode); }
const char* commandKindName(std::uint8_t kind) { return lookup(kCommandNames, kind); }

void fillPoseEstimate(const nav::NavSolution& nav, std::uint64_t sample_number, std::int64_t publish_time_ns,
                      visnav_PoseEstimate& out) {
  out.sample_number = sample_number;
  out.cycle_number = nav.cycle_number;
  out.frame_number = nav.frame_number;
  out.frame_received = nav.frame_received;
  out.exposure_time_ns = nav.exposure_time_ns;
  out.publish_time_ns = publish_time_ns;
  out.mode = modeValue(nav.mode);
  out.status = trackStatus(nav);
  out.pose_valid = nav.pose_valid;
  out.fault_bits = nav.fault_bits;
  copyVec3(nav.pose.t_c_m, out.position_m);
  Eigen::Quaterniond q = nav.pose.quaternion();
  if (q.w() < 0.0) q.coeffs() *= -1.0;  // CONVENTIONS.md: w >= 0
  out.quaternion[0] = q.w();
  out.quaternion[1] = q.x();
  out.quaternion[2] = q.y();
  out.quaternion[3] = q.z();
  const YawPitchRoll ypr = nav.pose.ypr();
  out.yaw_rad = ypr.yaw_rad;
  out.pitch_rad = ypr.pitch_rad;
  out.roll_rad = ypr.roll_rad;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out.covariance[6 * i + j] = nav.covariance(i, j);
  out.quality = nav.quality;
  out.tracked_surfaces = clampCount(nav.tracked_surfaces);
  out.lines_used = clampCount(nav.lines_used);
  out.lines_total = clampCount(nav.lines_total);
  out.symmetric_twins = static_cast<std::uint8_t>(std::clamp(nav.symmetric_twins, 0, 255));
  out.twin_by_continuity = nav.twin_by_continuity;
  out.withheld = nav.withheld;
}

void fillFarRangeEstimate(const nav::NavSolution& nav, std::uint64_t sample_number,
                          std::int64_t publish_time_ns, visnav_FarRangeEstimate& out) {
  const nav::FarRangeSolution& far = nav.far;
  out.sample_number = sample_number;
  out.cycle_number = nav.cycle_number;
  out.frame_number = nav.frame_number;
  out.frame_received = nav.frame_received;
  out.exposure_time_ns = nav.exposure_time_ns;
  out.publish_time_ns = publish_time_ns;
  out.mode = modeValue(nav.mode);
  out.valid = far.valid;
  out.fault_bits = nav.fault_bits;
  copyVec3(far.direction_c, out.direction_c);
  out.azimuth_rad = far.azimuth_rad;
  out.elevation_rad = far.elevation_rad;
  out.distance_m = far.distance_m;
  out.cluster_pixels = far.cluster_pixels < 0 ? 0U : static_cast<std::uint32_t>(far.cluster_pixels);
  out.circularity = far.circularity;
  out.cluster_count = clampCount(far.cluster_count);
  out.quality = far.quality;
}

void fillHealth(const nav::HealthRecord& health, std::uint64_t sample_number, std::int64_t publish_time_ns,
                visnav_Health& out) {
  out.sample_number = sample_number;
  out.publish_time_ns = publish_time_ns;
  out.mode = modeValue(health.mode);
  out.fault_bits = health.fault_bits;
  for (int i = 0; i < nav::kFaultBitCount; ++i) out.fault_counts[i] = health.fault_counts[i];
  out.frames_processed = health.frames_processed;
  out.frames_dropped = health.frames_dropped;
  out.cycle_slips = health.cycle_slips;
  out.mode_transitions = health.mode_transitions;
  for (int i = 0; i < nav::kTaskCount; ++i) {
    const nav::TaskTimingSummary& t = health.task_timing[i];
    out.task_timing[i] = visnav_TaskTiming{t.min_us, t.mean_us, t.max_us, t.p99_us};
  }
  out.last_transition.from_mode = modeValue(health.last_transition.from);
  out.last_transition.to_mode = modeValue(health.last_transition.to);
  out.last_transition.frame_number = health.last_transition.frame_number;
  copyBounded(health.last_transition.reason.data(), out.last_transition.reason,
              sizeof(out.last_transition.reason));
  out.last_command.command_id = health.last_command.command_id;
  out.last_command.kind = static_cast<std::uint8_t>(health.last_command.kind);
  out.last_command.accepted = health.last_command.accepted;
  copyBounded(health.last_command.reason.data(), out.last_command.reason, sizeof(out.last_command.reason));
}

nav::CommandAck ReceivedCommand::ack(bool accepted, const char* why) const {
  nav::CommandAck a;
  a.command_id = command_id;
  a.kind = kind;
  a.accepted = valid && accepted;
  copyBounded(valid ? why : reason.data(), a.reason.data(), a.reason.size());
  return a;
}

ReceivedCommand validateCommand(const visnav_ModeCommand& sample) {
  ReceivedCommand c;
  c.command_id = sample.command_id;
  c.raw_kind = sample.kind;
  if (sample.command_id == 0) {
    copyBounded("command_id 0 is reserved (use 1..4294967295)", c.reason.data(), c.reason.size());
    return c;
  }
  if (sample.kind > visnav_COMMAND_RESUME) {
    std::snprintf(c.reason.data(), c.reason.size(), "unknown command kind %u",
                  static_cast<unsigned>(sample.kind));
    return c;
  }
  c.kind = static_cast<nav::ModeCommandKind>(sample.kind);
  c.valid = true;
  copyBounded("ok", c.reason.data(), c.reason.size());
  return c;
}

}  // namespace visnav::telemetry
