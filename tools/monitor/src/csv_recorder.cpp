#include "visnav/monitor/csv_recorder.hpp"

#include "visnav/core/types.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::monitor {
namespace {

constexpr const char* kTaskNames[visnav_TASK_COUNT] = {"acquire", "process", "publish", "health"};

// Reasons are free text: keep the CSV one record per line, no quoting needed.
std::string csvText(const char* text) {
  std::string s(text);
  for (char& c : s)
    if (c == ',' || c == '\n' || c == '\r' || c == '"') c = ';';
  return s;
}

void receptionColumns(std::FILE* f, std::int64_t publish_time_ns, const Reception& r) {
  std::fprintf(f, ",%lld,%lld,%lld,%lld\n", static_cast<long long>(publish_time_ns),
               static_cast<long long>(r.receive_mono_ns), static_cast<long long>(r.source_wall_ns),
               static_cast<long long>(r.receive_wall_ns));
}
constexpr const char* kReceptionHeader = ",publish_time_ns,receive_time_ns,source_wall_ns,receive_wall_ns\n";

}  // namespace

std::string siblingPath(const std::string& path, const char* suffix) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path + suffix + ".csv";
  return path.substr(0, dot) + suffix + path.substr(dot);
}

CsvRecorder::~CsvRecorder() { close(); }

LoadError CsvRecorder::open(const std::string& pose_path) {
  close();
  const std::string far_path = siblingPath(pose_path, "_far_range");
  const std::string health_path = siblingPath(pose_path, "_health");
  m_pose = std::fopen(pose_path.c_str(), "w");
  if (m_pose == nullptr) return LoadError::failure(pose_path + ": cannot open for writing");
  m_far = std::fopen(far_path.c_str(), "w");
  if (m_far == nullptr) return LoadError::failure(far_path + ": cannot open for writing");
  m_health = std::fopen(health_path.c_str(), "w");
  if (m_health == nullptr) return LoadError::failure(health_path + ": cannot open for writing");

  std::fputs(
      "frame,timestamp_ns,status,flags,mode,quality,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg",
      m_pose);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) std::fprintf(m_pose, ",cov_%d_%d", i, j);
  std::fprintf(m_pose,
               ",tracked_surfaces,lines_total,lines_used,symmetric_twins,twin_by_continuity,withheld,"
               "sample_number%s",
               kReceptionHeader);

  std::fprintf(m_far,
               "frame,timestamp_ns,mode,valid,flags,dir_x,dir_y,dir_z,azimuth_deg,elevation_deg,distance_m,"
               "cluster_pixels,circularity,cluster_count,quality,sample_number%s",
               kReceptionHeader);

  std::fputs("sample_number,mode,fault_bits,frames_processed,frames_dropped,cycle_slips,mode_transitions",
             m_health);
  for (int i = 0; i < visnav_FAULT_BIT_COUNT; ++i) std::fprintf(m_health, ",fault_count_%d", i);
  for (const char* task : kTaskNames)
    std::fprintf(m_health, ",t_%s_min_us,t_%s_mean_us,t_%s_max_us,t_%s_p99_us", task, task, task, task);
  std::fprintf(m_health,
               ",transition_from,transition_to,transition_frame,transition_reason,command_id,command_kind,"
               "command_accepted,command_reason%s",
               kReceptionHeader);
  return LoadError::success();
}

void CsvRecorder::pose(const visnav_PoseEstimate& s, const Reception& r) {
  if (m_pose == nullptr) return;
  // Same number formats as visnav-replay's CSV, so both score to the same digits.
  std::fprintf(m_pose, "%llu,%lld,%s,%u,%s,%.6f,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g",
               static_cast<unsigned long long>(s.frame_number), static_cast<long long>(s.exposure_time_ns),
               telemetry::trackStatusName(s.status), s.fault_bits, telemetry::modeName(s.mode), s.quality,
               s.position_m[0], s.position_m[1], s.position_m[2], s.quaternion[0], s.quaternion[1],
               s.quaternion[2], s.quaternion[3], s.yaw_rad * kDegPerRad, s.pitch_rad * kDegPerRad,
               s.roll_rad * kDegPerRad);
  for (double c : s.covariance) std::fprintf(m_pose, ",%.6g", c);
  std::fprintf(m_pose, ",%u,%u,%u,%u,%d,%u,%llu", s.tracked_surfaces, s.lines_total, s.lines_used,
               s.symmetric_twins, s.twin_by_continuity ? 1 : 0, s.withheld,
               static_cast<unsigned long long>(s.sample_number));
  receptionColumns(m_pose, s.publish_time_ns, r);
}

void CsvRecorder::farRange(const visnav_FarRangeEstimate& s, const Reception& r) {
  if (m_far == nullptr) return;
  std::fprintf(m_far, "%llu,%lld,%s,%d,%u,%.12g,%.12g,%.12g,%.9g,%.9g,%.9g,%u,%.6g,%u,%.6f,%llu",
               static_cast<unsigned long long>(s.frame_number), static_cast<long long>(s.exposure_time_ns),
               telemetry::modeName(s.mode), s.valid ? 1 : 0, s.fault_bits, s.direction_c[0], s.direction_c[1],
               s.direction_c[2], s.azimuth_rad * kDegPerRad, s.elevation_rad * kDegPerRad, s.distance_m,
               s.cluster_pixels, s.circularity, s.cluster_count, s.quality,
               static_cast<unsigned long long>(s.sample_number));
  receptionColumns(m_far, s.publish_time_ns, r);
}

void CsvRecorder::health(const visnav_Health& s, const Reception& r) {
  if (m_health == nullptr) return;
  std::fprintf(m_health, "%llu,%s,%u,%llu,%llu,%llu,%llu", static_cast<unsigned long long>(s.sample_number),
               telemetry::modeName(s.mode), s.fault_bits, static_cast<unsigned long long>(s.frames_processed),
               static_cast<unsigned long long>(s.frames_dropped),
               static_cast<unsigned long long>(s.cycle_slips),
               static_cast<unsigned long long>(s.mode_transitions));
  for (std::uint32_t count : s.fault_counts) std::fprintf(m_health, ",%u", count);
  for (const visnav_TaskTiming& t : s.task_timing)
    std::fprintf(m_health, ",%.2f,%.2f,%.2f,%.2f", t.min_us, t.mean_us, t.max_us, t.p99_us);
  std::fprintf(m_health, ",%s,%s,%llu,%s,%u,%s,%d,%s", telemetry::modeName(s.last_transition.from_mode),
               telemetry::modeName(s.last_transition.to_mode),
               static_cast<unsigned long long>(s.last_transition.frame_number),
               csvText(s.last_transition.reason).c_str(), s.last_command.command_id,
               telemetry::commandKindName(s.last_command.kind), s.last_command.accepted ? 1 : 0,
               csvText(s.last_command.reason).c_str());
  receptionColumns(m_health, s.publish_time_ns, r);
}

bool CsvRecorder::close() {
  bool ok = true;
  for (std::FILE** f : {&m_pose, &m_far, &m_health}) {
    if (*f == nullptr) continue;
    if (std::fclose(*f) != 0) ok = false;
    *f = nullptr;
  }
  return ok;
}

}  // namespace visnav::monitor
