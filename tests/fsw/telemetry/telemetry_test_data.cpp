#include "telemetry_test_data.hpp"

#include <unistd.h>

#include <cstdio>

#include "visnav/geometry/pose.hpp"

namespace visnav::telemetry::test {

nav::NavSolution makeNavSolution(std::uint64_t i) {
  const auto x = static_cast<double>(i);
  nav::NavSolution s;
  s.cycle_number = 2000 + 2 * i;  // cycles without a frame between the published ones
  s.frame_number = 1000 + i;
  s.frame_received = i % 13 != 0;
  s.exposure_time_ns = 5'000'000'000LL + static_cast<std::int64_t>(i) * 200'000'000LL;
  const bool far = i % 11 == 0;
  const bool lost = !far && i % 7 == 0;
  s.mode = far ? nav::NavMode::kFarRange : nav::NavMode::kNearRange;
  s.pose_valid = !far && !lost;
  s.pose = Pose::fromYpr({0.01 * x, -0.2 + 0.003 * x, 2.5 - 0.002 * x},
                         Vec3(0.1 - 0.001 * x, -0.05, 25.0 - 0.01 * x));
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) s.covariance(r, c) = 1e-6 * (1 + r * 6 + c) + 1e-9 * x;
  s.quality = 0.5 + 0.4 * static_cast<double>(i % 5) / 4.0;
  s.tracked_surfaces = static_cast<int>(1 + i % 4);
  s.lines_used = static_cast<int>(4 + i % 3);
  s.lines_total = static_cast<int>(8 + i % 3);
  s.symmetric_twins = s.pose_valid ? static_cast<int>(1 + i % 4) : 0;
  s.twin_by_continuity = s.pose_valid && i % 2 == 0;
  s.withheld = lost ? nav::kWithheldDoubted | nav::kWithheldBranchUnknown : 0U;
  s.far.valid = far;
  s.far.direction_c = Vec3(0.01 * x, -0.02, 1.0).normalized();
  s.far.azimuth_rad = 0.001 * x;
  s.far.elevation_rad = -0.002 * x;
  s.far.distance_m = 300.0 - x;
  s.far.cluster_pixels = static_cast<int>(50 + i);
  s.far.circularity = 0.9 - 0.001 * x;
  s.far.cluster_count = static_cast<int>(1 + i % 3);
  s.far.quality = 0.25;
  s.fault_bits = i % 3 == 0 ? (nav::kFaultResidual | nav::kFaultTooFewLines) : 0U;
  s.timing = {100.0 + x, 2000.0 + x, 50.0, 20.0};
  return s;
}

nav::HealthRecord makeHealthRecord(std::uint64_t i) {
  nav::HealthRecord h;
  h.mode = i % 2 == 0 ? nav::NavMode::kNearRange : nav::NavMode::kAcquisition;
  h.fault_bits = static_cast<std::uint32_t>(i) & 0x7FFU;
  for (int b = 0; b < nav::kFaultBitCount; ++b) h.fault_counts[b] = static_cast<std::uint32_t>(i * 100 + b);
  h.frames_processed = 10 * i;
  h.frames_dropped = i / 2;
  h.cycle_slips = i / 3;
  h.mode_transitions = i / 4;
  h.last_transition.from = nav::NavMode::kAcquisition;
  h.last_transition.to = nav::NavMode::kNearRange;
  h.last_transition.frame_number = 990 + i;
  std::snprintf(h.last_transition.reason.data(), h.last_transition.reason.size(), "acquired, transition %llu",
                static_cast<unsigned long long>(i));
  h.last_command.command_id = static_cast<std::uint32_t>(40 + i);
  h.last_command.kind = nav::ModeCommandKind::kReacquire;
  h.last_command.accepted = i % 2 == 1;
  std::snprintf(h.last_command.reason.data(), h.last_command.reason.size(), "reason %llu",
                static_cast<unsigned long long>(i));
  for (int t = 0; t < nav::kTaskCount; ++t) {
    const double base = 10.0 * (t + 1) + static_cast<double>(i);
    h.task_timing[t] = {base, base + 1.5, base + 9.0, base + 7.25};
  }
  return h;
}

TelemetryParams uniqueLinkParams(const std::string& name) {
  TelemetryParams params;
  const std::string partition = name + "-" + std::to_string(getpid());
  setPartition(params, partition.c_str());
  return params;
}

int isolatedDomainId() { return 100 + static_cast<int>(getpid() % 100); }

TelemetryParams isolatedLinkParams(const std::string& name) {
  TelemetryParams params = uniqueLinkParams(name);
  params.domain_id = isolatedDomainId();
  return params;
}

}  // namespace visnav::telemetry::test
