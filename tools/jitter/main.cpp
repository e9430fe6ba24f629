// visnav-jitter: runs the cyclic executive on the real clock (CLOCK_MONOTONIC, absolute-deadline sleeps) for
// N cycles with one task (empty, or busy-waiting a given time) and prints the release jitter (wake time
// minus ideal release) p50/p99/max, the task time and the slips. Ctrl-C ends it early with the figures so
// far. Usage: fsw/executive/README.md. Exit codes (README.md "Exit codes", visnav::cli): 0 done, 1 p99 above
// --max-p99-us, 2 usage, 3 a --config that does not load (or executive parameters it refuses), 5 a refused
// realtime setting with --fatal (or realtime_fatal in the config).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/executive/executive.hpp"
#include "visnav/executive/realtime.hpp"
#include "visnav/io/config_io.hpp"

namespace {

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitRealtime;
using visnav::cli::kExitUsage;
using visnav::exec::DurationStats;

visnav::exec::Executive* g_executive = nullptr;
extern "C" void onSignal(int) {
  if (g_executive != nullptr) g_executive->requestStop();
}

struct BusyTask final : visnav::exec::CycleTask {
  std::int64_t busy_ns = 0;
  visnav::Status runCycle(const visnav::exec::CycleInfo&) override {
    const std::int64_t until = visnav::exec::monotonicNowNs() + busy_ns;
    while (visnav::exec::monotonicNowNs() < until) {
    }
    return visnav::Status::kOk;
  }
};

void usage(std::FILE* stream) {
  std::fputs(
      "usage: visnav-jitter [--cycles N] [--hz F] [--busy-us U] [--config FILE] [--priority P] [--cpu C]\n"
      "                     [--lock-memory] [--slack-ns N] [--fatal] [--max-p99-us X]\n"
      "       visnav-jitter --help | --version\n"
      "Runs the cyclic executive on the real clock and prints the release jitter (fsw/executive/README.md).\n"
      "  --cycles N      cycles to run (default 300: one minute at 5 Hz)\n"
      "  --hz F          major frame rate (default: the config's, else 5 Hz)\n"
      "  --busy-us U     the task busy-waits U us per cycle (default 0: empty task)\n"
      "  --config FILE   read the [executive] table of a visnav config (other tables are ignored)\n"
      "  --priority P    SCHED_FIFO priority   --cpu C  pin to CPU C   --lock-memory  mlockall\n"
      "  --slack-ns N    timer slack of the loop thread (default 1000; 0: the OS default, 50 us)\n"
      "  --fatal         a refused realtime setting is an error (exit 5)\n"
      "  --max-p99-us X  exit 1 when the jitter p99 exceeds X us\n"
      "  exit code: 0 done, 1 p99 above the limit, 2 usage, 3 a config that does not load or is invalid,\n"
      "  5 a realtime setting refused with --fatal\n",
      stream);
}

// --cycles, --priority and --cpu are integers ("1.5" is refused, not truncated); the rest are numbers.
bool parseValue(const std::string& arg, const char* text, double& out) {
  if (arg == "--cycles" || arg == "--priority" || arg == "--cpu") {
    long long n = 0;
    // Within +-2^53 every integer is exact as a double; the range checks below come before any cast.
    if (!visnav::cli::parseInteger(text, -(1LL << 53), 1LL << 53, n)) return false;
    out = static_cast<double>(n);
    return true;
  }
  return visnav::cli::parseNumber(text, out);
}

void printStats(const char* what, const DurationStats& s) {
  std::printf("%-22s p50 %9.1f  p99 %9.1f  max %9.1f  mean %9.1f  min %9.1f  (n %llu)\n", what,
              static_cast<double>(s.quantileNs(0.5)) * 1e-3, static_cast<double>(s.quantileNs(0.99)) * 1e-3,
              static_cast<double>(s.maxNs()) * 1e-3, s.meanNs() * 1e-3, static_cast<double>(s.minNs()) * 1e-3,
              static_cast<unsigned long long>(s.count()));
}

}  // namespace

