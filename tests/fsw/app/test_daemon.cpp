// The daemon's cycle in-process: a replay camera on the simulated clock (deterministic), real DDS on loopback
// read back by a GroundLink in the same process. Checks the wiring against the pipeline driven directly, the
// command path, slips and task timings in Health, the bounded camera wait on the real clock, the log, and the
// systemd watchdog withheld while a stage keeps failing (a real datagram socket stands in for systemd).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "app_test_support.hpp"
#include "visnav/app/daemon.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/replay/replay_camera.hpp"
#include "visnav/telemetry/ground_link.hpp"

namespace visnav::app {
namespace {

constexpr int kFrames = VISNAV_APP_TEST_FRAMES;  // far range, acquisition, near range

std::string partitionFor(const char* name) { return std::string(name) + "-" + std::to_string(getpid()); }

std::string replayConfig(const std::string& sequence, const std::string& partition, bool telemetry,
                         const std::string& extra = "") {
  return "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
         "\"\n[telemetry]\nenabled = " + (telemetry ? "true" : "false") + "\npartition = \"" + partition +
         "\"\n" + extra;
}

/// The log of a test: a file the EventLog writes to, read back as text.
struct LogFile {
  test::TempDir dir{"log"};
  std::string path = dir.path() + "/log.txt";
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  EventLog log{fd, false};
  ~LogFile() { ::close(fd); }
  std::string text() const {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
};

template <typename Sample, typename Take>
std::vector<Sample> drain(telemetry::GroundLink& link, Take take, std::size_t expected) {
  std::vector<Sample> out;
  std::array<Sample, telemetry::kMaxTakeBatch> batch{};
  std::array<dds_sample_info_t, telemetry::kMaxTakeBatch> infos{};
  for (int attempt = 0; attempt < 300 && out.size() < expected; ++attempt) {  // bounded: 3 s
    link.waitForData(10'000'000);
    const int n = (link.*take)(batch.data(), infos.data(), telemetry::kMaxTakeBatch);
    for (int i = 0; i < n; ++i)
      if (infos[static_cast<std::size_t>(i)].valid_data) out.push_back(batch[static_cast<std::size_t>(i)]);
  }
  return out;
}

TEST(Daemon, PublishesWhatThePipelineComputesForEveryFrame) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("daemon");
  const std::string partition = partitionFor("daemon-wiring");
  const VisnavConfig config = test::configFromText(dir, replayConfig(sequence, partition, true));
  telemetry::GroundLink ground;
  ASSERT_TRUE(ground.init(config.telemetry, 256).ok);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  options.wait_subscribers = 1;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  ASSERT_EQ(daemon.run(), kExitOk);

  // Reference: the same pipeline driven directly over the same frames at their recorded times.
  replay::ReplayCamera camera({sequence, camera::Pacing::kAsFastAsPossible, false, 2});
  ASSERT_TRUE(camera.open().ok);
  nav::NavigationPipeline reference;
  ASSERT_TRUE(
      reference.init(PinholeCamera(camera.sequence().camera), camera.sequence().model, config.pipeline).ok);
  std::vector<nav::NavSolution> expected;
  std::vector<nav::NavMode> mode_after;
  Frame frame;
  while (camera.acquire(0, frame) == camera::AcquireResult::kFrame) {
    nav::NavSolution solution;
    reference.process(&frame, frame.exposure_time_ns, solution);
    expected.push_back(solution);
    mode_after.push_back(reference.mode());
    camera.release(frame);
  }
  ASSERT_EQ(expected.size(), static_cast<std::size_t>(kFrames));

