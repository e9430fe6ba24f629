// The systemd watchdog means health (issue 14): a stage that keeps failing, or fails every cycle from an
// injected fault, withholds WATCHDOG=1 until systemd's timer would fire; without the fault every cycle is
// fed. A real datagram socket stands in for systemd's notify socket; the daemon runs on the simulated clock.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "daemon_test_support.hpp"
#include "visnav/replay/replay_camera.hpp"

namespace visnav::app {
namespace {

using test::kFrames;
using test::LogFile;
using test::partitionFor;
using test::replayConfig;

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

/// init() on the simulated clock as systemd would start the daemon: NOTIFY_SOCKET and WATCHDOG_USEC set
/// for the call only (the notifier reads them there).
int initUnderSystemd(Daemon& daemon, const VisnavConfig& config, const NotifySocket& systemd,
                     const char* watchdog_usec) {
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  setenv("WATCHDOG_USEC", watchdog_usec, 1);
  DaemonOptions options;
  options.simulated_clock = true;
  const int init = daemon.init(config, options);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  return init;
}

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
  LogFile log;
  Daemon daemon(log.log);
  ASSERT_EQ(initUnderSystemd(daemon, config, systemd, "2000000"), kExitOk) << log.text();
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
  LogFile log;
  Daemon daemon(log.log);
  ASSERT_EQ(initUnderSystemd(daemon, config, systemd, "1000000"), kExitOk) << log.text();
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
  LogFile log;
  Daemon daemon(log.log);
  ASSERT_EQ(initUnderSystemd(daemon, config, systemd, "1000000"), kExitOk) << log.text();
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

}  // namespace
}  // namespace visnav::app
