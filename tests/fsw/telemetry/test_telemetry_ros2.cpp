// [telemetry] naming = "ros2" (idl/README.md, "ROS 2"): a reader written only from ROS 2's names (topic
// rt/visnav_pose, type visnav_msgs::msg::dds_::PoseEstimate_, default partition, ROS 2's default QoS), as
// rmw_cyclonedds would create it, receives the flight writer's samples on real Cyclone DDS (loopback, a
// domain of this test process's own); a ModeCommand written under the ROS 2 names reaches the flight
// CommandReader; the shipped .msg files match idl/visnav.idl field by field; the config option is validated.
// GCC 12 at -O1 with ASan (debug preset) warns maybe-uninitialized inside libstdc++'s <regex> (the
// std::function of a moved _NFA state: a false positive in the library, not in this test code);
// set before any include, because the warning is placed at the library's lines.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "telemetry_test_data.hpp"
#include "visnav/io/config_io.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace visnav::telemetry {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

/// idlc's descriptor under another type name, built here from ROS 2's naming rule (not from the code under
/// test), without XTypes information, as a ROS 2 type support offers it.
dds_topic_descriptor_t ros2Type(const dds_topic_descriptor_t& d, const char* type_name) {
  return dds_topic_descriptor_t{
      d.m_size,     d.m_align,    d.m_flagset & ~static_cast<std::uint32_t>(DDS_TOPIC_XTYPES_METADATA),
      d.m_nkeys,    type_name,    d.m_keys,
      d.m_nops,     d.m_ops,      d.m_meta,
      {nullptr, 0}, {nullptr, 0}, d.restrict_data_representation};
}

/// A plain Cyclone participant standing in for a ROS 2 node: default partition, ROS 2 names only.
class Ros2Node {
 public:
  explicit Ros2Node(int domain_id) { m_participant = dds_create_participant(domain_id, nullptr, nullptr); }
  ~Ros2Node() {
    if (m_participant > 0) dds_delete(m_participant);
  }
  Ros2Node(const Ros2Node&) = delete;
  Ros2Node& operator=(const Ros2Node&) = delete;
  bool ok() const { return m_participant > 0; }

