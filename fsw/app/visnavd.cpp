// visnavd: the flight program. Validates the whole config, starts camera, pipeline, telemetry and the cyclic
// executive, runs until SIGTERM/SIGINT (or --cycles, or the end of a playback), logs a stop summary.
//   visnavd --config FILE [--cycles N] [--simulated-clock] [--pace-ms X] [--wait-subscribers N]
//           [--wait-timeout S] [--check]
//   visnavd --check FILE    (the same as --config FILE --check)
//   visnavd --help | --version
// Exit codes: fsw/app/README.md (0 ok, 2 usage, 3 config invalid, 4 init failure, 5 realtime refused).
#include <signal.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "visnav/app/camera_factory.hpp"
#include "visnav/app/daemon.hpp"
#include "visnav/version.hpp"

namespace {

std::atomic<visnav::app::Daemon*> g_daemon{nullptr};

// SIGTERM, SIGINT and SIGHUP stop the loop after the current cycle (SIGHUP: a clean stop, not a reload; a
// changed config takes effect at the next start, after `visnavd --check`). SIGUSR1 asks for one status line.
void onStopSignal(int signal_number) {
  if (visnav::app::Daemon* daemon = g_daemon.load()) daemon->requestStop(signal_number);
}

void onStatusSignal(int) {
  if (visnav::app::Daemon* daemon = g_daemon.load()) daemon->requestStatus();
}

void usage(std::FILE* stream) {
  std::fputs(
      "usage: visnavd --config FILE [--cycles N] [--simulated-clock] [--pace-ms X] [--wait-subscribers N]\n"
      "               [--wait-timeout S] [--wait-file FILE] [--check]\n"
      "       visnavd --check FILE | --help | --version\n"
      "The visnav flight program: camera, navigation pipeline and DDS telemetry on a cyclic executive.\n"
      "  --config FILE         run configuration (every table; reference: config/PARAMETERS.md)\n"
      "  --cycles N            stop after N cycles (default: run until SIGTERM/SIGINT)\n"
      "  --simulated-clock     simulated time from the first frame's timestamp; a replay or synthetic "
      "camera\n"
      "                        plays as fast as possible (deterministic: same numbers as visnav-replay)\n"
      "  --pace-ms X           with --simulated-clock: pause X ms of real time per cycle (ground tools keep "
      "up)\n"
      "  --wait-subscribers N  before the first cycle, wait for N readers on each flight topic\n"
      "  --wait-timeout S      longest wait for them (default 10 s; exit code 4 when they do not come)\n"
      "  --wait-file FILE      then wait (same bound) for FILE, a ground tool's --ready-file, instead of a\n"
      "                        0.5 s pause: its readers have matched too, nothing is lost\n"
      "  --check [FILE]        validate the config (FILE: the same as --config FILE) and every file it\n"
      "                        names (calibration, model, a replay sequence or synthetic scenario), then\n"
      "                        exit (0 valid, 3 invalid)\n"
      "  --help, --version     this text; the version\n"
      "  exit codes: 0 ok, 2 usage, 3 config invalid, 4 camera/pipeline/DDS init failure, 5 realtime "
      "refused\n",
      stream);
}

bool parseNumber(const char* text, double min, double max, double& out) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(value >= min && value <= max)) return false;
  out = value;
  return true;
}

