// The real clock and the OS settings (src/posix_os.cpp): absolute sleeps never wake early, a signal ends a
// sleeping loop at once, a stop from another thread within one period, and the realtime settings report
// refusals with a message (an unprivileged child process gets EPERM / ENOMEM), fatal only when asked.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <thread>

#include "visnav/executive/executive.hpp"
#include "visnav/executive/realtime.hpp"

namespace visnav::exec {
namespace {

constexpr std::int64_t kNsPerMs = 1000000;

TEST(MonotonicClock, AbsoluteSleepNeverReturnsBeforeTheDeadline) {
  MonotonicClock clock;
  for (int i = 0; i < 20; ++i) {
    const std::int64_t deadline = clock.nowNs() + 300000;  // 0.3 ms
    while (!clock.sleepUntilNs(deadline)) {
    }
    EXPECT_GE(clock.nowNs(), deadline);
  }
  EXPECT_TRUE(clock.sleepUntilNs(clock.nowNs() - kNsPerMs));  // a past deadline returns at once
}

TEST(MonotonicClock, ExecutiveKeepsAbsolutePhaseAt100Hz) {
  MonotonicClock clock;
  Executive executive;
  ExecutiveParams params;
  params.major_frame_hz = 100.0;
  ASSERT_TRUE(executive.init(params, clock).ok);
  std::int64_t releases[20] = {};
  struct Log final : CycleTask {
    std::int64_t* out = nullptr;
    Status runCycle(const CycleInfo& info) override {
      out[info.minor_frame % 20U] = info.release_ns;
      return Status::kOk;
    }
  } log;
  log.out = releases;
  TaskId log_task;
  ASSERT_TRUE(executive.addTask(log_task, "log", log).ok);
  EXPECT_EQ(executive.run(20), StopReason::kCycleLimit);
  // Functional checks only (timing figures come from visnav-jitter): no release before its ideal time.
  EXPECT_GE(executive.releaseJitter().minNs(), 0);
  for (int k = 1; k < 20 && executive.counters().slips == 0U; ++k)
    EXPECT_EQ(releases[k] - releases[k - 1], 10 * kNsPerMs);
}

std::atomic<Executive*> g_target{nullptr};
extern "C" void onSignal(int) { g_target.load()->requestStop(); }

TEST(MonotonicClock, SignalInterruptsTheSleepAndStopsTheLoop) {
  MonotonicClock clock;
  Executive executive;
  ExecutiveParams params;
  params.major_frame_hz = 0.5;  // a 2 s period: only the interrupted sleep can end it early
  ASSERT_TRUE(executive.init(params, clock).ok);
  g_target = &executive;
  struct sigaction action {};
  action.sa_handler = onSignal;  // no SA_RESTART: clock_nanosleep returns EINTR
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGUSR2, &action, &previous), 0);
  const pthread_t loop_thread = pthread_self();
  std::thread sender([loop_thread] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    pthread_kill(loop_thread, SIGUSR2);
  });
  const std::int64_t start = clock.nowNs();
  const StopReason reason = executive.run(0);
  const std::int64_t elapsed = clock.nowNs() - start;
  sender.join();
  sigaction(SIGUSR2, &previous, nullptr);
  EXPECT_EQ(reason, StopReason::kStopRequested);
  EXPECT_EQ(executive.counters().cycles, 1U);  // the first frame ran at once, the second never came
  EXPECT_LT(elapsed, 1500 * kNsPerMs);
}

