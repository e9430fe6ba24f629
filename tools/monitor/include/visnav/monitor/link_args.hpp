// Command-line options shared by the ground tools (visnav-monitor, visnav-command): where the telemetry is.
//   --config FILE     take domain and partition from the [telemetry] table of a visnav config
//   --domain N        override the DDS domain id
//   --partition NAME  override the partition
#pragma once

#include <string>

#include "visnav/core/status.hpp"
#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::monitor {

/// Consumes argv[i] (and its value) when it is one of the options above: returns true and advances `i`.
/// Sets `error` (and returns true) on a bad value, and `exit_code` to what the tool then exits with
/// (README.md "Exit codes"): cli::kExitInvalidInput for a --config that does not load or is invalid,
/// cli::kExitUsage for a bad --domain or --partition. Values are applied in order: --config first, then
/// overrides.
bool parseLinkArgument(int argc, char** argv, int& i, telemetry::TelemetryParams& link, LoadError& error,
                       int& exit_code);

constexpr const char* kLinkUsage = "[--config FILE] [--domain N] [--partition NAME]";

}  // namespace visnav::monitor
