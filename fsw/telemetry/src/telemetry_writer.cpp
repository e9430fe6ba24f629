#include "visnav/telemetry/telemetry_writer.hpp"

#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::telemetry {
namespace {

dds_entity_t createWriter(const Participant& participant, Topic topic, const TelemetryParams& params,
                          std::int64_t cycle_period_ns, const PooledSertype** sertype) {
  const dds_entity_t pooled_topic =
      createPooledTopic(participant.handle(), topicName(topic), topicDescriptor(topic),
                        static_cast<std::uint32_t>(params.sample_pool_blocks), sertype);
  if (pooled_topic < 0) return pooled_topic;
  dds_qos_t* qos = makeWriterQos(topic, params, cycle_period_ns);
  const dds_entity_t writer = dds_create_writer(participant.publisher(), pooled_topic, qos, nullptr);
  dds_delete_qos(qos);
  return writer;
}

}  // namespace

LoadError TelemetryWriter::init(const Participant& participant, const TelemetryParams& params,
                                std::int64_t cycle_period_ns) {
  if (!participant.isOpen()) return LoadError::failure("telemetry writer: participant not initialised");
  m_pose_writer = createWriter(participant, Topic::kPose, params, cycle_period_ns, &m_sertypes[0]);
  if (m_pose_writer < 0) return ddsFailure("creating the pose writer", m_pose_writer);
  m_far_writer = createWriter(participant, Topic::kFarRange, params, cycle_period_ns, &m_sertypes[1]);
  if (m_far_writer < 0) return ddsFailure("creating the far-range writer", m_far_writer);
  m_health_writer = createWriter(participant, Topic::kHealth, params, cycle_period_ns, &m_sertypes[2]);
  if (m_health_writer < 0) return ddsFailure("creating the health writer", m_health_writer);
  m_nav_samples = 0;
  m_health_samples = 0;
  m_counters = WriterCounters{};
  return LoadError::success();
}

bool TelemetryWriter::write(dds_entity_t writer, const void* sample) {
  const dds_return_t rc = dds_write(writer, sample);
  if (rc == DDS_RETCODE_OK) {
    ++m_counters.samples_written;
    return true;
  }
  ++m_counters.write_failures;
  if (rc == DDS_RETCODE_TIMEOUT) ++m_counters.write_timeouts;
  m_counters.last_error = rc;
  return false;
}

bool TelemetryWriter::publishNav(const nav::NavSolution& nav) {
  if (m_pose_writer <= 0) return false;
  ++m_nav_samples;
  const std::int64_t now_ns = monotonicNowNs();
  fillPoseEstimate(nav, m_nav_samples, now_ns, m_pose);
  fillFarRangeEstimate(nav, m_nav_samples, now_ns, m_far);
  const bool pose_ok = write(m_pose_writer, &m_pose);
  const bool far_ok = write(m_far_writer, &m_far);
  return pose_ok && far_ok;
}

bool TelemetryWriter::publishHealth(const nav::HealthRecord& health) {
  if (m_health_writer <= 0) return false;
  ++m_health_samples;
  fillHealth(health, m_health_samples, monotonicNowNs(), m_health);
  return write(m_health_writer, &m_health);
}

dds_entity_t TelemetryWriter::writer(Topic topic) const {
  switch (topic) {
    case Topic::kPose: return m_pose_writer;
    case Topic::kFarRange: return m_far_writer;
    case Topic::kHealth: return m_health_writer;
    case Topic::kModeCommand: break;
  }
  return 0;
}

bool TelemetryWriter::waitForReaders(std::uint32_t count, std::int64_t timeout_ns, Topic& missing) const {
  const std::int64_t deadline_ns = monotonicNowNs() + timeout_ns;
  for (Topic topic : kFlightTopics) {
    const std::int64_t left_ns = deadline_ns - monotonicNowNs();
    if (!telemetry::waitForReaders(writer(topic), count, left_ns > 0 ? left_ns : 0)) {
      missing = topic;
      return false;
    }
  }
  return true;
}

bool TelemetryWriter::waitForAcks(std::int64_t timeout_ns) const {
  const std::int64_t deadline_ns = monotonicNowNs() + timeout_ns;
  bool all = true;
  for (Topic topic : kFlightTopics) {
    const dds_entity_t w = writer(topic);
    if (w <= 0) continue;
    const std::int64_t left_ns = deadline_ns - monotonicNowNs();
    all =
        dds_wait_for_acks(w, static_cast<dds_duration_t>(left_ns > 0 ? left_ns : 0)) == DDS_RETCODE_OK && all;
  }
  return all;
}

std::uint32_t TelemetryWriter::poseDeadlineMisses() const {
  dds_offered_deadline_missed_status_t status{};
  if (dds_get_offered_deadline_missed_status(m_pose_writer, &status) != DDS_RETCODE_OK) return 0;
  return status.total_count;
}

std::uint64_t TelemetryWriter::samplePoolMisses() const {
  std::uint64_t misses = 0;
  for (const PooledSertype* s : m_sertypes) misses += pooledSertypeStats(s).pool_misses;
  return misses;
}

}  // namespace visnav::telemetry
