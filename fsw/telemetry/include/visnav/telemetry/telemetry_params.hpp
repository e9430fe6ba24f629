// Parameters of the DDS telemetry (the [telemetry] table of a config; reference in config/PARAMETERS.md).
// Header-only and DDS-free so config tools can load and document it without linking Cyclone DDS.
// The partition and the naming are text, which the numeric visit() table cannot carry: applyTelemetryConfig()
// reads them next to the table, and telemetryParametersMarkdown() documents them in the same format.
#pragma once

#include <array>
#include <cstddef>
#include <cstring>
#include <string>

#include "visnav/core/param_visitor.hpp"
#include "visnav/io/config_io.hpp"
#include "visnav/io/param_docs.hpp"

namespace visnav::telemetry {

constexpr std::size_t kPartitionCapacity = 64;  ///< bytes, including the terminating NUL
constexpr const char* kDefaultPartition = "visnav";

/// Topic and type names on the wire ([telemetry] naming; fsw/telemetry/README.md, "ROS 2").
enum class TopicNaming : int {
  kVisnav = 0,  ///< "visnav": topics visnav_pose..., types visnav::PoseEstimate..., in the partition
  kRos2 =
      1,  ///< "ros2": topics rt/visnav_pose..., types visnav_msgs::msg::dds_::PoseEstimate_..., no partition
};
/// "visnav" or "ros2".
inline const char* namingName(TopicNaming naming) { return naming == TopicNaming::kRos2 ? "ros2" : "visnav"; }

struct TelemetryParams {
  bool enabled = true;
  int domain_id = 0;
  std::array<char, kPartitionCapacity> partition{'v', 'i', 's', 'n', 'a', 'v', '\0'};  ///< kDefaultPartition
  double deadline_periods = 1.5;
  double max_blocking_ms = 2.0;
  int command_depth = 8;
  int history_depth = 8;
  int sample_pool_blocks = 12;
  TopicNaming naming = TopicNaming::kVisnav;

  template <typename Visitor>
  void visit(Visitor& v) {
    v.boolean({"telemetry", "enabled", "-", 0, 1, "publish DDS telemetry and accept ground commands"},
              enabled);
    v.integer(
        {"telemetry", "domain_id", "-", 0, 232,
         "DDS domain of every telemetry entity (ground tools must use the same; 232 is the UDP port limit)"},
        domain_id);
    v.real(
        {"telemetry", "deadline_periods", "periods", 1.0, 10.0,
         "deadline QoS of the pose and far-range writers in cycle periods: one period plus a jitter margin, "
         "so a missing sample (two periods) is always flagged and release jitter never is"},
        deadline_periods);
    v.real({"telemetry", "max_blocking_ms", "ms", 0.0, 50.0,
            "max_blocking_time of the reliable writers: the longest a write may wait for a slow reader"},
           max_blocking_ms);
    v.integer({"telemetry", "command_depth", "count", 1, 64,
               "keep-last depth of the ModeCommand reader = most commands taken in one cycle"},
              command_depth);
    v.integer(
        {"telemetry", "history_depth", "samples", 1, 64,
         "keep-last depth of the pose, far-range and health writers: the samples a reliable reader can still "
         "have resent; the publisher thread writes a backlog back to back, and with 1 a reader that missed "
         "one sample of a burst lost it for good (keep-last never waits for a reader, whatever the depth)"},
        history_depth);
    v.integer(
        {"telemetry", "sample_pool_blocks", "count", 2, 1024,
         "serialized samples each flight writer holds without allocating (writer history, transmit "
         "queue, retransmissions); beyond it a sample takes a heap block and is counted as a pool miss"},
        sample_pool_blocks);
  }

  const char* crossCheck() const {
    // The writer history holds history_depth serialized samples, the write in progress one more.
    if (sample_pool_blocks < history_depth + 1)
      return "[telemetry] sample_pool_blocks must be at least history_depth + 1 (the writer history and the "
             "sample being written come from the pool)";
    return nullptr;
  }

  const char* partitionName() const { return partition.data(); }
};

/// Nullptr when `name` is a usable partition: 1..63 characters of [A-Za-z0-9_.-] (no DDS wildcards).
inline const char* partitionProblem(const char* name) {
  const std::size_t length = std::strlen(name);
  if (length == 0) return "must not be empty";
  if (length >= kPartitionCapacity) return "is longer than 63 characters";
  for (std::size_t i = 0; i < length; ++i) {
    const char c = name[i];
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '.';
    if (!ok) return "may hold only letters, digits, '_', '-' and '.'";
  }
  return nullptr;
}

/// Sets the partition; false (params unchanged) when the name is unusable.
inline bool setPartition(TelemetryParams& params, const char* name) {
  if (partitionProblem(name) != nullptr) return false;
  params.partition.fill('\0');
  std::memcpy(params.partition.data(), name, std::strlen(name));
  return true;
}

/// Sets the naming from its config spelling; false (params unchanged) for anything but "visnav" and "ros2".
inline bool setNaming(TelemetryParams& params, const char* name) {
  if (std::strcmp(name, "visnav") == 0) {
    params.naming = TopicNaming::kVisnav;
  } else if (std::strcmp(name, "ros2") == 0) {
    params.naming = TopicNaming::kRos2;
  } else {
    return false;
  }
  return true;
}

/// Loads [telemetry] (the table, the partition and the naming) from an open config. Init-time only.
inline LoadError applyTelemetryConfig(io::ConfigFile& config, TelemetryParams& params) {
  TelemetryParams loaded = params;
  if (LoadError e = config.apply(loaded); !e.ok) return e;
  std::string partition;
  bool present = false;  // `partition = ""` is present and wrong, not absent
  if (LoadError e = config.stringValue("telemetry", "partition", partition, present); !e.ok) return e;
  if (present && !setPartition(loaded, partition.c_str()))
    return LoadError::failure("[telemetry] partition '" + partition + "' " +
                              partitionProblem(partition.c_str()));
  const bool partition_set = present;
  std::string naming;
  if (LoadError e = config.stringValue("telemetry", "naming", naming, present); !e.ok) return e;
  if (present && !setNaming(loaded, naming.c_str()))
    return LoadError::failure("[telemetry] naming '" + naming + "' must be \"visnav\" or \"ros2\"");
  // ROS 2 nodes (rmw_cyclonedds) read the default partition only: a partition would hide the topics again.
  if (loaded.naming == TopicNaming::kRos2 && partition_set)
    return LoadError::failure(
        "[telemetry] partition cannot be used with naming = \"ros2\" (ROS 2 reads the default partition; "
        "separate vehicles or runs by domain_id)");
  params = loaded;
  return LoadError::success();
}

/// Markdown reference of [telemetry]: the visit() table plus the partition and naming rows.
inline std::string telemetryParametersMarkdown() {
  return io::parameterTableMarkdown(TelemetryParams{}) + "| `[telemetry] partition` | string | \"" +
         kDefaultPartition +
         "\" | 1 .. 63 chars of A-Z a-z 0-9 _ - . | - | DDS partition of every telemetry topic: separates "
         "several vehicles or test runs in one domain (not with naming = \"ros2\") |\n"
         "| `[telemetry] naming` | string | \"visnav\" | \"visnav\" or \"ros2\" | - | topic and type names: "
         "visnav_pose / visnav::PoseEstimate in the partition, or ROS 2's rt/visnav_pose / "
         "visnav_msgs::msg::dds_::PoseEstimate_ in the default partition, so a ROS 2 node can subscribe "
         "(fsw/telemetry/README.md) |\n";
}

}  // namespace visnav::telemetry
