#include "visnav/telemetry/telemetry_writer.hpp"

#include <pthread.h>
#include <semaphore.h>
#include <signal.h>
#include <time.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string>

#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/pooled_sertype.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/spsc_ring.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"

namespace visnav::telemetry {
namespace {

constexpr long kIdleLookNs = 100'000'000;  // an idle publisher looks at the stop flag this often

/// One ring slot: a whole sample of one flight topic (fixed size, no pointer: copied, never referenced).
struct QueuedSample {
  Topic topic = Topic::kPose;
  union {
    visnav_PoseEstimate pose;
    visnav_FarRangeEstimate far;
    visnav_Health health;
  };
};

int topicIndex(Topic topic) { return static_cast<int>(topic); }

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

struct TelemetryWriter::Impl {
  dds_entity_t writers[kFlightTopicCount] = {};  // kFlightTopics order
  const PooledSertype* sertypes[kFlightTopicCount] = {};
  // Cycle thread only.
  std::uint64_t nav_samples = 0;
  std::uint64_t health_samples = 0;
  std::uint64_t failures_reported[kFlightTopicCount] = {};
  bool running = false;  // the publisher thread was started and not yet joined
  // Cycle thread -> publisher thread.
  SpscRing<QueuedSample, kQueueSlots> ring;
  sem_t ready{};  // posted per queued sample, on stop and on a hold: wakes an idle publisher
  std::atomic<bool> stopping{false};
  // Counts (written by one thread each, read by any).
  std::atomic<std::uint64_t> dropped{0};  // cycle thread
  std::atomic<std::uint64_t> written{0};  // publisher thread, the rest too
  std::atomic<std::uint64_t> failures{0};
  std::atomic<std::uint64_t> timeouts{0};
  std::atomic<std::int32_t> last_error{0};
  std::atomic<std::uint64_t> topic_failures[kFlightTopicCount] = {};
  // Publisher thread and waiters (flush, the test gate); the cycle thread never takes this mutex.
  std::mutex mutex;
  std::condition_variable changed;  // a sample was taken; the publisher parked; a hold ended; stop
  bool hold = false;                // test gate (DdsAccess::holdPublisher)
  bool parked = false;
  std::atomic<bool> hold_requested{false};
  pthread_t thread{};