TEST(MonotonicClock, StopFromAnotherThreadWithinOnePeriod) {
  MonotonicClock clock;
  Executive executive;
  ExecutiveParams params;
  params.major_frame_hz = 5.0;
  ASSERT_TRUE(executive.init(params, clock).ok);
  StopReason reason = StopReason::kNotRun;
  std::int64_t stopped_at = 0;
  std::thread loop([&] {
    reason = executive.run(0);
    stopped_at = clock.nowNs();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::int64_t requested_at = clock.nowNs();
  executive.requestStop();
  loop.join();
  EXPECT_EQ(reason, StopReason::kStopRequested);
  EXPECT_LE(stopped_at - requested_at, 200 * kNsPerMs + 100 * kNsPerMs);  // one period plus scheduling slack
}

TEST(Realtime, NothingRequestedIsAppliedTrivially) {
  RealtimeReport report;
  EXPECT_TRUE(applyRealtimeSettings(ExecutiveParams{}, report).ok);
  EXPECT_TRUE(report.allApplied());
  EXPECT_FALSE(report.scheduler.requested);
  EXPECT_EQ(report.scheduler.message[0], '\0');
}

TEST(Realtime, MissingCpuIsReportedAndFatalOnlyWhenAsked) {
  ExecutiveParams params;
  params.cpu_affinity = 1023;  // no such CPU here
  RealtimeReport report;
  EXPECT_TRUE(applyRealtimeSettings(params, report).ok);
  EXPECT_TRUE(report.affinity.requested);
  EXPECT_FALSE(report.affinity.applied);
  EXPECT_EQ(report.affinity.error_number, EINVAL);
  EXPECT_NE(std::strstr(report.affinity.message.data(), "CPU 1023"), nullptr)
      << report.affinity.message.data();
  params.realtime_fatal = true;
  const LoadError fatal = applyRealtimeSettings(params, report);
  EXPECT_FALSE(fatal.ok);
  EXPECT_NE(fatal.message.find("CPU 1023"), std::string::npos) << fatal.message;
}

// Runs applyRealtimeSettings in a child process (the settings must not change the test process) as an
// unprivileged user, and returns "<sched errno> <mlock errno> <has sched hint> <has mlock hint>".
std::string refusalsInUnprivilegedChild() {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    if (getuid() == 0 && setuid(65534) != 0) _exit(3);  // "nobody": no CAP_SYS_NICE, no CAP_IPC_LOCK
    const rlimit no_memlock{0, 0};                      // whatever the host's default, nothing may be locked
    if (setrlimit(RLIMIT_MEMLOCK, &no_memlock) != 0) _exit(5);
    ExecutiveParams params;
    params.sched_fifo_priority = 10;
    params.lock_memory = true;
    RealtimeReport report;
    const LoadError e = applyRealtimeSettings(params, report);
    char line[128];
    const int n = std::snprintf(
        line, sizeof line, "%d %d %d %d %d", report.scheduler.error_number, report.memory_lock.error_number,
        std::strstr(report.scheduler.message.data(), "CAP_SYS_NICE") != nullptr,
        std::strstr(report.memory_lock.message.data(), "RLIMIT_MEMLOCK") != nullptr, e.ok);
    if (write(fds[1], line, static_cast<std::size_t>(n)) != n) _exit(4);
    _exit(0);
  }
  close(fds[1]);
  char buffer[128] = {};
  const ssize_t n = read(fds[0], buffer, sizeof buffer - 1);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : "child failed";
}

TEST(Realtime, UnprivilegedRefusalsCarryTheReasonAndTheFix) {
  struct rlimit rtprio {};
  getrlimit(RLIMIT_RTPRIO, &rtprio);
  if (rtprio.rlim_cur >= 10) GTEST_SKIP() << "RLIMIT_RTPRIO permits SCHED_FIFO 10 without privileges here";
  int sched_errno = -1;
  int mlock_errno = -1;
  int sched_hint = 0;
  int mlock_hint = 0;
  int ok = 0;
  const std::string result = refusalsInUnprivilegedChild();
  ASSERT_EQ(std::sscanf(result.c_str(), "%d %d %d %d %d", &sched_errno, &mlock_errno, &sched_hint,
                        &mlock_hint, &ok),
            5)
      << result;
  EXPECT_EQ(sched_errno, EPERM);
  EXPECT_EQ(sched_hint, 1);
#if !defined(__SANITIZE_ADDRESS__)  // ASan intercepts mlockall and always returns 0
  EXPECT_TRUE(mlock_errno == ENOMEM || mlock_errno == EPERM) << mlock_errno;
  EXPECT_EQ(mlock_hint, 1);
#endif
  EXPECT_EQ(ok, 1);  // realtime_fatal is false: reported, not fatal
}

}  // namespace
}  // namespace visnav::exec