  /// rclcpp's default subscription QoS: reliable, volatile, keep-last 10 (Health: transient-local).
  dds_entity_t subscribe(const dds_topic_descriptor_t* type, const char* topic_name, bool transient_local) {
    const dds_entity_t topic = dds_create_topic(m_participant, type, topic_name, nullptr, nullptr);
    if (topic < 0) return topic;
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
    dds_qset_durability(qos, transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
    const dds_entity_t reader = dds_create_reader(m_participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    return reader;
  }
  /// rclcpp's default publisher QoS: reliable, volatile, keep-last 10.
  dds_entity_t advertise(const dds_topic_descriptor_t* type, const char* topic_name) {
    const dds_entity_t topic = dds_create_topic(m_participant, type, topic_name, nullptr, nullptr);
    if (topic < 0) return topic;
    dds_qos_t* qos = dds_create_qos();
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
    dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, 10);
    const dds_entity_t writer = dds_create_writer(m_participant, topic, qos, nullptr);
    dds_delete_qos(qos);
    return writer;
  }

 private:
  dds_entity_t m_participant = 0;
};

/// Takes one data sample from `reader` within `timeout_ns` (polling every 10 ms). False when none came.
template <typename Sample>
bool takeOne(dds_entity_t reader, Sample& out, std::int64_t timeout_ns) {
  const std::int64_t end = monotonicNowNs() + timeout_ns;
  while (monotonicNowNs() < end) {
    void* buffers[1] = {&out};
    dds_sample_info_t info{};
    if (dds_take(reader, buffers, &info, 1, 1) == 1 && info.valid_data) return true;
    dds_sleepfor(DDS_MSECS(10));
  }
  return false;
}

TelemetryParams ros2Params() {
  TelemetryParams params;
  params.domain_id = test::isolatedDomainId();
  params.naming = TopicNaming::kRos2;
  return params;
}

TEST(TelemetryRos2, TheNamesAreRos2s) {
  EXPECT_STREQ(topicName(Topic::kPose, TopicNaming::kRos2), "rt/visnav_pose");
  EXPECT_STREQ(topicName(Topic::kModeCommand, TopicNaming::kRos2), "rt/visnav_mode_command");
  EXPECT_STREQ(typeName(Topic::kHealth, TopicNaming::kRos2), "visnav_msgs::msg::dds_::Health_");
  EXPECT_STREQ(topicDescriptor(Topic::kFarRange, TopicNaming::kRos2)->m_typename,
               "visnav_msgs::msg::dds_::FarRangeEstimate_");
  // The default is unchanged.
  EXPECT_STREQ(topicName(Topic::kPose), "visnav_pose");
  EXPECT_STREQ(typeName(Topic::kPose), "visnav::PoseEstimate");
  EXPECT_EQ(topicDescriptor(Topic::kPose), &visnav_PoseEstimate_desc);
}

TEST(TelemetryRos2, AReaderWithRos2NamesReceivesTheFlightSamples) {
  const TelemetryParams params = ros2Params();
  Participant flight;
  ASSERT_TRUE(flight.init(params).ok);
  TelemetryWriter writer;
  ASSERT_TRUE(writer.init(flight, params, 200'000'000).ok);

  Ros2Node node(params.domain_id);
  ASSERT_TRUE(node.ok());
  const dds_topic_descriptor_t pose_type =
      ros2Type(visnav_PoseEstimate_desc, "visnav_msgs::msg::dds_::PoseEstimate_");
  const dds_topic_descriptor_t health_type = ros2Type(visnav_Health_desc, "visnav_msgs::msg::dds_::Health_");
  const dds_entity_t pose_reader = node.subscribe(&pose_type, "rt/visnav_pose", false);
  const dds_entity_t health_reader = node.subscribe(&health_type, "rt/visnav_health", true);
  ASSERT_GT(pose_reader, 0);
  ASSERT_GT(health_reader, 0);
  ASSERT_TRUE(waitForReaders(ddsWriter(writer, Topic::kPose), 1, 10 * kSecond));
  ASSERT_TRUE(waitForReaders(ddsWriter(writer, Topic::kHealth), 1, 10 * kSecond));
  ASSERT_TRUE(waitForWriters(pose_reader, 1, 10 * kSecond));
  ASSERT_TRUE(waitForWriters(health_reader, 1, 10 * kSecond));

  const nav::NavSolution nav = test::makeNavSolution(3);
  const nav::HealthRecord health = test::makeHealthRecord(3);
  ASSERT_TRUE(writer.publishNav(nav));
  ASSERT_TRUE(writer.publishHealth(health));
  visnav_PoseEstimate pose{};
  ASSERT_TRUE(takeOne(pose_reader, pose, 5 * kSecond)) << "no PoseEstimate under the ROS 2 names";
  EXPECT_EQ(pose.sample_number, 1U);
  EXPECT_EQ(pose.frame_number, nav.frame_number);
  EXPECT_EQ(pose.pose_valid, nav.pose_valid);
  EXPECT_EQ(pose.position_m[0], nav.pose.t_c_m.x());  // bit-exact: the same bytes
  EXPECT_EQ(pose.position_m[2], nav.pose.t_c_m.z());
  EXPECT_EQ(pose.covariance[7], nav.covariance(1, 1));
  visnav_Health received{};
  ASSERT_TRUE(takeOne(health_reader, received, 5 * kSecond)) << "no Health under the ROS 2 names";
  EXPECT_EQ(received.frames_processed, health.frames_processed);
  EXPECT_EQ(received.fault_counts[5], health.fault_counts[5]);
  EXPECT_STREQ(received.last_transition.reason, health.last_transition.reason.data());
  EXPECT_EQ(writer.counters().write_failures, 0U);
}

TEST(TelemetryRos2, ACommandWrittenUnderRos2NamesIsTaken) {
  const TelemetryParams params = ros2Params();
  Participant flight;
  ASSERT_TRUE(flight.init(params).ok);
  CommandReader commands;
  ASSERT_TRUE(commands.init(flight, params).ok);
  Ros2Node node(params.domain_id);
  const dds_topic_descriptor_t type =
      ros2Type(visnav_ModeCommand_desc, "visnav_msgs::msg::dds_::ModeCommand_");
  const dds_entity_t writer = node.advertise(&type, "rt/visnav_mode_command");
  ASSERT_GT(writer, 0);
  ASSERT_TRUE(waitForReaders(writer, 1, 10 * kSecond));
  ASSERT_TRUE(waitForWriters(ddsReader(commands), 1, 10 * kSecond));
  visnav_ModeCommand command{};
  command.command_id = 42;
  command.kind = visnav_COMMAND_STANDBY;
  ASSERT_EQ(dds_write(writer, &command), DDS_RETCODE_OK);
  ReceivedCommand received[4];
  int n = 0;
  for (int i = 0; i < 500 && n == 0; ++i) {  // bounded: 5 s
    n = commands.poll(received, 4);
    if (n == 0) dds_sleepfor(DDS_MSECS(10));
  }
  ASSERT_EQ(n, 1);
  EXPECT_TRUE(received[0].valid);
  EXPECT_EQ(received[0].command_id, 42U);
  EXPECT_EQ(received[0].kind, nav::ModeCommandKind::kStandby);
}

// ---- the .msg files against the IDL ----

struct Field {
  std::string type;  // ROS 2 spelling
  std::string name;
  bool operator==(const Field& o) const { return type == o.type && name == o.name; }
};

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The structs of idl/visnav.idl as ROS 2 fields: IDL types mapped by ROS 2's rules (double -> float64,
/// boolean -> bool, string<N> -> string<=N, T x[N] -> T[N] x), array bounds resolved from the constants.
std::map<std::string, std::vector<Field>> idlStructs(const std::string& idl) {
  std::map<std::string, std::string> constants;
  const std::regex constant(R"(const\s+\w+\s+(\w+)\s*=\s*(\d+)\s*;)");
  for (std::sregex_iterator it(idl.begin(), idl.end(), constant), end; it != end; ++it)
    constants[(*it)[1]] = (*it)[2];
  const std::map<std::string, std::string> types = {{"double", "float64"}, {"boolean", "bool"}};
  std::map<std::string, std::vector<Field>> out;
  const std::regex body(R"(struct\s+(\w+)\s*\{([^}]*)\})");
  const std::regex member(R"(^\s*([\w<>]+)\s+(\w+)(\[(\w+)\])?\s*;)");
  for (std::sregex_iterator it(idl.begin(), idl.end(), body), end; it != end; ++it) {
    std::istringstream lines((*it)[2].str());
    std::vector<Field>& fields = out[(*it)[1]];
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, member)) continue;
      std::string type = m[1];
      if (types.count(type) != 0U) type = types.at(type);
      if (type.rfind("string<", 0) == 0) type = "string<=" + type.substr(7, type.size() - 8);
      if (m[3].matched) {
        const std::string bound = m[4];
        type += "[" + (constants.count(bound) != 0U ? constants[bound] : bound) + "]";
      }
      fields.push_back({type, m[2]});
    }
  }
  return out;
}

