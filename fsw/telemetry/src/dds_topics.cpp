#include "visnav/telemetry/dds_topics.hpp"

#include <time.h>
#include <unistd.h>

#include <cmath>
#include <type_traits>

namespace visnav::telemetry {

static_assert(std::is_same_v<EntityHandle, dds_entity_t>,
              "participant.hpp's opaque handle is a dds_entity_t");

namespace {

constexpr int kNamingCount = 2;  // TopicNaming values
constexpr const char* kTopicNames[kNamingCount][kTopicCount] = {
    {"visnav_pose", "visnav_far_range", "visnav_health", "visnav_mode_command"},
    {"rt/visnav_pose", "rt/visnav_far_range", "rt/visnav_health", "rt/visnav_mode_command"}};
// ROS 2's IDL mapping of a .msg (rosidl, rmw_cyclonedds): <package>::msg::dds_::<Message>_ (idl/ros2/).
constexpr const char* kRos2TypeNames[kTopicCount] = {
    "visnav_msgs::msg::dds_::PoseEstimate_", "visnav_msgs::msg::dds_::FarRangeEstimate_",
    "visnav_msgs::msg::dds_::Health_", "visnav_msgs::msg::dds_::ModeCommand_"};
constexpr const char* kTopicLabels[kTopicCount] = {"pose", "far_range", "health", "mode_command"};
const dds_topic_descriptor_t* const kDescriptors[kTopicCount] = {
    &visnav_PoseEstimate_desc, &visnav_FarRangeEstimate_desc, &visnav_Health_desc, &visnav_ModeCommand_desc};

int namingIndex(TopicNaming naming) { return naming == TopicNaming::kRos2 ? 1 : 0; }

/// idlc's descriptor under the ROS 2 type name: same size, alignment, ops (the CDR is the same), no XTypes
/// type information (its type objects name the visnav:: types).
dds_topic_descriptor_t ros2Descriptor(const dds_topic_descriptor_t& d, const char* type_name) {
  return dds_topic_descriptor_t{
      d.m_size,     d.m_align,    d.m_flagset & ~static_cast<std::uint32_t>(DDS_TOPIC_XTYPES_METADATA),
      d.m_nkeys,    type_name,    d.m_keys,
      d.m_nops,     d.m_ops,      d.m_meta,
      {nullptr, 0}, {nullptr, 0}, d.restrict_data_representation};
}

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

const char* topicName(Topic topic, TopicNaming naming) {
  return kTopicNames[namingIndex(naming)][static_cast<int>(topic)];
}

const char* typeName(Topic topic, TopicNaming naming) {
  return naming == TopicNaming::kRos2 ? kRos2TypeNames[static_cast<int>(topic)]
                                      : kDescriptors[static_cast<int>(topic)]->m_typename;
}

const dds_topic_descriptor_t* topicDescriptor(Topic topic, TopicNaming naming) {
  // Made on first use (thread-safe static initialisation), in static storage: no allocation.
  static const dds_topic_descriptor_t kRos2[kTopicCount] = {
      ros2Descriptor(visnav_PoseEstimate_desc, kRos2TypeNames[0]),
      ros2Descriptor(visnav_FarRangeEstimate_desc, kRos2TypeNames[1]),
      ros2Descriptor(visnav_Health_desc, kRos2TypeNames[2]),
      ros2Descriptor(visnav_ModeCommand_desc, kRos2TypeNames[3])};
  return naming == TopicNaming::kRos2 ? &kRos2[static_cast<int>(topic)]
                                      : kDescriptors[static_cast<int>(topic)];
}
const char* topicLabel(Topic topic) { return kTopicLabels[static_cast<int>(topic)]; }

dds_qos_t* makeWriterQos(Topic topic, const TelemetryParams& params, std::int64_t cycle_period_ns) {
  dds_qos_t* qos = dds_create_qos();
  const auto max_blocking_ns = static_cast<dds_duration_t>(std::llround(params.max_blocking_ms * 1e6));
  // Reliable: a reliable ground reader gets every sample the writer still holds (the last history_depth).
  // Keep-last never waits for acknowledgments (the oldest unacknowledged sample is replaced), so a dead
  // reader cannot block a write; max_blocking_time bounds the remaining case (resource limits) all the same.
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, max_blocking_ns);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST,
                   topic == Topic::kModeCommand ? params.command_depth : params.history_depth);
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

LoadError Participant::init(const TelemetryParams& params) {
  return create(params.domain_id, params.partitionName(), params.naming);
}

LoadError Participant::init(int domain_id, const char* partition) {
  return create(domain_id, partition, TopicNaming::kVisnav);
}

LoadError Participant::create(int domain_id, const char* partition, TopicNaming naming) {
  close();
  m_naming = naming;
  if (naming == TopicNaming::kRos2) {
    partition = nullptr;  // ROS 2 reads the default partition
  } else if (const char* problem = partitionProblem(partition)) {
    return LoadError::failure(std::string("DDS partition '") + partition + "' " + problem);
  }
  m_participant = dds_create_participant(static_cast<dds_domainid_t>(domain_id), nullptr, nullptr);
  if (m_participant < 0) {
    const dds_return_t code = m_participant;
    m_participant = 0;
    return ddsFailure("creating the DDS participant (check CYCLONEDDS_URI)", code);
  }
  dds_qos_t* qos = dds_create_qos();
  if (partition != nullptr) dds_qset_partition1(qos, partition);
  m_publisher = dds_create_publisher(m_participant, qos, nullptr);
  m_subscriber = dds_create_subscriber(m_participant, qos, nullptr);
  dds_delete_qos(qos);
  if (m_publisher < 0) return ddsFailure("creating the DDS publisher", m_publisher);
  if (m_subscriber < 0) return ddsFailure("creating the DDS subscriber", m_subscriber);
  for (int i = 0; i < kTopicCount; ++i) {
    const auto topic = static_cast<Topic>(i);
    m_topics[i] = dds_create_topic(m_participant, topicDescriptor(topic, naming), topicName(topic, naming),
                                   nullptr, nullptr);
    if (m_topics[i] < 0) return ddsFailure(topicName(topic, naming), m_topics[i]);
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
