// Second process for the telemetry tests and the latency measurement.
//   telemetry_test_peer publish --partition P --count N --rate-hz R [--wait-readers K [--wait-file F]]
//       [--live-exposure]
//       publishes NavSolution/HealthRecord 1..N of telemetry_test_data at R Hz (absolute deadlines on
//       CLOCK_MONOTONIC), after waiting (bounded) for K matched readers on each writer and then for the
//       file F (visnav-monitor --ready-file: the readers matched this writer too); waits for the
//       acknowledgments before exiting. --live-exposure stamps each frame's exposure 1 ms before publication
//       (as a live camera would) instead of the synthetic timestamps.
//   telemetry_test_peer stall-reader --partition P [--max-seconds S]
//       the worst subscriber: reliable KEEP_ALL readers of pose and health limited to one sample, never read.
//       Prints "ready" once created; exits on SIGTERM or after S seconds.
#include <time.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "telemetry_test_data.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace {

using namespace visnav::telemetry;

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

struct Args {
  std::string mode;
  std::string partition = "visnav-test";
  long count = 10;
  double rate_hz = 5.0;
  long wait_readers = 0;
  std::string wait_file;
  bool live_exposure = false;
  double max_seconds = 60.0;
};

bool parse(int argc, char** argv, Args& a) {
  if (argc < 2) return false;
  a.mode = argv[1];
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool v = i + 1 < argc;
    if (arg == "--partition" && v)
      a.partition = argv[++i];
    else if (arg == "--count" && v)
      a.count = std::atol(argv[++i]);
    else if (arg == "--rate-hz" && v)
      a.rate_hz = std::atof(argv[++i]);
    else if (arg == "--wait-readers" && v)
      a.wait_readers = std::atol(argv[++i]);
    else if (arg == "--wait-file" && v)
      a.wait_file = argv[++i];
    else if (arg == "--max-seconds" && v)
      a.max_seconds = std::atof(argv[++i]);
    else if (arg == "--live-exposure")
      a.live_exposure = true;
    else
      return false;
  }
  return a.rate_hz > 0.0 && a.count >= 0;
}

void sleepUntil(std::int64_t t_ns) {
  timespec ts{static_cast<time_t>(t_ns / 1'000'000'000), static_cast<long>(t_ns % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

int publish(const Args& a) {
  TelemetryParams params;
  if (!setPartition(params, a.partition.c_str())) return 2;
  Participant participant;
  TelemetryWriter writer;
  const auto period_ns = static_cast<std::int64_t>(1e9 / a.rate_hz);
  visnav::LoadError e = participant.init(params.domain_id, params.partitionName());
  if (e.ok) e = writer.init(participant, params, period_ns);
  if (!e.ok) {
    std::fprintf(stderr, "telemetry_test_peer: %s\n", e.message.c_str());
    return 2;
  }
  for (Topic t : {Topic::kPose, Topic::kFarRange, Topic::kHealth}) {
    if (a.wait_readers > 0 &&
        !waitForReaders(ddsWriter(writer, t), static_cast<std::uint32_t>(a.wait_readers), 10'000'000'000LL)) {
      std::fprintf(stderr, "telemetry_test_peer: no reader on %s within 10 s\n", topicName(t));
      return 3;
    }
  }
  if (!a.wait_file.empty() && !waitForFile(a.wait_file.c_str(), 10'000'000'000LL)) {
    std::fprintf(stderr, "telemetry_test_peer: no ready file %s within 10 s\n", a.wait_file.c_str());
    return 3;
  }
  std::int64_t next_ns = monotonicNowNs();
  for (long i = 1; i <= a.count && g_stop == 0; ++i) {
    sleepUntil(next_ns);
    next_ns += period_ns;
    visnav::nav::NavSolution nav = test::makeNavSolution(static_cast<std::uint64_t>(i));
    if (a.live_exposure) nav.exposure_time_ns = monotonicNowNs() - 1'000'000;
    writer.publishNav(nav);
    writer.publishHealth(test::makeHealthRecord(static_cast<std::uint64_t>(i)));
    // A reader that has just matched starts out of sync with a Cyclone writer and takes the first samples
    // through a heartbeat / acknack round trip: wait for it once, so a loaded machine cannot lose sample 1
    // from the writer's history before the reader asked for it (tests count every sample from 1).
    if (i == 1 && a.wait_readers > 0) {
      writer.waitForAcks(10'000'000'000LL);
      next_ns = monotonicNowNs() + period_ns;
    }
  }
  writer.waitForAcks(5'000'000'000LL);  // the queue written, then acknowledged
  writer.stop();
  const WriterCounters c = writer.counters();
  std::printf("published %llu samples, %llu dropped, %llu write failures\n",
              static_cast<unsigned long long>(c.samples_written),
              static_cast<unsigned long long>(c.samples_dropped),
              static_cast<unsigned long long>(c.write_failures));
  return c.write_failures == 0 && c.samples_dropped == 0 ? 0 : 1;
}

int stallReader(const Args& a) {
  Participant participant;
  if (visnav::LoadError e = participant.init(0, a.partition.c_str()); !e.ok) {
    std::fprintf(stderr, "telemetry_test_peer: %s\n", e.message.c_str());
    return 2;
  }
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_resource_limits(qos, 1, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  for (Topic t : {Topic::kPose, Topic::kHealth}) {
    if (t == Topic::kHealth) dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
    if (dds_create_reader(participant.subscriber(), participant.topic(t), qos, nullptr) < 0) return 2;
  }
  dds_delete_qos(qos);
  std::printf("ready\n");
  std::fflush(stdout);
  const std::int64_t end_ns = monotonicNowNs() + static_cast<std::int64_t>(a.max_seconds * 1e9);
  while (g_stop == 0 && monotonicNowNs() < end_ns) dds_sleepfor(DDS_MSECS(20));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!parse(argc, argv, args)) {
    std::fputs(
        "usage: telemetry_test_peer publish|stall-reader [--partition P] [--count N] [--rate-hz R]\n"
        "       [--wait-readers K] [--wait-file F] [--live-exposure] [--max-seconds S]\n",
        stderr);
    return 2;
  }
  std::signal(SIGTERM, onSignal);
  std::signal(SIGINT, onSignal);
  if (args.mode == "publish") return publish(args);
  if (args.mode == "stall-reader") return stallReader(args);
  return 2;
}
