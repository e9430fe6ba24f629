// visnav-command: sends one ModeCommand and waits (bounded) for its acknowledgment in Health.
//   visnav-command force-far-range|reacquire|standby|resume [--id N] [--timeout S] [--config FILE] ...
// Exit code: 0 accepted, 1 rejected, 2 usage, 3 a --config that does not load, 4 DDS did not start, the write
// failed, or timeout (no flight software listening, or no acknowledgment in time).
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/monitor/link_args.hpp"
#include "visnav/telemetry/ground_link.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace {

using visnav::telemetry::GroundLink;

// The shared table (README "Exit codes"): a timeout is "the other side never answered".
constexpr int kExitAccepted = visnav::cli::kExitOk;
constexpr int kExitRejected = visnav::cli::kExitFailed;
constexpr int kExitUsage = visnav::cli::kExitUsage;
constexpr int kExitTimeout = visnav::cli::kExitStartup;
constexpr int kExitNoLink = visnav::cli::kExitStartup;  // DDS did not start, or refused the write

void usage(std::FILE* stream) {
  std::fprintf(
      stream,
      "usage: visnav-command force-far-range|reacquire|standby|resume [--id N] [--timeout S] %s\n"
      "       visnav-command --help | --version\n"
      "Sends one mode command to visnavd over DDS and waits for its acknowledgment.\n"
      "  --id N       command id echoed in the acknowledgment (1..4294967295; default: from time and pid)\n"
      "  --timeout S  longest wait for the flight software and its acknowledgment (default 5)\n"
      "  exit code: 0 accepted, 1 rejected, 2 usage, 3 a config that does not load, 4 DDS did not start\n"
      "  or timeout\n",
      visnav::monitor::kLinkUsage);
}

bool parseKind(const std::string& text, std::uint8_t& kind) {
  const char* names[] = {"force-far-range", "reacquire", "standby", "resume"};
  for (std::uint8_t k = 0; k < 4; ++k) {
    if (text == names[k]) {
      kind = k;
      return true;
    }
  }
  return false;
}

std::uint32_t defaultCommandId() {
  const auto mixed = static_cast<std::uint32_t>(visnav::telemetry::monotonicNowNs() / 1000) ^
                     (static_cast<std::uint32_t>(getpid()) << 16);
  return mixed == 0 ? 1U : mixed;
}

/// Waits for a Health sample acknowledging `command_id`; fills `ack`. False on timeout.
bool waitForAck(GroundLink& link, std::uint32_t command_id, std::int64_t deadline_ns,
                visnav_CommandAck& ack) {
  std::array<visnav_Health, visnav::telemetry::kMaxTakeBatch> samples{};
  std::array<dds_sample_info_t, visnav::telemetry::kMaxTakeBatch> infos{};
  while (true) {  // bounded by deadline_ns
    const std::int64_t left_ns = deadline_ns - visnav::telemetry::monotonicNowNs();
    if (left_ns <= 0) return false;
    link.waitForData(left_ns);
    const int n = link.takeHealth(samples.data(), infos.data(), visnav::telemetry::kMaxTakeBatch);
    for (int i = 0; i < n; ++i) {
      if (infos[i].valid_data && samples[i].last_command.command_id == command_id) {
        ack = samples[i].last_command;
        return true;
      }
    }
    // Pose and far-range samples also wake the waitset: drop them, only Health matters here.
    visnav_PoseEstimate pose{};
    dds_sample_info_t info{};
    while (link.takePose(&pose, &info, 1) > 0) {
    }
    visnav_FarRangeEstimate far{};
    while (link.takeFarRange(&far, &info, 1) > 0) {
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  visnav::telemetry::TelemetryParams link_params;
  std::uint8_t kind = 0;
  bool have_kind = false;
  std::uint32_t command_id = 0;
  double timeout_s = 5.0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    visnav::LoadError error;
    int error_code = kExitUsage;
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-command", usage); code >= 0)
      return code;
    if (visnav::monitor::parseLinkArgument(argc, argv, i, link_params, error, error_code)) {
      if (!error.ok) {
        std::fprintf(stderr, "visnav-command: %s\n", error.message.c_str());
        return error_code;
      }
    } else if (arg == "--id" && has_value) {
      long long id = 0;
      if (!visnav::cli::parseInteger(argv[++i], 1, 0xFFFFFFFFLL, id)) {
        std::fprintf(stderr, "visnav-command: --id wants 1..4294967295\n");
        return kExitUsage;
      }
      command_id = static_cast<std::uint32_t>(id);
    } else if (arg == "--timeout" && has_value) {
      if (!visnav::cli::parseNumber(argv[++i], timeout_s) || !(timeout_s > 0.0 && timeout_s <= 3600.0)) {
        std::fprintf(stderr, "visnav-command: --timeout wants seconds in (0, 3600]\n");
        return kExitUsage;
      }
    } else if (!have_kind && parseKind(arg, kind)) {
      have_kind = true;
    } else {
      std::fprintf(stderr, "visnav-command: unknown or incomplete argument '%s'\n", arg.c_str());
      usage(stderr);
      return kExitUsage;
    }
  }
  if (!have_kind) {
    usage(stderr);
    return kExitUsage;
  }
  if (command_id == 0) command_id = defaultCommandId();

  GroundLink link;
  if (visnav::LoadError e = link.init(link_params, 16); !e.ok) {
    std::fprintf(stderr, "visnav-command: %s\n", e.message.c_str());
    return kExitNoLink;
  }
  const auto timeout_ns = static_cast<std::int64_t>(timeout_s * 1e9);
  const std::int64_t deadline_ns = visnav::telemetry::monotonicNowNs() + timeout_ns;
  // The command topic is volatile: a command written before the flight reader is matched would be lost.
  if (!visnav::telemetry::waitForReaders(link.commandWriter(), 1, timeout_ns)) {
    std::fprintf(stderr,
                 "visnav-command: no flight software listening on domain %d partition %s within %.1f s\n",
                 link_params.domain_id, link_params.partitionName(), timeout_s);
    return kExitTimeout;
  }
  if (const dds_return_t rc = link.sendCommand(command_id, kind); rc != DDS_RETCODE_OK) {
    std::fprintf(stderr, "visnav-command: write failed: %s\n", dds_strretcode(rc));
    return kExitNoLink;
  }
  std::printf("visnav-command: sent #%u %s\n", command_id, visnav::telemetry::commandKindName(kind));
  visnav_CommandAck ack{};
  if (!waitForAck(link, command_id, deadline_ns, ack)) {
    std::fprintf(stderr, "visnav-command: no acknowledgment of #%u within %.1f s\n", command_id, timeout_s);
    return kExitTimeout;
  }
  std::printf("visnav-command: #%u %s %s: %s\n", ack.command_id, visnav::telemetry::commandKindName(ack.kind),
              ack.accepted ? "accepted" : "rejected", ack.reason);
  return ack.accepted ? kExitAccepted : kExitRejected;
}
