// Separate processes over loopback DDS: visnav-monitor receiving everything a publisher process sends (none
// lost, CSV readable by visnav-eval with the published poses), visnav-command exit codes against a flight
// loop, and non-blocking writes while a subscriber process never reads or is frozen.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "process_util.hpp"
#include "telemetry_test_data.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"  // test-only: the DDS writers

namespace visnav::telemetry {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

std::size_t lineCount(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(TelemetryProcesses, MonitorReceivesEverySampleFromAnotherProcess) {
  constexpr int kCount = 60;
  const TelemetryParams params = test::uniqueLinkParams("two-process");
  const std::string partition = params.partitionName();
  const std::string csv = test::tempPath("monitor") + ".csv";
  const std::string monitor_out = test::tempPath("monitor-out");
  const std::string ready = test::tempPath("monitor-ready");
  const pid_t monitor =
      test::spawnProcess({VISNAV_MONITOR, "--partition", partition, "--samples", std::to_string(kCount),
                          "--duration", "20", "--no-view", "--csv", csv, "--ready-file", ready},
                         monitor_out);
  ASSERT_GT(monitor, 0);
  // 50 Hz keeps the test short. The publisher waits (bounded) until its writers see the monitor's readers
  // and then for the monitor's ready file (its readers see the writers): the first sample is not dropped.
  const pid_t publisher = test::spawnProcess({VISNAV_TEST_PEER, "publish", "--partition", partition,
                                              "--count", std::to_string(kCount), "--rate-hz", "50",
                                              "--wait-readers", "1", "--wait-file", ready});
  ASSERT_GT(publisher, 0);
  EXPECT_EQ(test::waitProcess(publisher, 20.0), 0);
  ASSERT_EQ(test::waitProcess(monitor, 20.0), 0) << test::readText(monitor_out);

  const std::string summary = test::readText(monitor_out);
  EXPECT_NE(summary.find("pose: samples 60, "), std::string::npos) << summary;
  EXPECT_NE(summary.find("lost samples 0, lost frames 0 (none)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("health: samples 60, "), std::string::npos) << summary;

  std::vector<eval::ReplayRow> rows;
  const LoadError e = eval::loadReplayCsv(csv, rows);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(kCount));
  for (int k = 0; k < kCount; ++k) {
    const nav::NavSolution n = test::makeNavSolution(static_cast<std::uint64_t>(k + 1));
    EXPECT_EQ(rows[k].frame, static_cast<std::int64_t>(n.frame_number));
    EXPECT_EQ(eval::isTracked(rows[k].status), n.pose_valid);
    EXPECT_LE((rows[k].pose.t_c_m - n.pose.t_c_m).norm(), 1e-10);
    EXPECT_LE((rows[k].pose.R_c_m - n.pose.R_c_m).norm(), 1e-10);
  }
  EXPECT_EQ(lineCount(test::readText(csv.substr(0, csv.size() - 4) + "_far_range.csv")), kCount + 1U);
  EXPECT_EQ(lineCount(test::readText(csv.substr(0, csv.size() - 4) + "_health.csv")), kCount + 1U);
}

// A stand-in for the flight loop: polls commands every 20 ms, accepts every valid one except resume
// ("not in standby"), acknowledges in Health.
class FlightLoop {
 public:
  explicit FlightLoop(const TelemetryParams& params) {
    ok = participant.init(params.domain_id, params.partitionName()).ok &&
         writer.init(participant, params, 0).ok && reader.init(participant, params).ok;
    if (ok) thread = std::thread([this] { run(); });
  }
  ~FlightLoop() {
    stop = true;
    if (thread.joinable()) thread.join();
  }
  bool ok = false;

 private:
  void run() {
    nav::HealthRecord health;
    ReceivedCommand batch[kMaxCommandDepth];
    while (!stop) {
      const int n = reader.poll(batch, kMaxCommandDepth);
      for (int i = 0; i < n; ++i) {
        const bool resume = batch[i].kind == nav::ModeCommandKind::kResume;
        health.last_command = batch[i].ack(!resume, resume ? "not in standby" : "ok");
      }
      writer.publishHealth(health);
      dds_sleepfor(DDS_MSECS(20));
    }
  }
  Participant participant;
  TelemetryWriter writer;
  CommandReader reader;
  std::atomic<bool> stop{false};
  std::thread thread;
};

TEST(TelemetryProcesses, MonitorThatHearsNothingSaysSoAndFails) {
  // A partition nobody publishes on stands for a wrong CYCLONEDDS_URI, domain or partition.
  const std::string partition = "silent-" + std::to_string(getpid());
  const std::string err = test::tempPath("monitor-silent");
  const pid_t monitor = test::spawnProcess(
      {"/bin/sh", "-c",
       std::string(VISNAV_MONITOR) + " --partition " + partition + " --duration 1 --no-view 2> " + err});
  ASSERT_GT(monitor, 0);
  EXPECT_EQ(test::waitProcess(monitor, 30.0), 4);  // README "Exit codes": nobody answered
  EXPECT_NE(test::readText(err).find("no sample on any topic"), std::string::npos) << test::readText(err);
  EXPECT_NE(test::readText(err).find("partition '" + partition + "'"), std::string::npos);
}

TEST(TelemetryProcesses, VisnavCommandExitCodeReflectsTheAcknowledgment) {
  const TelemetryParams params = test::uniqueLinkParams("command");
  const std::string partition = params.partitionName();
  const std::string out = test::tempPath("command-out");
  {
    FlightLoop flight(params);
    ASSERT_TRUE(flight.ok);
    pid_t pid = test::spawnProcess({VISNAV_COMMAND, "standby", "--partition", partition, "--id", "77"}, out);
    EXPECT_EQ(test::waitProcess(pid, 15.0), 0);
    EXPECT_NE(test::readText(out).find("#77 standby accepted: ok"), std::string::npos) << test::readText(out);
    pid = test::spawnProcess({VISNAV_COMMAND, "resume", "--partition", partition, "--id", "78"}, out);
    EXPECT_EQ(test::waitProcess(pid, 15.0), 1);
    EXPECT_NE(test::readText(out).find("#78 resume rejected: not in standby"), std::string::npos);
  }
  // Nobody listening: bounded wait, then exit code 4 (README "Exit codes").
  const std::int64_t start = monotonicNowNs();
  pid_t pid = test::spawnProcess({VISNAV_COMMAND, "reacquire", "--partition", partition, "--timeout", "1"});
  EXPECT_EQ(test::waitProcess(pid, 15.0), 4);
  EXPECT_LT(monotonicNowNs() - start, 8 * kSecond);
  pid = test::spawnProcess({VISNAV_COMMAND, "warp-drive", "--partition", partition});
  EXPECT_EQ(test::waitProcess(pid, 15.0), 2);
}

struct WriteTimes {
  std::vector<double> ms;
  double max() const { return *std::max_element(ms.begin(), ms.end()); }
  double median() {
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
  }
};

WriteTimes publishCycles(TelemetryWriter& writer, int cycles) {
  WriteTimes t;
  for (int i = 1; i <= cycles; ++i) {
    const std::int64_t start = monotonicNowNs();
    writer.publishNav(test::makeNavSolution(static_cast<std::uint64_t>(i)));
    writer.publishHealth(test::makeHealthRecord(static_cast<std::uint64_t>(i)));
    t.ms.push_back(static_cast<double>(monotonicNowNs() - start) * 1e-6);
    dds_sleepfor(DDS_MSECS(2));
  }
  return t;
}

TEST(TelemetryProcesses, PublishNeverBlocksOnAStalledOrFrozenSubscriber) {
  const TelemetryParams params = test::uniqueLinkParams("stall");
  const std::string ready = test::tempPath("stall-ready");
  const pid_t peer = test::spawnProcess(
      {VISNAV_TEST_PEER, "stall-reader", "--partition", params.partitionName(), "--max-seconds", "60"},
      ready);
  ASSERT_GT(peer, 0);
  Participant flight;
  TelemetryWriter writer;
  ASSERT_TRUE(flight.init(params.domain_id, params.partitionName()).ok);
  ASSERT_TRUE(writer.init(flight, params, 200'000'000).ok);
  ASSERT_TRUE(waitForReaders(ddsWriter(writer, Topic::kPose), 1, 10 * kSecond)) << test::readText(ready);
  ASSERT_TRUE(waitForReaders(ddsWriter(writer, Topic::kHealth), 1, 10 * kSecond));

  constexpr int kCycles = 300;  // the stalled reader's one-sample history is full after the first
  WriteTimes stalled = publishCycles(writer, kCycles);
  kill(peer, SIGSTOP);  // frozen: no acknowledgment, no NACK, its socket buffer fills up
  WriteTimes frozen = publishCycles(writer, kCycles);
  // Dead: killed without a goodbye, it stays matched until its lease expires (10 s by default). (SIGKILL also
  // because Cyclone's own receive thread in the stalled process waits for room in the full KEEP_ALL history,
  // which would hold up a clean exit there.)
  kill(peer, SIGKILL);
  EXPECT_EQ(test::waitProcess(peer, 10.0), 128 + SIGKILL);
  WriteTimes dead = publishCycles(writer, kCycles);
  dds_publication_matched_status_t matched{};
  ASSERT_EQ(dds_get_publication_matched_status(ddsWriter(writer, Topic::kPose), &matched), DDS_RETCODE_OK);
  EXPECT_EQ(matched.current_count, 1U);  // the dead reader was still matched for the whole phase

  ASSERT_TRUE(writer.flush(10 * kSecond));
  EXPECT_EQ(writer.counters().write_failures, 0U);
  EXPECT_EQ(writer.counters().samples_dropped, 0U);
  EXPECT_EQ(writer.counters().samples_written, 3U * 3U * kCycles);
  // A blocked writer would wait max_blocking_time (2 ms) per write and then fail; these are bounded by a
  // scheduling hiccup on a loaded 2-core machine, not by the reader.
  for (WriteTimes* t : {&stalled, &frozen, &dead}) {
    EXPECT_LT(t->max(), 50.0);
    EXPECT_LT(t->median(), 1.0);
  }
  std::printf(
      "publishNav + publishHealth [ms]: stalled reader median %.3f max %.3f; frozen %.3f / %.3f; "
      "dead %.3f / %.3f\n",
      stalled.median(), stalled.max(), frozen.median(), frozen.max(), dead.median(), dead.max());
}

}  // namespace
}  // namespace visnav::telemetry
