#include "visnav/telemetry/dds_topics.hpp"

#include <time.h>
#include <unistd.h>

#include <cmath>

namespace visnav::telemetry {
namespace {

constexpr const char* kTopicNames[kTopicCount] = {"visnav_pose", "visnav_far_range", "visnav_health",
                                                  "visnav_mode_command"};
constexpr const char* kTopicLabels[kTopicCount] = {"pose", "far_range", "health", "mode_command"};
const dds_topic_descriptor_t* const kDescriptors[kTopicCount] = {
    &visnav_PoseEstimate_desc, &visnav_FarRangeEstimate_desc, &visnav_Health_desc, &visnav_ModeCommand_desc};

template <typename GetStatus>
bool waitForMatch(GetStatus get_current_count, std::uint32_t count, std::int64_t timeout_ns) {
  const std::int64_t end_ns = monotonicNowNs() + timeout_ns;
  while (true) {  // bounded by timeout_ns
    std::uint32_t current = 0;
    if (get_current_count(current) && current >= count) return true;
    if (monotonicNowNs() >= end_ns) return false;
    dds_sleepfor(DDS_MSECS(10));
  }
}

}  // namespace

std::int64_t monotonicNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

const char* topicName(Topic topic) { return kTopicNames[static_cast<int>(topic)]; }
const dds_topic_descriptor_t* topicDescriptor(Topic topic) { return kDescriptors[static_cast<int>(topic)]; }
const char* topicLabel(Topic topic) { return kTopicLabels[static_cast<int>(topic)]; }

dds_qos_t* makeWriterQos(Topic topic, const TelemetryParams& params, std::int64_t cycle_period_ns) {
  dds_qos_t* qos = dds_create_qos();
  const auto max_blocking_ns = static_cast<dds_duration_t>(std::llround(params.max_blocking_ms * 1e6));
  // Reliable: a reliable ground reader gets every sample the writer still holds. Keep-last never waits for
  // acknowledgments (a newer sample replaces an unacknowledged one), so a dead reader cannot block a write;
  // max_blocking_time bounds the remaining case (resource limits) all the same.
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, max_blocking_ns);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, topic == Topic::kModeCommand ? params.command_depth : 1);
  dds_qset_durability(qos,
                      topic == Topic::kHealth ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  if ((topic == Topic::kPose || topic == Topic::kFarRange) && cycle_period_ns > 0) {
    dds_qset_deadline(qos, static_cast<dds_duration_t>(
                               std::llround(params.deadline_periods * static_cast<double>(cycle_period_ns))));
  }
  return qos;
}

dds_qos_t* makeReaderQos(Topic topic, int depth) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, depth);
  dds_qset_durability(qos,
                      topic == Topic::kHealth ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  return qos;
}

LoadError ddsFailure(const char* what, dds_return_t code) {
  return LoadError::failure(std::string(what) + ": " + dds_strretcode(code));
}

Participant::~Participant() { close(); }

void Participant::close() {
  if (m_participant > 0) dds_delete(m_participant);
  m_participant = 0;
  m_publisher = 0;
  m_subscriber = 0;
  for (dds_entity_t& t : m_topics) t = 0;
}

LoadError Participant::init(int domain_id, const char* partition) {
  close();
  if (const char* problem = partitionProblem(partition))
    return LoadError::failure(std::string("DDS partition '") + partition + "' " + problem);
  m_participant = dds_create_participant(static_cast<dds_domainid_t>(domain_id), nullptr, nullptr);
  if (m_participant < 0) {
    const dds_return_t code = m_participant;
    m_participant = 0;
    return ddsFailure("creating the DDS participant (check CYCLONEDDS_URI)", code);
  }
  dds_qos_t* qos = dds_create_qos();
  dds_qset_partition1(qos, partition);
  m_publisher = dds_create_publisher(m_participant, qos, nullptr);
  m_subscriber = dds_create_subscriber(m_participant, qos, nullptr);
  dds_delete_qos(qos);
  if (m_publisher < 0) return ddsFailure("creating the DDS publisher", m_publisher);
  if (m_subscriber < 0) return ddsFailure("creating the DDS subscriber", m_subscriber);
  for (int i = 0; i < kTopicCount; ++i) {
    m_topics[i] = dds_create_topic(m_participant, kDescriptors[i], kTopicNames[i], nullptr, nullptr);
    if (m_topics[i] < 0) return ddsFailure(kTopicNames[i], m_topics[i]);
  }
  return LoadError::success();
}

bool waitForReaders(dds_entity_t writer, std::uint32_t count, std::int64_t timeout_ns) {
  return waitForMatch(
      [writer](std::uint32_t& current) {
        dds_publication_matched_status_t status{};
        if (dds_get_publication_matched_status(writer, &status) != DDS_RETCODE_OK) return false;
        current = status.current_count;
        return true;
      },
      count, timeout_ns);
}

bool waitForWriters(dds_entity_t reader, std::uint32_t count, std::int64_t timeout_ns) {
  return waitForMatch(
      [reader](std::uint32_t& current) {
        dds_subscription_matched_status_t status{};
        if (dds_get_subscription_matched_status(reader, &status) != DDS_RETCODE_OK) return false;
        current = status.current_count;
        return true;
      },
      count, timeout_ns);
}

bool waitForFile(const char* path, std::int64_t timeout_ns) {
  return waitForMatch(
      [path](std::uint32_t& current) {
        current = access(path, F_OK) == 0 ? 1U : 0U;
        return true;
      },
      1, timeout_ns);
}

}  // namespace visnav::telemetry
