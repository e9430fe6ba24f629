// Flight side, once per cycle: NavSolution -> PoseEstimate + FarRangeEstimate, HealthRecord -> Health.
// init() creates the writers on topics of a pooled sertype (pooled_sertype.hpp); publishNav()/publishHealth()
// fill samples the writer owns in place and write them: no allocation (the serialized samples come from pools
// sized at init), no wait on any reader (keep-last reliable writers, bounded max_blocking_time).
// A failed write is counted and reported, never retried inside the cycle.
#pragma once

#include <cstdint>

#include "visnav/navigation/nav_solution.hpp"
#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/pooled_sertype.hpp"

namespace visnav::telemetry {

struct WriterCounters {
  std::uint64_t samples_written = 0;
  std::uint64_t write_failures = 0;  ///< dds_write returned an error (timeout included)
  std::uint64_t write_timeouts = 0;  ///< of which DDS_RETCODE_TIMEOUT (max_blocking_time reached)
  dds_return_t last_error = DDS_RETCODE_OK;
};

class TelemetryWriter {
 public:
  /// `cycle_period_ns` sets the pose / far-range deadline (deadline_periods of it); <= 0: no deadline.
  LoadError init(const Participant& participant, const TelemetryParams& params, std::int64_t cycle_period_ns);

  /// Writes PoseEstimate and FarRangeEstimate for this frame. False when a write failed (counted).
  bool publishNav(const nav::NavSolution& nav);
  /// Writes Health. False when the write failed (counted).
  bool publishHealth(const nav::HealthRecord& health);

  const WriterCounters& counters() const { return m_counters; }
  dds_entity_t writer(Topic topic) const;

  /// Init time: waits (bounded by `timeout_ns` over all topics) until every flight topic's writer has at
  /// least `count` matched readers. False on timeout, with `missing` the first topic short of readers.
  bool waitForReaders(std::uint32_t count, std::int64_t timeout_ns, Topic& missing) const;
  /// Shutdown: waits (bounded by `timeout_ns` over all topics) until the matched reliable readers have
  /// acknowledged every sample written, so the last samples arrive before the participant goes. True when
  /// all did (or nothing was written yet: no writer).
  bool waitForAcks(std::int64_t timeout_ns) const;
  /// Offered-deadline misses of the pose writer so far (a cycle that published nothing in time).
  std::uint32_t poseDeadlineMisses() const;
  /// Serialized-sample pool of one flight topic, for pooledSertypeStats() (nullptr: kModeCommand, before
  /// init).
  const PooledSertype* sertype(Topic topic) const {
    return static_cast<int>(topic) < kFlightTopicCount ? m_sertypes[static_cast<int>(topic)] : nullptr;
  }
  /// Samples that found their topic's pool empty and took a heap block, over the three topics.
  std::uint64_t samplePoolMisses() const;

 private:
  bool write(dds_entity_t writer, const void* sample);

  dds_entity_t m_pose_writer = 0;
  dds_entity_t m_far_writer = 0;
  dds_entity_t m_health_writer = 0;
  const PooledSertype* m_sertypes[kFlightTopicCount] = {};  // kFlightTopics order
  std::uint64_t m_nav_samples = 0;
  std::uint64_t m_health_samples = 0;
  WriterCounters m_counters;
  // One sample per topic for the whole run, overwritten in place every cycle.
  visnav_PoseEstimate m_pose{};
  visnav_FarRangeEstimate m_far{};
  visnav_Health m_health{};
};

}  // namespace visnav::telemetry
