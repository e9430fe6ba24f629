#include "visnav/telemetry/telemetry_writer.hpp"

#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/pooled_sertype.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"

namespace visnav::telemetry {

struct TelemetryWriter::Impl {
  dds_entity_t pose_writer = 0;
  dds_entity_t far_writer = 0;
  dds_entity_t health_writer = 0;
  const PooledSertype* sertypes[kFlightTopicCount] = {};  // kFlightTopics order
  std::uint64_t nav_samples = 0;
  std::uint64_t health_samples = 0;
  // One sample per topic for the whole run, overwritten in place every cycle.
  visnav_PoseEstimate pose{};
  visnav_FarRangeEstimate far{};
  visnav_Health health{};

  dds_entity_t writer(Topic topic) const {
    switch (topic) {
      case Topic::kPose: return pose_writer;
      case Topic::kFarRange: return far_writer;
      case Topic::kHealth: return health_writer;
      case Topic::kModeCommand: break;
    }
    return 0;
  }
};

namespace {

dds_entity_t createWriter(const Participant& participant, Topic topic, const TelemetryParams& params,
                          std::int64_t cycle_period_ns, const PooledSertype** sertype) {
  const dds_entity_t pooled_topic =
      createPooledTopic(participant.handle(), topicName(topic, participant.naming()),
                        topicDescriptor(topic, participant.naming()),
                        static_cast<std::uint32_t>(params.sample_pool_blocks), sertype);
  if (pooled_topic < 0) return pooled_topic;
  dds_qos_t* qos = makeWriterQos(topic, params, cycle_period_ns);
  const dds_entity_t writer = dds_create_writer(participant.publisher(), pooled_topic, qos, nullptr);
  dds_delete_qos(qos);
  return writer;
}

}  // namespace

TelemetryWriter::TelemetryWriter() = default;
TelemetryWriter::~TelemetryWriter() = default;

LoadError TelemetryWriter::init(const Participant& participant, const TelemetryParams& params,
                                std::int64_t cycle_period_ns) {
  if (!participant.isOpen()) return LoadError::failure("telemetry writer: participant not initialised");
  if (!m_impl) m_impl = std::make_unique<Impl>();  // the one allocation: init time
  Impl& d = *m_impl;
  d = Impl{};
  d.pose_writer = createWriter(participant, Topic::kPose, params, cycle_period_ns, &d.sertypes[0]);
  if (d.pose_writer < 0) return ddsFailure("creating the pose writer", d.pose_writer);
  d.far_writer = createWriter(participant, Topic::kFarRange, params, cycle_period_ns, &d.sertypes[1]);
  if (d.far_writer < 0) return ddsFailure("creating the far-range writer", d.far_writer);
  d.health_writer = createWriter(participant, Topic::kHealth, params, cycle_period_ns, &d.sertypes[2]);
  if (d.health_writer < 0) return ddsFailure("creating the health writer", d.health_writer);
  m_counters = WriterCounters{};
  return LoadError::success();
}

bool TelemetryWriter::write(EntityHandle writer, const void* sample) {
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
  if (!m_impl || m_impl->pose_writer <= 0) return false;
  Impl& d = *m_impl;
  ++d.nav_samples;
  const std::int64_t now_ns = monotonicNowNs();
  fillPoseEstimate(nav, d.nav_samples, now_ns, d.pose);
  fillFarRangeEstimate(nav, d.nav_samples, now_ns, d.far);
  const bool pose_ok = write(d.pose_writer, &d.pose);
  const bool far_ok = write(d.far_writer, &d.far);
  return pose_ok && far_ok;
}

bool TelemetryWriter::publishHealth(const nav::HealthRecord& health) {
  if (!m_impl || m_impl->health_writer <= 0) return false;
  Impl& d = *m_impl;
  ++d.health_samples;
  fillHealth(health, d.health_samples, monotonicNowNs(), d.health);
  return write(d.health_writer, &d.health);
}

dds_entity_t DdsAccess::writer(const TelemetryWriter& writer, Topic topic) {
  return writer.m_impl ? writer.m_impl->writer(topic) : 0;
}

bool TelemetryWriter::waitForReaders(std::uint32_t count, std::int64_t timeout_ns, Topic& missing) const {
  const std::int64_t deadline_ns = monotonicNowNs() + timeout_ns;
  for (Topic topic : kFlightTopics) {
    const std::int64_t left_ns = deadline_ns - monotonicNowNs();
    if (!telemetry::waitForReaders(ddsWriter(*this, topic), count, left_ns > 0 ? left_ns : 0)) {
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
    const dds_entity_t w = ddsWriter(*this, topic);
    if (w <= 0) continue;
    const std::int64_t left_ns = deadline_ns - monotonicNowNs();
    all =
        dds_wait_for_acks(w, static_cast<dds_duration_t>(left_ns > 0 ? left_ns : 0)) == DDS_RETCODE_OK && all;
  }
  return all;
}

std::uint32_t TelemetryWriter::poseDeadlineMisses() const {
  dds_offered_deadline_missed_status_t status{};
  if (dds_get_offered_deadline_missed_status(ddsWriter(*this, Topic::kPose), &status) != DDS_RETCODE_OK)
    return 0;
  return status.total_count;
}

const PooledSertype* TelemetryWriter::sertype(Topic topic) const {
  if (!m_impl || static_cast<int>(topic) >= kFlightTopicCount) return nullptr;
  return m_impl->sertypes[static_cast<int>(topic)];
}

std::uint64_t TelemetryWriter::samplePoolMisses() const {
  if (!m_impl) return 0;
  std::uint64_t misses = 0;
  for (const PooledSertype* s : m_impl->sertypes) misses += pooledSertypeStats(s).pool_misses;
  return misses;
}

}  // namespace visnav::telemetry