  const auto poses = drain<visnav_PoseEstimate>(ground, &telemetry::GroundLink::takePose, kFrames);
  const auto healths = drain<visnav_Health>(ground, &telemetry::GroundLink::takeHealth, kFrames);
  ASSERT_EQ(poses.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(healths.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const nav::NavSolution& e = expected[i];
    EXPECT_EQ(poses[i].sample_number, i + 1);
    EXPECT_EQ(poses[i].frame_number, e.frame_number);
    EXPECT_EQ(poses[i].exposure_time_ns, e.exposure_time_ns);
    EXPECT_EQ(poses[i].mode, static_cast<std::uint8_t>(e.mode)) << i;
    EXPECT_EQ(poses[i].pose_valid, e.pose_valid) << i;
    EXPECT_EQ(poses[i].position_m[2], e.pose.t_c_m.z()) << i;  // bit-identical: same code, same inputs
    EXPECT_EQ(healths[i].sample_number, i + 1);
    EXPECT_EQ(healths[i].frames_processed, i + 1);
    EXPECT_EQ(healths[i].mode, static_cast<std::uint8_t>(mode_after[i])) << i;
  }
  EXPECT_EQ(healths.back().mode_transitions, reference.modes().transitionCount());
  EXPECT_TRUE(daemon.counters().end_of_stream);
  EXPECT_EQ(daemon.executive().counters().cycles,
            static_cast<std::uint64_t>(kFrames + 1));  // + end of stream
  EXPECT_EQ(daemon.telemetryWriter().counters().samples_written, 3U * kFrames);

  const std::string text = log.text();
  EXPECT_NE(text.find("event=subscribers_matched readers=1"), std::string::npos) << text;
  EXPECT_NE(text.find("event=start config="), std::string::npos) << text;
  const std::string frames = std::to_string(kFrames);
  EXPECT_NE(text.find("event=end_of_stream driver=replay frames=" + frames + " action=stop"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("event=stop reason=end_of_stream cycles=" + std::to_string(kFrames + 1) +
                      " frames=" + frames + " cycles_without_frame=0"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("event=stop_timing clock=simulated"), std::string::npos) << text;
  // One log line per mode transition, with its reason.
  std::size_t lines = 0;
  for (std::size_t at = text.find("event=mode_transition"); at != std::string::npos;
       at = text.find("event=mode_transition", at + 1))
    ++lines;
  EXPECT_EQ(lines, reference.modes().transitionCount());
  EXPECT_GE(lines, 2U);  // far range -> acquisition -> near range
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kNearRange);
}

TEST(Daemon, CommandsAreValidatedAndAcknowledgedInHealth) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-commands"), true, "[daemon]\nplayback_loop = true\n"));
  telemetry::GroundLink ground;
  ASSERT_TRUE(ground.init(config.telemetry, 256).ok);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  options.wait_subscribers = 1;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  ASSERT_TRUE(telemetry::waitForReaders(ground.commandWriter(), 1, 10'000'000'000LL));
  ASSERT_EQ(daemon.executive().run(3), exec::StopReason::kCycleLimit);

  auto commandRoundTrip = [&](std::uint32_t id, std::uint8_t kind) {
    EXPECT_EQ(ground.sendCommand(id, kind), DDS_RETCODE_OK);
    for (int i = 0; i < 200 && daemon.lastHealth().last_command.command_id != id; ++i) {  // bounded: 2 s
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      daemon.executive().run(1);
    }
    return daemon.lastHealth().last_command;
  };
  nav::CommandAck ack = commandRoundTrip(77, 2);  // standby
  EXPECT_EQ(ack.command_id, 77U);
  EXPECT_TRUE(ack.accepted);
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kStandby);
  ack = commandRoundTrip(78, 9);  // no such kind
  EXPECT_EQ(ack.command_id, 78U);
  EXPECT_FALSE(ack.accepted);
  EXPECT_NE(std::string(ack.reason.data()).find('9'), std::string::npos) << ack.reason.data();
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kStandby);
  ack = commandRoundTrip(79, 3);  // resume
  EXPECT_TRUE(ack.accepted) << ack.reason.data();
  EXPECT_NE(daemon.pipeline().mode(), nav::NavMode::kStandby);
  EXPECT_EQ(daemon.counters().commands, 3U);
  EXPECT_EQ(daemon.counters().commands_accepted, 2U);

  const std::string text = log.text();
  EXPECT_NE(text.find("event=command id=77 kind=standby raw_kind=2 accepted=yes"), std::string::npos) << text;
  EXPECT_NE(text.find("event=command id=78 kind=unknown raw_kind=9 accepted=no"), std::string::npos) << text;
  EXPECT_NE(text.find("to=standby reason="), std::string::npos) << text;
}

TEST(Daemon, SlipsAndTaskTimingsReachHealth) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  // Each task "takes" 60 ms on the simulated clock: 240 ms per 200 ms cycle, a slip every cycle.
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-slips"), false,
                        "[executive]\nsim_task_time = \"fixed\"\nsim_task_us = 60000.0\n"));
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  ASSERT_EQ(daemon.executive().run(6), exec::StopReason::kCycleLimit);
  const nav::HealthRecord& health = daemon.lastHealth();
  EXPECT_EQ(daemon.executive().counters().slips, 6U);
  EXPECT_EQ(health.cycle_slips, 5U);  // the sixth slip is known only after its health task ran
  EXPECT_EQ(health.fault_counts[static_cast<std::size_t>(bitIndex(kFaultCycleSlip))], 5U);
  EXPECT_NE(health.fault_bits & nav::kFaultCycleSlip, 0U);
  for (int task = 0; task < nav::kTaskCount; ++task) {
    const nav::TaskTimingSummary& t = health.task_timing[static_cast<std::size_t>(task)];
    EXPECT_DOUBLE_EQ(t.min_us, 60000.0) << task;
    EXPECT_DOUBLE_EQ(t.max_us, 60000.0) << task;
  }
  EXPECT_NE(log.text().find("event=cycle_slip minor_frame=0 overrun_ms=40.000 releases_skipped=1"),
            std::string::npos)
      << log.text();
}

