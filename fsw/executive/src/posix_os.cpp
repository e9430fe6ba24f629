// Every OS call of the executive: the monotonic clock, its absolute-deadline sleep, and the realtime
// settings.
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "visnav/executive/clock.hpp"
#include "visnav/executive/realtime.hpp"

namespace visnav::exec {

std::int64_t monotonicNowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

std::int64_t MonotonicClock::nowNs() { return monotonicNowNs(); }

bool MonotonicClock::sleepUntilNs(std::int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline_ns / 1000000000LL);
  ts.tv_nsec = static_cast<long>(deadline_ns % 1000000000LL);
  // Absolute deadline: a late wake-up is not carried into the next period. Returns EINTR on a signal.
  return clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == 0;
}

namespace {

void refuse(RealtimeOutcome& outcome, int error_number, const char* what, const char* how) {
  outcome.applied = false;
  outcome.error_number = error_number;
  std::snprintf(outcome.message.data(), outcome.message.size(), "%s refused: %s (%s); %s", what,
                std::strerror(error_number),
                error_number == EPERM    ? "EPERM"
                : error_number == ENOMEM ? "ENOMEM"
                                         : "errno",
                how);
}

void accept(RealtimeOutcome& outcome, const char* what) {
  outcome.applied = true;
  std::snprintf(outcome.message.data(), outcome.message.size(), "%s applied", what);
}

}  // namespace

LoadError applyRealtimeSettings(const ExecutiveParams& params, RealtimeReport& report) {
  report = RealtimeReport{};
  char what[96];
  if (params.sched_fifo_priority > 0) {
    report.scheduler.requested = true;
    std::snprintf(what, sizeof what, "SCHED_FIFO priority %d", params.sched_fifo_priority);
    sched_param sp{};
    sp.sched_priority = params.sched_fifo_priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (rc == 0) {
      accept(report.scheduler, what);
    } else {
      refuse(report.scheduler, rc, what,
             "run as root, grant CAP_SYS_NICE (setcap cap_sys_nice+ep) or raise RLIMIT_RTPRIO "
             "(systemd LimitRTPRIO=); the thread keeps SCHED_OTHER");
    }
  }
  if (params.cpu_affinity >= 0) {
    report.affinity.requested = true;
    std::snprintf(what, sizeof what, "CPU affinity to CPU %d", params.cpu_affinity);
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<std::size_t>(params.cpu_affinity), &set);
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    if (rc == 0) {
      accept(report.affinity, what);
    } else {
      refuse(report.affinity, rc, what,
             rc == EINVAL
                 ? "that CPU does not exist or is not allowed (cgroup cpuset); the thread is not pinned"
                 : "the thread is not pinned");
    }
  }
  if (params.lock_memory) {
    report.memory_lock.requested = true;
    std::snprintf(what, sizeof what, "mlockall(MCL_CURRENT | MCL_FUTURE)");
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      accept(report.memory_lock, what);
    } else {
      refuse(report.memory_lock, errno, what,
             "grant CAP_IPC_LOCK or raise RLIMIT_MEMLOCK (ulimit -l, systemd LimitMEMLOCK=infinity); memory "
             "stays pageable");
    }
  }
  if (params.timer_slack_ns > 0) {
    report.timer_slack.requested = true;
    std::snprintf(what, sizeof what, "timer slack %d ns", params.timer_slack_ns);
    if (prctl(PR_SET_TIMERSLACK, static_cast<unsigned long>(params.timer_slack_ns), 0UL, 0UL, 0UL) == 0) {
      accept(report.timer_slack, what);
    } else {
      refuse(report.timer_slack, errno, what, "sleeps keep the default slack (50 us)");
    }
  }
  if (report.allApplied() || !params.realtime_fatal) return LoadError::success();
  std::string message = "executive: realtime_fatal is set and";
  for (const RealtimeOutcome* o :
       {&report.scheduler, &report.affinity, &report.memory_lock, &report.timer_slack}) {
    if (o->requested && !o->applied) message += std::string(" ") + o->message.data() + ";";
  }
  return LoadError::failure(message);
}

}  // namespace visnav::exec
