// visnav-monitor: live view of the telemetry, CSV recording, summary at the end. See tools/monitor/README.md.
// Exit codes (README.md "Exit codes", visnav::cli): 0 done, 1 --samples not reached, 2 usage, 3 a --config
// that does not load or a --csv / --ready-file that cannot be written, 4 DDS did not start or no sample at
// all.
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/monitor/link_args.hpp"
#include "visnav/monitor/monitor.hpp"

namespace {

std::atomic<bool> g_stop{false};
void onSignal(int) { g_stop.store(true); }

void usage(std::FILE* stream) {
  std::fprintf(
      stream,
      "usage: visnav-monitor %s [--csv FILE] [--samples N] [--duration S] [--no-view]\n"
      "       [--ready-file FILE]\n"
      "       visnav-monitor --help | --version\n"
      "Live view of visnavd's DDS telemetry, CSV recording, summary at the end.\n"
      "  --csv FILE     record every sample: FILE (pose, visnav-eval columns), FILE's stem +\n"
      "                 _far_range.csv and _health.csv\n"
      "  --samples N    stop after N PoseEstimate samples\n"
      "  --duration S   stop after S seconds\n"
      "  --ready-file FILE  create FILE once every reader has matched a writer (a publisher that\n"
      "                 waits for it loses nothing: visnavd --wait-file)\n"
      "  exit code: 0 done, 1 --samples not reached, 2 usage, 3 a config that does not load or a file\n"
      "  that cannot be written, 4 DDS did not start or no sample at all\n",
      visnav::monitor::kLinkUsage);
}

}  // namespace

int main(int argc, char** argv) {
  visnav::monitor::MonitorOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    visnav::LoadError error;
    int error_code = visnav::cli::kExitUsage;
    double number = 0.0;
    long long count = 0;
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-monitor", usage); code >= 0)
      return code;
    if (visnav::monitor::parseLinkArgument(argc, argv, i, options.link, error, error_code)) {
      if (!error.ok) {
        std::fprintf(stderr, "visnav-monitor: %s\n", error.message.c_str());
        return error_code;
      }
    } else if (arg == "--csv" && has_value) {
      options.csv_path = argv[++i];
    } else if (arg == "--samples" && has_value &&
               visnav::cli::parseInteger(argv[i + 1], 0, std::numeric_limits<long long>::max(), count)) {
      options.stop_after_pose_samples = static_cast<std::uint64_t>(count);
      ++i;
    } else if (arg == "--duration" && has_value && visnav::cli::parseNumber(argv[i + 1], number) &&
               number >= 0.0) {
      options.duration_s = number;
      ++i;
    } else if (arg == "--ready-file" && has_value) {
      options.ready_file = argv[++i];
    } else if (arg == "--no-view") {
      options.live_view = false;
    } else {
      std::fprintf(stderr, "visnav-monitor: unknown or incomplete argument '%s'\n", arg.c_str());
      usage(stderr);
      return visnav::cli::kExitUsage;
    }
  }
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  visnav::monitor::MonitorResult result;
  const visnav::LoadError error = visnav::monitor::runMonitor(options, g_stop, result, stdout);
  if (!error.ok) {
    std::fprintf(stderr, "visnav-monitor: %s\n", error.message.c_str());
    return result.link_failed ? visnav::cli::kExitStartup : visnav::cli::kExitInvalidInput;
  }
  if (result.pose.samples() + result.far_range.samples() + result.health.samples() == 0) {
    // Silence is a misconfiguration far more often than an idle flight program: say where it listened.
    std::fprintf(stderr,
                 "visnav-monitor: no sample on any topic in %.1f s (domain %d, partition '%s'): is visnavd "
                 "running, and do CYCLONEDDS_URI, --domain and --partition match its [telemetry]?\n",
                 result.elapsed_s, options.link.domain_id, options.link.partitionName());
    return visnav::cli::kExitStartup;  // the other side never answered (README "Exit codes")
  }
  return options.stop_after_pose_samples > 0 && !result.reached_sample_limit && !g_stop.load()
             ? visnav::cli::kExitFailed
             : visnav::cli::kExitOk;
}
