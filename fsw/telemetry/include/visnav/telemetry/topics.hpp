// The four telemetry topics by name, DDS-free: what flight code (fsw/app) and people see of them. Their
// types, QoS and the DDS calls are behind this library (include-dds/visnav/telemetry/dds_topics.hpp, for the
// ground tools and tests only). Topic table and QoS reasons: fsw/telemetry/README.md.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::telemetry {

enum class Topic : int { kPose = 0, kFarRange = 1, kHealth = 2, kModeCommand = 3 };
constexpr int kTopicCount = 4;
/// The topics the flight side writes (and the ground reads), in Topic order: the one list of them.
constexpr int kFlightTopicCount = 3;
constexpr std::array<Topic, kFlightTopicCount> kFlightTopics = {Topic::kPose, Topic::kFarRange,
                                                                Topic::kHealth};

/// DDS topic name: "visnav_pose", ... ([telemetry] naming = "visnav"), "rt/visnav_pose", ... ("ros2": the
/// ROS 2 topic /visnav_pose).
const char* topicName(Topic topic, TopicNaming naming = TopicNaming::kVisnav);
/// DDS type name: "visnav::PoseEstimate", ... ("visnav"), "visnav_msgs::msg::dds_::PoseEstimate_", ...
/// ("ros2").
const char* typeName(Topic topic, TopicNaming naming = TopicNaming::kVisnav);
/// Short name for people ("pose", "far_range", "health", "mode_command").
const char* topicLabel(Topic topic);

/// CLOCK_MONOTONIC now [ns]: the clock of publish_time_ns and of the ground tools' latency figures.
std::int64_t monotonicNowNs();

/// Waits (bounded, polling every 10 ms) until the file `path` exists. False on timeout. The writer side's
/// half of a start handshake: a writer sees a reader match before that reader has matched the writer, and a
/// reader drops what arrives from a writer it has not matched; a ground tool's `--ready-file` appears once
/// its readers have matched, so a publisher that waits for it loses nothing from its first sample on.
bool waitForFile(const char* path, std::int64_t timeout_ns);

}  // namespace visnav::telemetry
