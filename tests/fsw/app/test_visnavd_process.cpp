// visnavd as a process: exit codes, --check, the systemd notify protocol against a socket of the test (READY,
// one WATCHDOG per cycle, STOPPING), and SIGTERM/SIGINT ending the loop within one cycle.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "../telemetry/process_util.hpp"
#include "app_test_support.hpp"
#include "visnav/executive/clock.hpp"

namespace visnav::app {
namespace {

using telemetry::test::readText;
using telemetry::test::spawnProcess;
using telemetry::test::waitProcess;

/// Runs visnavd with `args` through /bin/sh so stderr lands in `log_path`. Returns the pid.
pid_t spawnDaemon(const std::string& args, const std::string& log_path) {
  return spawnProcess(
      {"/bin/sh", "-c", std::string("exec ") + VISNAV_DAEMON + " " + args + " 2> " + log_path});
}

/// Starts visnavd with `args` and its stderr on the pipe `fds` (the child gets the write end, the parent
/// keeps only the read end). Returns the pid (-1 on failure).
pid_t spawnWithStderrPipe(const int fds[2], const std::vector<std::string>& args) {
  std::vector<const char*> argv{VISNAV_DAEMON};
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], 2);
    close(fds[0]);
    close(fds[1]);
    execv(VISNAV_DAEMON, const_cast<char* const*>(argv.data()));
    _exit(127);
  }
  close(fds[1]);
  return pid;
}

int runDaemon(const std::string& args, const std::string& log_path, double timeout_s = 30.0) {
  const pid_t pid = spawnDaemon(args, log_path);
  EXPECT_GT(pid, 0);
  return waitProcess(pid, timeout_s);
}

TEST(Visnavd, ExitCodes) {
  test::TempDir dir("visnavd");
  const std::string log = dir.path() + "/stderr.txt";
  EXPECT_EQ(runDaemon("", log), 2);
  EXPECT_EQ(runDaemon("--config x.toml --cycles -3", log), 2);
  EXPECT_EQ(runDaemon("--config x.toml --bogus", log), 2);
  EXPECT_NE(readText(log).find("unknown, incomplete or out-of-range argument '--bogus'"), std::string::npos);

  const std::string typo =
      dir.write("typo.toml", "[executive]\nmajor_frame_hz = 5.0\n\n[camera]\ndrivr = \"replay\"\n");
  EXPECT_EQ(runDaemon("--config " + typo, log), 3);
  EXPECT_NE(readText(log).find("level=error event=config_invalid message=\"" + typo +
                               ":5: unknown key [camera] drivr\""),
            std::string::npos)
      << readText(log);
  EXPECT_EQ(runDaemon("--config " + dir.path() + "/none.toml", log), 3);

  const std::string no_sequence =
      dir.write("nosequence.toml",
                "[camera]\ndriver = \"replay\"\ndevice = \"missing\"\n[telemetry]\nenabled = false\n");
  EXPECT_EQ(runDaemon("--config " + no_sequence + " --check", log), 3);  // --check loads the sequence too
  EXPECT_EQ(runDaemon("--config " + no_sequence, log), 4);
  EXPECT_NE(readText(log).find("event=init_failed stage=camera"), std::string::npos) << readText(log);

  const std::string no_reader = dir.write(
      "noreader.toml", "[camera]\ndriver = \"synthetic\"\ndevice = \"" + std::string(VISNAV_SOURCE_DIR) +
                           "/config/scenarios/approach_ci.toml\"\n[telemetry]\npartition = \"nobody-" +
                           std::to_string(getpid()) + "\"\n");
  EXPECT_EQ(runDaemon("--config " + no_reader + " --wait-subscribers 1 --wait-timeout 0.5", log), 4);
  EXPECT_NE(readText(log).find("stage=telemetry message=\"fewer than 1 readers on visnav_pose"),
            std::string::npos)
      << readText(log);
  // Readers matched (a monitor is running) but its ready file never appears: bounded, exit code 4.
  const std::string monitor_out = dir.path() + "/monitor.txt";
  const pid_t monitor =
      spawnProcess({VISNAV_MONITOR, "--config", no_reader, "--duration", "20", "--no-view"}, monitor_out);
  ASSERT_GT(monitor, 0);
  EXPECT_EQ(runDaemon("--config " + no_reader + " --wait-subscribers 1 --wait-timeout 2 --wait-file " +
                          dir.path() + "/never.ready",
                      log),
            4);
  EXPECT_NE(readText(log).find("stage=telemetry message=\"no ready file " + dir.path() + "/never.ready"),
            std::string::npos)
      << readText(log);
  kill(monitor, SIGTERM);
  EXPECT_EQ(waitProcess(monitor, 10.0), 4);  // visnavd never published: nobody answered (README "Exit codes")

  for (const char* shipped : {"visnavd.toml", "visnavd-testbed.toml"})
    EXPECT_EQ(
        runDaemon(std::string("--config ") + VISNAV_SOURCE_DIR + "/config/" + shipped + " --check", log), 0)
        << shipped;
}