// Real clock, 5 Hz, a replay recorded at 0.625 Hz and paced at that rate: 7 of 8 cycles have no frame. The
// wait is bounded by acquire_timeout_ms, so the cycle never slips, and the missing frames are counted.
TEST(Daemon, ACameraSlowerThanTheCycleNeverBlocksIt) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig slow =
      test::configFromText(dir, "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                    "\"\nacquire_timeout_ms = 50.0\n[telemetry]\nenabled = false\n");
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.max_cycles = 10;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(slow, options), kExitOk) << log.text();
  ASSERT_EQ(daemon.run(), kExitOk);
  EXPECT_EQ(daemon.counters().frames, 2U);  // t = 0 and t = 1.6 s
  EXPECT_EQ(daemon.counters().cycles_without_frame, 8U);
  EXPECT_EQ(daemon.camera().counters().timeouts, 8U);
  EXPECT_EQ(daemon.executive().counters().slips, 0U);
  const exec::DurationStats& acquire = daemon.executive().taskStats(daemon.taskId(CycleStage::kAcquire)).exec;
  EXPECT_LT(acquire.maxNs(), 80'000'000);  // 50 ms bound plus scheduling
  EXPECT_GE(acquire.maxNs(), 50'000'000);
  EXPECT_EQ(daemon.lastHealth().frames_dropped, 8U);
  EXPECT_NE(log.text().find("event=fault_onset fault=no_frame frame="), std::string::npos) << log.text();
}

