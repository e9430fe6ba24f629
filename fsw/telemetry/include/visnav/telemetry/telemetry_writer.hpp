// Flight side, once per cycle: NavSolution -> PoseEstimate + FarRangeEstimate, HealthRecord -> Health.
// init() creates the writers on topics of a pooled sertype (pooled_sertype.hpp) and starts one publisher
// thread. publishNav()/publishHealth() (the cycle's thread) fill each sample in place into a slot of a
// bounded single-producer/single-consumer ring sized at init (kQueueSlots) and return: no DDS call, no
// allocation, no lock (spsc_ring.hpp). The publisher thread takes the slots in order and calls dds_write,
// so whatever Cyclone does inside dds_write (it allocates on 0.2-1 % of writes to a remote reliable reader,
// fsw/telemetry/README.md) happens on that thread, not the cycle's. A full ring drops the newest sample
// (counted); a failed write is counted and reported by the next publish call of that topic, never retried.
// DDS-free header: the writers, the ring and the thread live in an implementation object allocated once, in
// init() (test-only access to the DDS writers: include-dds/visnav/telemetry/telemetry_writer_dds.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "visnav/navigation/nav_solution.hpp"
#include "visnav/telemetry/participant.hpp"
#include "visnav/telemetry/topics.hpp"

namespace visnav::telemetry {

class PooledSertype;  // pooled_sertype.hpp
struct DdsAccess;     // telemetry_writer_dds.hpp

/// A snapshot: the publisher thread updates the counts while the cycle runs. Every sample the cycle hands
/// over is queued or dropped; every queued one is, once the ring has drained, written or failed.
struct WriterCounters {
  std::uint64_t samples_queued = 0;   ///< handed to the publisher thread through the ring
  std::uint64_t samples_dropped = 0;  ///< refused by a full ring (the publisher thread fell behind)
  std::uint64_t samples_written = 0;  ///< dds_write returned OK
  std::uint64_t write_failures = 0;   ///< dds_write returned an error (timeout included)
  std::uint64_t write_timeouts = 0;   ///< of which DDS_RETCODE_TIMEOUT (max_blocking_time reached)
  std::int32_t last_error = 0;        ///< DDS return code of the last failed write (0: DDS_RETCODE_OK)
};

class TelemetryWriter {
 public:
  /// Ring slots (one sample each) between the cycle and the publisher thread: 21 cycles of 3 samples, 4 s
  /// at 5 Hz, of a publisher thread that gets no CPU.
  static constexpr std::size_t kQueueSlots = 64;

  TelemetryWriter();
  ~TelemetryWriter();  ///< stop(): drains the ring, joins the thread
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  /// `cycle_period_ns` sets the pose / far-range deadline (deadline_periods of it); <= 0: no deadline. Topic
  /// names follow the participant's naming. Starts the publisher thread (signals blocked in it).
  LoadError init(const Participant& participant, const TelemetryParams& params, std::int64_t cycle_period_ns);

  /// Queues PoseEstimate and FarRangeEstimate for this frame. False when one was dropped (ring full), when a
  /// write of either topic failed since the last call (counted), or when the writer is not running.
  bool publishNav(const nav::NavSolution& nav);
  /// Queues Health. False when it was dropped, when a Health write failed since the last call, or when the
  /// writer is not running.
  bool publishHealth(const nav::HealthRecord& health);

  WriterCounters counters() const;

  /// Waits (bounded) until the publisher thread has handed every sample queued so far to dds_write. True
  /// when it did (also when nothing is queued, or the thread is not running and the ring is empty).
  bool flush(std::int64_t timeout_ns) const;
  /// Shutdown: the publisher thread writes what is still queued, then ends and is joined. Bounded: at most
  /// kQueueSlots writes, each bounded by max_blocking_time. Idempotent; the destructor calls it.
  void stop();

  /// Init time: waits (bounded by `timeout_ns` over all topics) until every flight topic's writer has at
  /// least `count` matched readers. False on timeout, with `missing` the first topic short of readers.
  bool waitForReaders(std::uint32_t count, std::int64_t timeout_ns, Topic& missing) const;
  /// Shutdown: flush(), then waits (bounded by `timeout_ns` over both) until the matched reliable readers
  /// have acknowledged every sample written, so the last samples arrive before the participant goes. True
  /// when all did (or nothing was written yet: no writer).
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
  struct Impl;  // telemetry_writer.cpp: the DDS writers, pools, the ring and the publisher thread

  bool failedSince(Topic topic);

  std::unique_ptr<Impl> m_impl;  ///< allocated by init()
};

}  // namespace visnav::telemetry