// `--check FILE` is `--config FILE --check`, and it loads every file the config names: a playback camera's
// sequence or scenario (and the scenario's own camera and model) with the loaders the daemon uses, so a
// config that would fail at start with exit 4 fails the check with exit 3, naming the file and the errno
// text.
TEST(Visnavd, CheckFileLoadsEveryNamedFile) {
  test::TempDir dir("visnavd_check");
  const std::string log = dir.path() + "/stderr.txt";
  const std::string scenario = std::string(VISNAV_SOURCE_DIR) + "/config/scenarios/approach_ci.toml";
  const std::string good = dir.write("good.toml", "[camera]\ndriver = \"synthetic\"\ndevice = \"" + scenario +
                                                      "\"\n[telemetry]\nenabled = false\n");
  EXPECT_EQ(runDaemon("--check " + good, log), 0) << readText(log);
  EXPECT_EQ(runDaemon("--config " + good + " --check", log), 0) << readText(log);
  EXPECT_EQ(runDaemon("--check " + good + " --cycles 1", log), 0) << readText(log);
  EXPECT_EQ(runDaemon(std::string("--check ") + VISNAV_SOURCE_DIR + "/config/visnavd.toml", log), 0)
      << readText(log);

  const std::string no_scenario = dir.write(
      "noscenario.toml",
      "[camera]\ndriver = \"synthetic\"\ndevice = \"missing.toml\"\n[telemetry]\nenabled = false\n");
  EXPECT_EQ(runDaemon("--check " + no_scenario, log), 3);
  EXPECT_NE(readText(log).find("event=config_invalid"), std::string::npos) << readText(log);
  EXPECT_NE(readText(log).find(dir.path() + "/missing.toml: cannot open: No such file or directory"),
            std::string::npos)
      << readText(log);
  EXPECT_EQ(runDaemon("--config " + no_scenario, log), 4);  // the same file at start: init failure

  // A scenario (approach_ci's) whose camera calibration does not exist.
  std::string text = readText(scenario);
  const std::string camera_line = "camera = \"../cameras/vga_6mm.toml\"";
  const std::string model_line = "model = \"../models/";
  ASSERT_NE(text.find(camera_line), std::string::npos);
  ASSERT_NE(text.find(model_line), std::string::npos);
  text.replace(text.find(camera_line), camera_line.size(), "camera = \"nocamera.toml\"");
  text.replace(text.find(model_line), model_line.size(),
               "model = \"" + std::string(VISNAV_SOURCE_DIR) + "/config/models/");
  const std::string broken_scenario = dir.write("broken_scenario.toml", text);
  const std::string broken =
      dir.write("broken.toml", "[camera]\ndriver = \"synthetic\"\ndevice = \"" + broken_scenario +
                                   "\"\n[telemetry]\nenabled = false\n");
  EXPECT_EQ(runDaemon("--check " + broken, log), 3);
  EXPECT_NE(readText(log).find(dir.path() + "/nocamera.toml: cannot open: No such file or directory"),
            std::string::npos)
      << readText(log);

  EXPECT_EQ(runDaemon("--check " + dir.path() + "/none.toml", log), 3);
  EXPECT_NE(readText(log).find("none.toml: cannot open: No such file or directory"), std::string::npos)
      << readText(log);
  EXPECT_EQ(runDaemon("--check", log), 2);  // neither FILE nor --config
}