// --check: what Daemon::init loads before it touches hardware or DDS, and nothing more. A playback camera
// (replay sequence, synthetic scenario) is opened with its own loader, so a missing or broken one fails here
// (exit 3) and not at start (exit 4); a live camera is not opened: the device may be absent until flight.
int checkConfig(const visnav::app::VisnavConfig& config, visnav::app::EventLog& log) {
  using namespace visnav::app;
  if (const char* problem = runProblem(config)) {
    log.event(LogLevel::kError, "config_invalid", "message=\"%s: %s\"", config.path.c_str(), problem);
    return kExitConfig;
  }
  visnav::CameraIntrinsics intrinsics;
  visnav::PolygonModel model;
  bool have_camera = false;
  bool have_model = false;
  if (visnav::LoadError e = loadConfiguredFiles(config, intrinsics, have_camera, model, have_model); !e.ok) {
    log.event(LogLevel::kError, "config_invalid", "message=\"%s\"", e.message.c_str());
    return kExitConfig;
  }
  OpenedCamera camera;
  if (visnav::LoadError e = openCamera(config, true, camera); !e.ok) {
    log.event(LogLevel::kError, "config_invalid", "message=\"%s: %s\"", config.path.c_str(),
              e.message.c_str());
    return kExitConfig;
  }
  const bool size_differs = camera.playback && have_camera &&
                            (intrinsics.width_px != camera.intrinsics.width_px ||
                             intrinsics.height_px != camera.intrinsics.height_px);
  if (camera.source) camera.source->close();
  if (size_differs) {
    log.event(LogLevel::kError, "config_invalid",
              "message=\"[files] camera %s is %dx%d but the camera delivers %dx%d frames\"",
              config.files.camera.c_str(), intrinsics.width_px, intrinsics.height_px,
              camera.intrinsics.width_px, camera.intrinsics.height_px);
    return kExitConfig;
  }
  std::printf("visnavd: %s is valid\n", config.path.c_str());
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace visnav::app;
  std::string config_path;
  DaemonOptions options;
  bool check_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    double number = 0.0;
    if (arg == "--config" && has_value) {
      config_path = argv[++i];
    } else if (arg == "--cycles" && has_value && parseNumber(argv[++i], 1.0, 1e15, number)) {
      options.max_cycles = static_cast<std::uint64_t>(number);
    } else if (arg == "--simulated-clock") {
      options.simulated_clock = true;
    } else if (arg == "--pace-ms" && has_value && parseNumber(argv[++i], 0.0, 10000.0, number)) {
      options.pace_ms = number;
    } else if (arg == "--wait-subscribers" && has_value && parseNumber(argv[++i], 0.0, 1000.0, number)) {
      options.wait_subscribers = static_cast<int>(number);
    } else if (arg == "--wait-timeout" && has_value && parseNumber(argv[++i], 0.0, 3600.0, number)) {
      options.wait_timeout_s = number;
    } else if (arg == "--wait-file" && has_value) {
      options.wait_file = argv[++i];
    } else if (arg == "--check") {
      check_only = true;
      if (has_value && argv[i + 1][0] != '-') config_path = argv[++i];  // --check FILE
    } else if (arg == "--help" || arg == "-h") {
      usage(stdout);
      return kExitOk;
    } else if (arg == "--version") {
      std::printf("visnavd %s\n", visnav::kVersion);
      return kExitOk;
    } else {
      std::fprintf(stderr, "visnavd: unknown, incomplete or out-of-range argument '%s'\n", arg.c_str());
      usage(stderr);
      return kExitUsage;
    }
  }
  if (config_path.empty()) {
    usage(stderr);
    return kExitUsage;
  }

  // A reader that goes away (`visnavd 2>&1 | head`) must not kill the daemon: write() returns EPIPE and the
  // line is counted as dropped.
  signal(SIGPIPE, SIG_IGN);
  EventLog log;
  VisnavConfig config;
  if (visnav::LoadError e = loadVisnavConfig(config_path, config); !e.ok) {
    log.event(LogLevel::kError, "config_invalid", "message=\"%s\"", e.message.c_str());
    return kExitConfig;
  }
  if (check_only) return checkConfig(config, log);

  // SIGTERM/SIGINT stay blocked while DDS starts its threads (they inherit the mask), so the signal reaches
  // this thread and interrupts the executive's sleep: the loop ends at once, or after the running cycle.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGHUP);
  sigaddset(&stop_signals, SIGUSR1);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  struct sigaction action {};
  action.sa_handler = &onStopSignal;  // no SA_RESTART: clock_nanosleep returns EINTR
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);
  struct sigaction status_action {};
  status_action.sa_handler = &onStatusSignal;
  status_action.sa_flags = SA_RESTART;
  sigemptyset(&status_action.sa_mask);
  sigaction(SIGUSR1, &status_action, nullptr);
  // From here on a stalled stderr (journald, a pipe nobody reads) must not block the cycle: lines go through
  // the log's ring and its drain thread (started with the stop signals blocked, like the DDS threads).
  if (!log.startAsync())
    log.event(LogLevel::kWarning, "log_sync",
              "message=\"no drain thread: log lines are written by the cycle\"");

  auto daemon =
      std::make_unique<Daemon>(log);  // large (executive statistics, pipeline buffers): heap, at init
  if (const int code = daemon->init(config, options); code != kExitOk) return code;
  g_daemon.store(daemon.get());
  pthread_sigmask(SIG_UNBLOCK, &stop_signals, nullptr);  // a signal that came during init stops the loop now
  const int code = daemon->run();
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  g_daemon.store(nullptr);
  return code;
}