/// systemd's end of $NOTIFY_SOCKET: a datagram socket bound at a path of the test.
class NotifySocket {
 public:
  NotifySocket() {
    m_path = "/tmp/visnav-daemon-notify-" + std::to_string(getpid());
    m_fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, m_path.c_str(), m_path.size() + 1);
    unlink(m_path.c_str());
    EXPECT_EQ(bind(m_fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  }
  ~NotifySocket() {
    close(m_fd);
    unlink(m_path.c_str());
  }
  const std::string& path() const { return m_path; }
  /// Takes every datagram waiting and returns how many were "WATCHDOG=1".
  int drainWatchdogs() {
    int count = 0;
    char buffer[512];
    for (ssize_t n; (n = recv(m_fd, buffer, sizeof(buffer), MSG_DONTWAIT)) > 0;)
      count += std::string(buffer, static_cast<std::size_t>(n)) == "WATCHDOG=1" ? 1 : 0;
    return count;
  }

 private:
  std::string m_path;
  int m_fd = -1;
};

// The watchdog means health (fsw/app/README.md, "Watchdog"): frames 20..29 of the replay are unreadable, so
// the camera delivers nothing for 10 cycles; past [daemon] camera_stall_cycles = 2 the acquire stage stops
// beating and WATCHDOG=1 stops, one cycle at a time, until frames come again. Simulated clock: exact counts.
TEST(Daemon, AStageThatKeepsFailingWithholdsTheWatchdog) {
  const std::string source = test::renderedApproachCi(kFrames);
  ASSERT_FALSE(source.empty());
  test::TempDir dir("daemon");
  const std::string sequence = dir.path() + "/sequence";
  std::filesystem::copy(source, sequence, std::filesystem::copy_options::recursive);
  {
    replay::ReplayCamera copy({sequence, camera::Pacing::kAsFastAsPossible, false, 2});
    ASSERT_TRUE(copy.open().ok);
    for (std::size_t i = 20; i < 30; ++i) std::ofstream(copy.sequence().frames[i].file) << "not a PGM\n";
  }
  const VisnavConfig config = test::configFromText(
      dir,
      replayConfig(sequence, partitionFor("daemon-watchdog"), false, "[daemon]\ncamera_stall_cycles = 2\n"));
  NotifySocket systemd;
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  setenv("WATCHDOG_USEC", "2000000", 1);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  const int init = daemon.init(config, options);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  ASSERT_EQ(init, kExitOk) << log.text();
  ASSERT_TRUE(daemon.notifier().active());

  std::vector<int> strokes;  // WATCHDOG=1 per cycle
  for (int cycle = 0; cycle < 40; ++cycle) {
    ASSERT_EQ(daemon.executive().run(1), exec::StopReason::kCycleLimit);
    strokes.push_back(systemd.drainWatchdogs());
  }
  std::vector<int> expected(40, 1);
  for (std::size_t i = 22; i < 30; ++i) expected[i] = 0;  // cycles 20, 21 are within the stall allowance
  EXPECT_EQ(strokes, expected);
  EXPECT_EQ(daemon.counters().frames, 30U);
  EXPECT_EQ(daemon.camera().counters().errors, 10U);
  EXPECT_EQ(daemon.counters().watchdog_withheld, 8U);
  EXPECT_EQ(daemon.counters().watchdog_strokes, 32U);
  const HeartbeatMonitor& heartbeat = daemon.heartbeat();
  EXPECT_EQ(heartbeat.stage(CycleStage::kAcquire).missed, 8U);
  for (CycleStage stage : {CycleStage::kProcess, CycleStage::kPublish, CycleStage::kHealth})
    EXPECT_EQ(heartbeat.stage(stage).missed, 0U) << stageName(stage);  // no frame is not processing's failure
  const std::string text = log.text();
  EXPECT_NE(text.find("event=heartbeat_missed stage=acquire minor_frame="), std::string::npos) << text;
  EXPECT_NE(text.find("event=heartbeat_restored stage=acquire minor_frame="), std::string::npos) << text;
  EXPECT_NE(text.find("missed_in_a_row=8 missed=8"), std::string::npos) << text;
}

/// systemd's side of WatchdogSec (service_dispatch_watchdog): every WATCHDOG=1 re-arms a timer of
/// `watchdog_ns`; it fires once that much time passes without one. Time is the daemon's simulated clock, read
/// by the test after each cycle, so the verdict is exact and owes nothing to the machine's speed.
struct SystemdWatchdogStandIn {
  std::int64_t watchdog_ns = 0;
  std::int64_t armed_at_ns = 0;
  /// Feeds the strokes received during a cycle that ended at `now_ns`; true once the watchdog fired.
  bool cycleEnded(int strokes, std::int64_t now_ns) {
    if (strokes > 0) armed_at_ns = now_ns;
    return now_ns - armed_at_ns >= watchdog_ns;
  }
};

// Issue 14, "a repeatedly failing stage must lead to the watchdog firing": fault injection ([daemon]
// fault_stage, off by default) makes the process stage report a failure every cycle from cycle 10 on. The
// daemon runs on the simulated clock with every task charged 50 ms (one 200 ms period per cycle, no slip);
// systemd's end is the real notify socket plus the stand-in above, with WatchdogSec = 1 s (5 cycles).
TEST(Daemon, AProcessStageThatFailsEveryCycleLetsSystemdsWatchdogFire) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-fault"), false,
                        "[daemon]\nfault_stage = \"process\"\nfault_kind = \"fail\"\nfault_from_cycle = 10\n"
                        "[executive]\nsim_task_time = \"fixed\"\nsim_task_us = 50000.0\n"));
  NotifySocket systemd;
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  setenv("WATCHDOG_USEC", "1000000", 1);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  const int init = daemon.init(config, options);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  ASSERT_EQ(init, kExitOk) << log.text();
  ASSERT_EQ(daemon.notifier().watchdogUsec(), 1000000U);

  SystemdWatchdogStandIn watchdog{static_cast<std::int64_t>(daemon.notifier().watchdogUsec()) * 1000,
                                  daemon.clock().nowNs()};
  std::vector<int> strokes;  // WATCHDOG=1 per cycle
  int fired_in_cycle = -1;
  for (int cycle = 0; cycle < 30; ++cycle) {
    ASSERT_EQ(daemon.executive().run(1), exec::StopReason::kCycleLimit);
    strokes.push_back(systemd.drainWatchdogs());
    if (watchdog.cycleEnded(strokes.back(), daemon.clock().nowNs()) && fired_in_cycle < 0)
      fired_in_cycle = cycle;
  }
  std::vector<int> expected(30, 0);
  for (std::size_t i = 0; i < 10; ++i) expected[i] = 1;
  EXPECT_EQ(strokes, expected);
  EXPECT_EQ(fired_in_cycle, 14);  // last stroke at the end of cycle 9, + 1 s = 5 cycles
  EXPECT_EQ(daemon.executive().counters().slips, 0U);
  EXPECT_EQ(daemon.counters().faults_injected, 20U);
  EXPECT_EQ(daemon.counters().watchdog_withheld, 20U);
  EXPECT_EQ(daemon.heartbeat().stage(CycleStage::kProcess).missed, 20U);
  for (CycleStage stage : {CycleStage::kAcquire, CycleStage::kPublish, CycleStage::kHealth})
    EXPECT_EQ(daemon.heartbeat().stage(stage).missed, 0U) << stageName(stage);
  EXPECT_EQ(daemon.executive().taskStats(daemon.taskId(CycleStage::kProcess)).failures, 20U);
  const std::string text = log.text();
  EXPECT_NE(text.find("event=fault_injected stage=process kind=fail minor_frame=0 cycle=10"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("event=heartbeat_missed stage=process"), std::string::npos) << text;
}

