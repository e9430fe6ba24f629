// Flight side, once per cycle: NavSolution -> PoseEstimate + FarRangeEstimate, HealthRecord -> Health.
// init() creates the writers on topics of a pooled sertype (pooled_sertype.hpp); publishNav()/publishHealth()
// fill samples the writer owns in place and write them: no allocation (the serialized samples come from pools
// sized at init), no wait on any reader (keep-last reliable writers, bounded max_blocking_time).
// A failed write is counted and reported, never retried inside the cycle.
// DDS-free header: the writers and samples live in an implementation object allocated once, in init()
// (test-only access to the DDS writers: include-dds/visnav/telemetry/telemetry_writer_dds.hpp).
#pragma once

#include <cstdint>
#include <memory>

#include "visnav/navigation/nav_solution.hpp"
#include "visnav/telemetry/participant.hpp"
#include "visnav/telemetry/topics.hpp"

namespace visnav::telemetry {

class PooledSertype;  // pooled_sertype.hpp
struct DdsAccess;     // telemetry_writer_dds.hpp

struct WriterCounters {
  std::uint64_t samples_written = 0;
  std::uint64_t write_failures = 0;  ///< dds_write returned an error (timeout included)
  std::uint64_t write_timeouts = 0;  ///< of which DDS_RETCODE_TIMEOUT (max_blocking_time reached)
  std::int32_t last_error = 0;       ///< DDS return code of the last failed write (0: DDS_RETCODE_OK)
};

class TelemetryWriter {
 public:
  TelemetryWriter();
  ~TelemetryWriter();
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  /// `cycle_period_ns` sets the pose / far-range deadline (deadline_periods of it); <= 0: no deadline. Topic
  /// names follow the participant's naming.
  LoadError init(const Participant& participant, const TelemetryParams& params, std::int64_t cycle_period_ns);

  /// Writes PoseEstimate and FarRangeEstimate for this frame. False when a write failed (counted).
  bool publishNav(const nav::NavSolution& nav);
  /// Writes Health. False when the write failed (counted).
  bool publishHealth(const nav::HealthRecord& health);

  const WriterCounters& counters() const { return m_counters; }

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
  const PooledSertype* sertype(Topic topic) const;
  /// Samples that found their topic's pool empty and took a heap block, over the three topics.
  std::uint64_t samplePoolMisses() const;

 private:
  friend struct DdsAccess;
  struct Impl;  // telemetry_writer.cpp: the DDS writers, pools and the one sample per topic

  bool write(EntityHandle writer, const void* sample);

  std::unique_ptr<Impl> m_impl;  ///< allocated once, by the first init()
  WriterCounters m_counters;
};

}  // namespace visnav::telemetry