int main(int argc, char** argv) {
  visnav::exec::ExecutiveParams params;
  double cycles = 300.0;
  double hz = -1.0;
  double busy_us = 0.0;
  double max_p99_us = -1.0;
  double slack_ns = -1.0;
  std::string config_path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    double value = 0.0;
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-jitter", usage); code >= 0) return code;
    if (arg == "--lock-memory") {
      params.lock_memory = true;
    } else if (arg == "--fatal") {
      params.realtime_fatal = true;
    } else if (arg == "--config" && has_value) {
      config_path = argv[++i];
    } else if (has_value && parseValue(arg, argv[i + 1], value)) {
      ++i;
      if (arg == "--cycles" && value >= 1.0) {
        cycles = value;
      } else if (arg == "--hz" && value >= 0.1 && value <= 1000.0) {
        hz = value;
      } else if (arg == "--busy-us" && value >= 0.0) {
        busy_us = value;
      } else if (arg == "--priority" && value >= 0.0 && value <= 99.0) {
        params.sched_fifo_priority = static_cast<int>(value);
      } else if (arg == "--cpu" && value >= -1.0 && value <= 1023.0) {
        params.cpu_affinity = static_cast<int>(value);
      } else if (arg == "--slack-ns" && value >= 0.0 && value <= 1e6) {
        slack_ns = value;
      } else if (arg == "--max-p99-us" && value > 0.0) {
        max_p99_us = value;
      } else {
        std::fprintf(stderr, "visnav-jitter: bad value for %s\n", arg.c_str());
        usage(stderr);
        return kExitUsage;
      }
    } else {
      std::fprintf(stderr, "visnav-jitter: bad argument '%s'\n", arg.c_str());
      usage(stderr);
      return kExitUsage;
    }
  }
  if (!config_path.empty()) {
    visnav::exec::ExecutiveParams from_file;
    visnav::io::ConfigFile config;
    visnav::LoadError e = config.open(config_path);
    if (e.ok) e = config.apply(from_file);
    if (!e.ok) {
      std::fprintf(stderr, "visnav-jitter: %s\n", e.message.c_str());
      return kExitInvalidInput;
    }
    // Command-line realtime flags add to what the file asks for.
    if (params.sched_fifo_priority == 0) params.sched_fifo_priority = from_file.sched_fifo_priority;
    if (params.cpu_affinity < 0) params.cpu_affinity = from_file.cpu_affinity;
    params.lock_memory = params.lock_memory || from_file.lock_memory;
    params.realtime_fatal = params.realtime_fatal || from_file.realtime_fatal;
    params.timer_slack_ns = from_file.timer_slack_ns;
    params.major_frame_hz = from_file.major_frame_hz;
    params.minor_frames_per_major = from_file.minor_frames_per_major;
  }
  if (slack_ns >= 0.0) params.timer_slack_ns = static_cast<int>(slack_ns);
  if (hz > 0.0) {
    params.major_frame_hz = hz;
    params.minor_frames_per_major = 1;
  }

  visnav::exec::RealtimeReport report;
  const visnav::LoadError rt = visnav::exec::applyRealtimeSettings(params, report);
  for (const visnav::exec::RealtimeOutcome* o :
       {&report.scheduler, &report.affinity, &report.memory_lock, &report.timer_slack}) {
    if (o->requested) std::fprintf(stderr, "visnav-jitter: %s\n", o->message.data());
  }
  if (!rt.ok) {  // a refused setting with realtime_fatal, as visnavd's exit 5
    std::fprintf(stderr, "visnav-jitter: %s\n", rt.message.c_str());
    return kExitRealtime;
  }

  visnav::exec::MonotonicClock clock;
  // Static: the signal handler reaches it through g_executive, so it must outlive every path out of main.
  static visnav::exec::Executive executive;
  BusyTask task;
  task.busy_ns = static_cast<std::int64_t>(busy_us * 1e3);
  visnav::exec::TaskId busy_task;
  visnav::LoadError e = executive.init(params, clock);
  if (e.ok) e = executive.addTask(busy_task, "busy", task);
  if (!e.ok) {  // the command line's values are range-checked above: what is refused here came from --config
    std::fprintf(stderr, "visnav-jitter: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  g_executive = &executive;
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  executive.run(static_cast<std::uint64_t>(cycles));

  const DurationStats& jitter = executive.releaseJitter();
  std::printf(
      "visnav-jitter: %llu cycles at %.3f Hz (minor period %.1f us), task busy %.1f us, timer slack %d ns, "
      "%s%s%s\n",
      static_cast<unsigned long long>(executive.counters().cycles),
      params.major_frame_hz * params.minor_frames_per_major,
      static_cast<double>(executive.minorPeriodNs()) * 1e-3, busy_us,
      report.timer_slack.applied ? params.timer_slack_ns : 50000,
      report.scheduler.applied ? "SCHED_FIFO" : "SCHED_OTHER", report.affinity.applied ? ", pinned" : "",
      report.memory_lock.applied ? ", memory locked" : "");
  std::printf("all figures in us\n");
  printStats("release jitter", jitter);
  printStats("task execution", executive.taskStats(busy_task).exec);
  printStats("cycle busy", executive.cycleBusy());
  std::printf("slips %llu, releases skipped %llu, worst overrun %.1f us\n",
              static_cast<unsigned long long>(executive.counters().slips),
              static_cast<unsigned long long>(executive.counters().releases_skipped),
              static_cast<double>(executive.counters().worst_overrun_ns) * 1e-3);
  if (max_p99_us > 0.0 && static_cast<double>(jitter.quantileNs(0.99)) * 1e-3 > max_p99_us) {
    std::printf("visnav-jitter: p99 above the %.1f us limit\n", max_p99_us);
    return kExitFailed;
  }
  return kExitOk;
}
