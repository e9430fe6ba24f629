// Ground side (visnav-monitor, visnav-command, tests): reliable readers for PoseEstimate, FarRangeEstimate
// and Health (Health transient-local, so the current state arrives at once), a ModeCommand writer, and a
// waitset to sleep until something arrives. Same topics and QoS table as the flight side (dds_topics.hpp).
#pragma once

#include <array>
#include <cstdint>

#include "visnav/telemetry/dds_topics.hpp"

namespace visnav::telemetry {

constexpr int kMaxTakeBatch = 64;  ///< most samples one take*() returns

class GroundLink {
 public:
  GroundLink() = default;
  ~GroundLink();
  GroundLink(const GroundLink&) = delete;
  GroundLink& operator=(const GroundLink&) = delete;

  /// Domain and partition come from `params` (the same [telemetry] table the flight side reads);
  /// `reader_depth` is the keep-last depth of each reader (samples buffered between two takes).
  LoadError init(const TelemetryParams& params, int reader_depth);

  /// Sleeps until a sample is waiting on any reader or `timeout_ns` passed. False on timeout.
  bool waitForData(std::int64_t timeout_ns);

  /// Takes up to min(capacity, kMaxTakeBatch) samples, oldest first; returns the count (< 0: DDS error).
  /// Entries whose info.valid_data is false are state notifications without data.
  int takePose(visnav_PoseEstimate* out, dds_sample_info_t* infos, int capacity) {
    return take(Topic::kPose, out, infos, capacity);
  }
  int takeFarRange(visnav_FarRangeEstimate* out, dds_sample_info_t* infos, int capacity) {
    return take(Topic::kFarRange, out, infos, capacity);
  }
  int takeHealth(visnav_Health* out, dds_sample_info_t* infos, int capacity) {
    return take(Topic::kHealth, out, infos, capacity);
  }

  /// Writes one ModeCommand (reliable). Returns the dds_write code.
  dds_return_t sendCommand(std::uint32_t command_id, std::uint8_t kind);

  /// True once each flight-topic reader has matched at least one writer (from then on nothing a matched
  /// writer sends is dropped for being from an unknown writer).
  bool allReadersMatched() const;

  dds_entity_t reader(Topic topic) const { return m_readers[static_cast<int>(topic)]; }
  dds_entity_t commandWriter() const { return m_command_writer; }

 private:
  template <typename Sample>
  int take(Topic topic, Sample* out, dds_sample_info_t* infos, int capacity) {
    std::array<void*, kMaxTakeBatch> buffers{};
    const int n = capacity < kMaxTakeBatch ? capacity : kMaxTakeBatch;
    for (int i = 0; i < n; ++i) buffers[i] = &out[i];
    return takeInto(topic, buffers.data(), infos, n);
  }
  int takeInto(Topic topic, void** buffers, dds_sample_info_t* infos, int count);

  Participant m_participant;
  dds_entity_t m_readers[kTopicCount] = {};  ///< indexed by Topic; none for kModeCommand
  dds_entity_t m_command_writer = 0;
  dds_entity_t m_waitset = 0;
};

}  // namespace visnav::telemetry