/// systemd's end of the notify protocol.
class NotifySocket {
 public:
  NotifySocket() : m_path("/tmp/visnavd-notify-" + std::to_string(getpid())) {
    m_fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, m_path.c_str(), sizeof(address.sun_path) - 1);
    unlink(m_path.c_str());
    EXPECT_EQ(bind(m_fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
  }
  ~NotifySocket() {
    close(m_fd);
    unlink(m_path.c_str());
  }
  const std::string& path() const { return m_path; }
  /// Next message within `timeout_ms`, "" when none came.
  std::string next(int timeout_ms) {
    timeval tv{timeout_ms / 1000, (timeout_ms % 1000) * 1000};
    setsockopt(m_fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
    char buffer[512];
    const ssize_t n = recv(m_fd, buffer, sizeof(buffer), 0);
    return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string();
  }

 private:
  std::string m_path;
  int m_fd = -1;
};

TEST(Visnavd, NotifiesSystemdReadyOneWatchdogPerCycleAndStopping) {
  const std::string sequence = test::renderedApproachCi(VISNAV_APP_TEST_FRAMES);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("visnavd");
  const std::string config = dir.write(
      "notify.toml", "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                         "\"\n[daemon]\nplayback_pacing = \"as_fast_as_possible\"\nplayback_loop = true\n"
                         "[executive]\nmajor_frame_hz = 20.0\n[telemetry]\nenabled = false\n");
  NotifySocket systemd;
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  const pid_t pid =
      spawnDaemon("--config " + config + " --cycles 6 --simulated-clock", dir.path() + "/log.txt");
  unsetenv("NOTIFY_SOCKET");
  ASSERT_GT(pid, 0);
  std::vector<std::string> messages;
  for (std::string m = systemd.next(10000); !m.empty(); m = systemd.next(3000)) {
    messages.push_back(m);
    if (m == "STOPPING=1") break;
  }
  EXPECT_EQ(waitProcess(pid, 10.0), 0);
  ASSERT_GE(messages.size(), 8U) << readText(dir.path() + "/log.txt");
  EXPECT_EQ(messages.front().rfind("READY=1\nSTATUS=running, mode ", 0), 0U) << messages.front();
  EXPECT_EQ(messages.back(), "STOPPING=1");
  int watchdogs = 0;
  for (const std::string& m : messages) watchdogs += m == "WATCHDOG=1" ? 1 : 0;
  EXPECT_EQ(watchdogs, 6);  // one per cycle
  const std::string log = readText(dir.path() + "/log.txt");
  EXPECT_NE(log.find("systemd=yes"), std::string::npos) << log;
  EXPECT_NE(log.find("event=stop reason=cycle_limit cycles=6"), std::string::npos) << log;
  EXPECT_NE(log.find("watchdog_notifications="), std::string::npos) << log;
}

// Issue 14, "a hung stage must lead to the watchdog firing", from outside: visnavd as a process on the
// simulated clock, its process stage made to hang at cycle 10 by fault injection ([daemon] fault_kind =
// "hang": it blocks until SIGTERM, as a deadlocked stage would), $NOTIFY_SOCKET a socket of this test. The
// datagrams say it in order: exactly 10 WATCHDOG=1 (cycles 0-9), the STATUS= of the injected hang, then
// nothing for 2 x WatchdogSec (systemd would fire: it is never fed again), and after SIGTERM STOPPING=1
// without a WATCHDOG=1 before it. The silence is waited for in real time, but only a daemon that strokes
// while a stage hangs can fail it, however slow the machine.
TEST(Visnavd, AHungStageStopsTheWatchdogUntilSystemdWouldFire) {
  const std::string sequence = test::renderedApproachCi(VISNAV_APP_TEST_FRAMES);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("visnavd");
  const std::string config =
      dir.write("hang.toml",
                "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                    "\"\n[daemon]\nplayback_loop = true\nfault_stage = \"process\"\nfault_kind = \"hang\"\n"
                    "fault_from_cycle = 10\n[telemetry]\nenabled = false\n");
  NotifySocket systemd;
  setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
  setenv("WATCHDOG_USEC", "500000", 1);
  const std::string log_path = dir.path() + "/log.txt";
  const pid_t pid = spawnDaemon("--config " + config + " --simulated-clock --pace-ms 5", log_path);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  ASSERT_GT(pid, 0);
  std::vector<std::string> before_hang;
  std::string message = systemd.next(20000);
  for (; !message.empty() && message.rfind("STATUS=fault injection", 0) != 0; message = systemd.next(10000))
    before_hang.push_back(message);
  ASSERT_EQ(message, "STATUS=fault injection: process stage hangs") << readText(log_path);
  ASSERT_FALSE(before_hang.empty());
  EXPECT_EQ(before_hang.front().rfind("READY=1", 0), 0U) << before_hang.front();
  int watchdogs = 0;
  for (const std::string& m : before_hang) watchdogs += m == "WATCHDOG=1" ? 1 : 0;
  EXPECT_EQ(watchdogs, 10);
  // systemd's WatchdogSec is 0.5 s here: twice that without a single datagram, so it would have fired.
  EXPECT_EQ(systemd.next(1000), "") << "the daemon notified systemd while its process stage hung";
  kill(pid, SIGTERM);
  std::vector<std::string> after;
  for (message = systemd.next(5000); !message.empty(); message = systemd.next(5000)) {
    after.push_back(message);
    if (message == "STOPPING=1") break;
  }
  EXPECT_EQ(waitProcess(pid, 10.0), 0) << readText(log_path);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(after.back(), "STOPPING=1");
  for (const std::string& m : after) EXPECT_NE(m, "WATCHDOG=1");
  const std::string log = readText(log_path);
  EXPECT_NE(log.find("event=fault_injection_armed stage=process kind=hang from_cycle=10"), std::string::npos)
      << log;
  EXPECT_NE(log.find("event=fault_injected stage=process kind=hang"), std::string::npos) << log;
  EXPECT_NE(log.find("event=stop reason=stop_request cycles=11 "), std::string::npos) << log;
  EXPECT_NE(log.find(" watchdog_withheld=1 heartbeat_misses=acquire:0,process:1,publish:0,health:0 "
                     "faults_injected=1 "),
            std::string::npos)
      << log;
}

TEST(Visnavd, StopsWithinOneCycleOnSigtermAndSigint) {
  const std::string sequence = test::renderedApproachCi(VISNAV_APP_TEST_FRAMES);
  test::TempDir dir("visnavd");
  const std::string config =
      dir.write("signal.toml", "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                   "\"\n[daemon]\nplayback_loop = true\n[telemetry]\npartition = \"signal-" +
                                   std::to_string(getpid()) + "\"\n");
  for (int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    NotifySocket systemd;
    setenv("NOTIFY_SOCKET", systemd.path().c_str(), 1);
    const std::string log_path = dir.path() + "/signal" + std::to_string(signal_number) + ".txt";
    const pid_t pid = spawnDaemon("--config " + config, log_path);
    unsetenv("NOTIFY_SOCKET");
    ASSERT_GT(pid, 0);
    ASSERT_EQ(systemd.next(20000).rfind("READY=1", 0), 0U) << readText(log_path);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // a few 5 Hz cycles
    const std::int64_t sent_ns = exec::monotonicNowNs();
    kill(pid, signal_number);
    std::string message;
    for (int i = 0; i < 100 && message != "STOPPING=1"; ++i) message = systemd.next(1000);  // skip WATCHDOG=1
    EXPECT_EQ(message, "STOPPING=1");
    const std::int64_t stopped_ns = exec::monotonicNowNs();
    EXPECT_EQ(waitProcess(pid, 10.0), 0) << readText(log_path);
    EXPECT_LT(stopped_ns - sent_ns, 200'000'000) << "longer than one 5 Hz cycle";
    const std::string log = readText(log_path);
    EXPECT_NE(log.find("event=stop reason=stop_request"), std::string::npos) << log;
    EXPECT_NE(log.find(std::string(" signal=") + sigabbrev_np(signal_number) + " "), std::string::npos)
        << log;
    EXPECT_NE(log.find("event=stop_timing clock=monotonic"), std::string::npos) << log;
  }
}

TEST(Visnavd, Sigusr1LogsAStatusLineAndSigpipeIsHarmless) {
  const std::string sequence = test::renderedApproachCi(VISNAV_APP_TEST_FRAMES);
  test::TempDir dir("visnavd");
  const std::string config =
      dir.write("usr1.toml", "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                 "\"\n[daemon]\nplayback_loop = true\n[telemetry]\nenabled = false\n");
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t pid = spawnWithStderrPipe(fds, {"--config", config, "--simulated-clock", "--pace-ms", "100"});
  ASSERT_GE(pid, 0);
  // Read until the start line, then ask for a status line, then close the reader: the daemon's next lines
  // meet EPIPE, which must cost lines, not the process (SIGPIPE would end it with 141).
  std::string text;
  char buffer[4096];
  bool asked = false;
  for (int i = 0; i < 400 && text.find("event=status") == std::string::npos; ++i) {
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    if (!asked && text.find("event=start") != std::string::npos) {
      kill(pid, SIGUSR1);
      asked = true;
    }
  }
  EXPECT_NE(text.find("level=notice event=status cycles="), std::string::npos) << text;
  close(fds[0]);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a few cycles log into the closed pipe
  kill(pid, SIGTERM);
  EXPECT_EQ(waitProcess(pid, 20.0), 0);  // not 141 (SIGPIPE)
}

TEST(Visnavd, AStalledLogPipeDoesNotStopTheCycle) {
  // visnavd on the monotonic clock (60 cycles at 5 Hz) with stderr on a pipe whose reader stops for 10 s:
  // the smallest pipe buffer, already full. A cycle that wrote its log lines itself would stop at the first
  // line for those 10 s; the executive would then report a ~10 s overrun.
  const std::string sequence = test::renderedApproachCi(VISNAV_APP_TEST_FRAMES);
  test::TempDir dir("visnavd");
  const std::string config =
      dir.write("stall.toml", "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                  "\"\n[daemon]\nplayback_loop = true\n[telemetry]\nenabled = false\n");
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  fcntl(fds[1], F_SETPIPE_SZ, 4096);
  fcntl(fds[1], F_SETFL, O_NONBLOCK);
  const char fill[256] = {};
  while (write(fds[1], fill, sizeof(fill)) > 0) {
  }
  fcntl(fds[1], F_SETFL, 0);
  const pid_t pid = spawnWithStderrPipe(fds, {"--config", config, "--cycles", "60"});
  ASSERT_GE(pid, 0);
  std::this_thread::sleep_for(std::chrono::seconds(10));  // the stalled reader
  std::string text;
  char buffer[4096];
  for (;;) {  // ends at EOF: the daemon has exited and closed its stderr
    const ssize_t n = read(fds[0], buffer, sizeof(buffer));
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  const std::size_t stop = text.find("event=stop reason=cycle_limit cycles=60 ");
  ASSERT_NE(stop, std::string::npos) << text.substr(text.find_first_not_of('\0'));
  const std::string summary = text.substr(stop, text.find('\n', stop) - stop);
  const std::size_t overrun = summary.find("worst_overrun_ms=");
  ASSERT_NE(overrun, std::string::npos) << summary;
  // Blocked: ~10000 ms. Running: the cycle's own overrun, 0 unless the machine is extremely loaded.
  EXPECT_LT(std::strtod(summary.c_str() + overrun + 17, nullptr), 2000.0) << summary;
  std::printf("stalled-pipe run: %s\n", summary.c_str());
}

}  // namespace
}  // namespace visnav::app