/// The fields of a .msg (constants and comments skipped).
std::vector<Field> msgFields(const std::string& text) {
  std::vector<Field> fields;
  std::istringstream lines(text);
  const std::regex field(R"(^\s*([\w<=\[\]]+)\s+(\w+)\s*(#.*)?$)");
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (std::regex_match(line, m, field)) fields.push_back({m[1], m[2]});
  }
  return fields;
}

TEST(TelemetryRos2, MsgFilesMatchTheIdlFieldByField) {
  const auto structs = idlStructs(readFile(std::string(VISNAV_SOURCE_DIR) + "/idl/visnav.idl"));
  ASSERT_EQ(structs.size(), 7U);
  for (const auto& [name, idl_fields] : structs) {
    const std::string path = std::string(VISNAV_SOURCE_DIR) + "/idl/ros2/visnav_msgs/msg/" + name + ".msg";
    const std::string text = readFile(path);
    ASSERT_FALSE(text.empty()) << path;
    const std::vector<Field> msg = msgFields(text);
    ASSERT_EQ(msg.size(), idl_fields.size()) << name;
    for (std::size_t i = 0; i < msg.size(); ++i) {
      EXPECT_EQ(msg[i].name, idl_fields[i].name) << name << " field " << i;
      EXPECT_EQ(msg[i].type, idl_fields[i].type) << name << "." << idl_fields[i].name;
    }
  }
}

// ---- the config option ----

LoadError loadTelemetry(const std::string& text, TelemetryParams& params) {
  const std::string path = ::testing::TempDir() + "/ros2_naming_" + std::to_string(getpid()) + ".toml";
  std::ofstream(path) << text;
  io::ConfigFile config;
  LoadError e = config.open(path);
  if (e.ok) e = applyTelemetryConfig(config, params);
  std::remove(path.c_str());
  return e;
}

TEST(TelemetryRos2, TheNamingOptionIsValidated) {
  TelemetryParams params;
  EXPECT_EQ(params.naming, TopicNaming::kVisnav);  // the default stays
  ASSERT_TRUE(loadTelemetry("[telemetry]\nnaming = \"ros2\"\n", params).ok);
  EXPECT_EQ(params.naming, TopicNaming::kRos2);
  ASSERT_TRUE(loadTelemetry("[telemetry]\nnaming = \"visnav\"\n", params).ok);
  EXPECT_EQ(params.naming, TopicNaming::kVisnav);
  LoadError e = loadTelemetry("[telemetry]\nnaming = \"ROS2\"\n", params);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("[telemetry] naming 'ROS2' must be \"visnav\" or \"ros2\""), std::string::npos)
      << e.message;
  e = loadTelemetry("[telemetry]\nnaming = 2\n", params);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("naming must be a string"), std::string::npos) << e.message;
  e = loadTelemetry("[telemetry]\nnaming = \"ros2\"\npartition = \"vehicle1\"\n", params);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("partition cannot be used with naming = \"ros2\""), std::string::npos)
      << e.message;
  EXPECT_EQ(params.naming, TopicNaming::kVisnav);  // unchanged on error
  EXPECT_NE(telemetryParametersMarkdown().find("| `[telemetry] naming` | string | \"visnav\" |"),
            std::string::npos);
}

}  // namespace
}  // namespace visnav::telemetry