  Impl() { sem_init(&ready, 0, 0); }
  ~Impl() { sem_destroy(&ready); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  dds_entity_t writer(Topic topic) const {
    const int i = topicIndex(topic);
    return i >= 0 && i < kFlightTopicCount ? writers[i] : 0;
  }

  // Cycle thread: fill a slot in place and hand it over; a full ring drops this (the newest) sample.
  template <typename Fill>
  bool queue(Topic topic, const Fill& fill) {
    QueuedSample* slot = ring.beginPush();
    if (slot == nullptr) {
      dropped.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    slot->topic = topic;
    fill(*slot);
    ring.commitPush();
    sem_post(&ready);  // atomic increment, a futex wake only if the publisher sleeps: never blocks
    return true;
  }

  // Publisher thread.
  void writeOne(const QueuedSample& s) {
    const void* sample = nullptr;
    switch (s.topic) {
      case Topic::kPose: sample = &s.pose; break;
      case Topic::kFarRange: sample = &s.far; break;
      case Topic::kHealth: sample = &s.health; break;
      case Topic::kModeCommand: return;
    }
    const dds_return_t rc = dds_write(writer(s.topic), sample);
    if (rc == DDS_RETCODE_OK) {
      written.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    failures.fetch_add(1, std::memory_order_relaxed);
    topic_failures[topicIndex(s.topic)].fetch_add(1, std::memory_order_relaxed);
    if (rc == DDS_RETCODE_TIMEOUT) timeouts.fetch_add(1, std::memory_order_relaxed);
    last_error.store(rc, std::memory_order_relaxed);
  }

  void parkWhileHeld() {
    std::unique_lock<std::mutex> lock(mutex);
    if (!hold) return;
    parked = true;
    changed.notify_all();
    changed.wait(lock, [this] { return !hold || stopping.load(std::memory_order_acquire); });
    parked = false;
  }

  void drainLoop() {
    for (;;) {
      if (hold_requested.load(std::memory_order_acquire)) parkWhileHeld();
      if (const QueuedSample* s = ring.front()) {
        writeOne(*s);  // counted before the slot goes back: flush() sees the count
        ring.pop();
        const std::lock_guard<std::mutex> lock(mutex);
        changed.notify_all();
        continue;
      }
      // Stop only on an empty ring, read after the flag: a sample queued just before stop() is still written.
      if (stopping.load(std::memory_order_acquire)) {
        if (ring.front() == nullptr) return;
        continue;
      }
      timespec until{};
      clock_gettime(CLOCK_MONOTONIC, &until);
      until.tv_nsec += kIdleLookNs;
      if (until.tv_nsec >= 1'000'000'000L) {
        until.tv_nsec -= 1'000'000'000L;
        ++until.tv_sec;
      }
      sem_clockwait(&ready, CLOCK_MONOTONIC, &until);  // a sample, stop or hold; or look again
    }
  }

  static void* threadMain(void* self) {
    // Signals (SIGTERM, SIGUSR1, ...) are the cycle thread's business: never delivered here.
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, nullptr);
    static_cast<Impl*>(self)->drainLoop();
    return nullptr;
  }
};

TelemetryWriter::TelemetryWriter() = default;
TelemetryWriter::~TelemetryWriter() { stop(); }

LoadError TelemetryWriter::init(const Participant& participant, const TelemetryParams& params,
                                std::int64_t cycle_period_ns) {
  if (!participant.isOpen()) return LoadError::failure("telemetry writer: participant not initialised");
  if (const char* problem = params.crossCheck()) return LoadError::failure(problem);
  stop();                             // a second init(): the old thread goes first
  m_impl = std::make_unique<Impl>();  // init time: writers, ring, counters
  Impl& d = *m_impl;
  static_assert(kFlightTopicCount == 3, "one writer per flight topic");
  constexpr const char* kWhat[kFlightTopicCount] = {
      "creating the pose writer", "creating the far-range writer", "creating the health writer"};
  for (Topic topic : kFlightTopics) {
    const int i = topicIndex(topic);
    d.writers[i] = createWriter(participant, topic, params, cycle_period_ns, &d.sertypes[i]);
    if (d.writers[i] < 0) return ddsFailure(kWhat[i], d.writers[i]);
  }
  const int rc = pthread_create(&d.thread, nullptr, &Impl::threadMain, &d);
  if (rc != 0)
    return LoadError::failure(std::string("telemetry writer: cannot start the publisher thread: ") +
                              std::strerror(rc));
  pthread_setname_np(d.thread, "visnav-publish");
  d.running = true;
  return LoadError::success();
}

void TelemetryWriter::stop() {
  if (!m_impl || !m_impl->running) return;
  Impl& d = *m_impl;
  d.stopping.store(true, std::memory_order_release);
  {
    const std::lock_guard<std::mutex> lock(d.mutex);  // ends a test hold: stop wins
    d.changed.notify_all();
  }
  sem_post(&d.ready);
  pthread_join(d.thread, nullptr);
  d.running = false;
}

bool TelemetryWriter::failedSince(Topic topic) {
  Impl& d = *m_impl;
  const int i = topicIndex(topic);
  const std::uint64_t now = d.topic_failures[i].load(std::memory_order_relaxed);
  const bool failed = now != d.failures_reported[i];
  d.failures_reported[i] = now;
  return failed;
}

bool TelemetryWriter::publishNav(const nav::NavSolution& nav) {
  if (!m_impl || !m_impl->running) return false;
  Impl& d = *m_impl;
  ++d.nav_samples;  // also for a dropped sample: the reader sees the gap, as for a loss in transport
  const std::int64_t now_ns = monotonicNowNs();
  const bool pose_queued =
      d.queue(Topic::kPose, [&](QueuedSample& s) { fillPoseEstimate(nav, d.nav_samples, now_ns, s.pose); });
  const bool far_queued = d.queue(
      Topic::kFarRange, [&](QueuedSample& s) { fillFarRangeEstimate(nav, d.nav_samples, now_ns, s.far); });
  const bool pose_failed = failedSince(Topic::kPose);
  const bool far_failed = failedSince(Topic::kFarRange);
  return pose_queued && far_queued && !pose_failed && !far_failed;
}

bool TelemetryWriter::publishHealth(const nav::HealthRecord& health) {
  if (!m_impl || !m_impl->running) return false;
  Impl& d = *m_impl;
  ++d.health_samples;
  const std::int64_t now_ns = monotonicNowNs();
  const bool queued = d.queue(
      Topic::kHealth, [&](QueuedSample& s) { fillHealth(health, d.health_samples, now_ns, s.health); });
  const bool failed = failedSince(Topic::kHealth);
  return queued && !failed;
}

WriterCounters TelemetryWriter::counters() const {
  WriterCounters c;
  if (!m_impl) return c;
  const Impl& d = *m_impl;
  c.samples_queued = d.ring.pushed();
  c.samples_dropped = d.dropped.load(std::memory_order_relaxed);
  c.samples_written = d.written.load(std::memory_order_relaxed);
  c.write_failures = d.failures.load(std::memory_order_relaxed);
  c.write_timeouts = d.timeouts.load(std::memory_order_relaxed);
  c.last_error = d.last_error.load(std::memory_order_relaxed);
  return c;
}

bool TelemetryWriter::flush(std::int64_t timeout_ns) const {
  if (!m_impl) return true;
  Impl& d = *m_impl;
  const std::uint64_t target = d.ring.pushed();
  if (d.ring.popped() >= target) return true;
  if (!d.running) return false;  // nobody left to take them
  std::unique_lock<std::mutex> lock(d.mutex);
  return d.changed.wait_for(lock, std::chrono::nanoseconds(timeout_ns > 0 ? timeout_ns : 0),
                            [&] { return d.ring.popped() >= target; });
}

dds_entity_t DdsAccess::writer(const TelemetryWriter& writer, Topic topic) {
  return writer.m_impl ? writer.m_impl->writer(topic) : 0;
}

bool DdsAccess::holdPublisher(TelemetryWriter& writer, std::int64_t timeout_ns) {
  if (!writer.m_impl || !writer.m_impl->running) return false;
  TelemetryWriter::Impl& d = *writer.m_impl;
  std::unique_lock<std::mutex> lock(d.mutex);
  d.hold = true;
  d.hold_requested.store(true, std::memory_order_release);
  sem_post(&d.ready);  // an idle publisher wakes up and parks
  return d.changed.wait_for(lock, std::chrono::nanoseconds(timeout_ns), [&] { return d.parked; });
}

void DdsAccess::releasePublisher(TelemetryWriter& writer) {
  if (!writer.m_impl) return;
  TelemetryWriter::Impl& d = *writer.m_impl;
  const std::lock_guard<std::mutex> lock(d.mutex);
  d.hold = false;
  d.hold_requested.store(false, std::memory_order_release);
  d.changed.notify_all();
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
  bool all = flush(timeout_ns);  // what is still queued is written first
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
  if (!m_impl || topicIndex(topic) >= kFlightTopicCount) return nullptr;
  return m_impl->sertypes[topicIndex(topic)];
}

std::uint64_t TelemetryWriter::samplePoolMisses() const {
  if (!m_impl) return 0;
  std::uint64_t misses = 0;
  for (const PooledSertype* s : m_impl->sertypes) misses += pooledSertypeStats(s).pool_misses;
  return misses;
}

}  // namespace visnav::telemetry