// Without fault injection the same run strokes every cycle and the stand-in never fires: the test above
// fails for the reason it names, not because of the stand-in or the clock.
TEST(Daemon, WithoutTheInjectedFaultTheWatchdogIsFedEveryCycle) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-nofault"), false,
                        "[executive]\nsim_task_time = \"fixed\"\nsim_task_us = 50000.0\n"));
  NotifySocket systemd;
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  setenv("WATCHDOG_USEC", "1000000", 1);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  const int init = daemon.init(config, options);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  ASSERT_EQ(init, kExitOk) << log.text();
  SystemdWatchdogStandIn watchdog{1'000'000'000, daemon.clock().nowNs()};
  for (int cycle = 0; cycle < 30; ++cycle) {
    ASSERT_EQ(daemon.executive().run(1), exec::StopReason::kCycleLimit);
    const int strokes = systemd.drainWatchdogs();
    EXPECT_EQ(strokes, 1) << cycle;
    EXPECT_FALSE(watchdog.cycleEnded(strokes, daemon.clock().nowNs())) << cycle;
  }
  EXPECT_EQ(daemon.counters().faults_injected, 0U);
  EXPECT_EQ(log.text().find("fault_inject"), std::string::npos) << log.text();
}

TEST(Daemon, AStopRequestEndsTheLoopWithinOneCycle) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-stop"), false, "[daemon]\nplayback_loop = true\n"));
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  std::int64_t requested_ns = 0;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    requested_ns = exec::monotonicNowNs();
    daemon.requestStop();
  });
  EXPECT_EQ(daemon.run(), kExitOk);
  const std::int64_t stopped_ns = exec::monotonicNowNs();
  stopper.join();
  EXPECT_LT(stopped_ns - requested_ns,
            200'000'000 + 50'000'000);  // at most one period (no signal to wake it)
  EXPECT_NE(log.text().find("event=stop reason=stop_request"), std::string::npos) << log.text();
}

TEST(Daemon, InitFailuresGiveTheirExitCodes) {
  test::TempDir dir("daemon");
  LogFile log;
  {
    Daemon daemon(log.log);
    const VisnavConfig missing = test::configFromText(
        dir, "[camera]\ndriver = \"replay\"\ndevice = \"no-such-sequence\"\n[telemetry]\nenabled = false\n");
    EXPECT_EQ(daemon.init(missing, {}), kExitInit);
  }
  {
    Daemon daemon(log.log);
    const VisnavConfig bad_model = test::configFromText(
        dir, "[camera]\ndriver = \"synthetic\"\ndevice = \"" + std::string(VISNAV_SOURCE_DIR) +
                 "/config/scenarios/approach_ci.toml\"\n[files]\nmodel = \"nothing.toml\"\n");
    EXPECT_EQ(daemon.init(bad_model, {}), kExitConfig);
  }
  const std::string text = log.text();
  EXPECT_NE(text.find("level=error event=init_failed stage=camera message=\"camera replay '" + dir.path() +
                      "/no-such-sequence'"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("level=error event=config_invalid message=\"" + dir.path() + "/nothing.toml"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace visnav::app
