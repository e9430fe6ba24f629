// The options every visnav binary answers the same way (GNU and Debian conventions, help2man reads them):
//   --help, -h   the usage on stdout, exit 0
//   --version    "NAME VERSION" on stdout (the project version, visnav/version.hpp), exit 0
// A usage error stays on stderr with exit 2 (kExitUsage). Each tool checks argv[i] here first in its
// argument loop, so "--help" given as an option's value stays that value.
#pragma once

#include <cstdio>
#include <cstring>

#include "visnav/version.hpp"

namespace visnav::cli {

// Exit codes, one table for every visnav binary (README.md "Exit codes"; what 4 and 5 cover in visnavd:
// fsw/app/README.md):
constexpr int kExitOk = 0;            // done; the check or gate asked for holds
constexpr int kExitFailed = 1;        // ran, and the result is negative (a gate or requirement failed)
constexpr int kExitUsage = 2;         // command line: unknown, incomplete or out-of-range argument
constexpr int kExitInvalidInput = 3;  // a config or input file that does not load or is invalid
constexpr int kExitStartup = 4;       // could not start: device, DDS, or the other side never answered
constexpr int kExitRealtime = 5;      // a realtime setting was refused and asked to be fatal (visnavd)
constexpr int kNotStandard = -1;

/// Writes a tool's usage text to `stream` (stdout for --help, stderr on a usage error).
using UsageWriter = void (*)(std::FILE* stream);

inline void printVersion(const char* name) { std::printf("%s %s\n", name, visnav::kVersion); }

/// --help or -h: `usage(stdout)`; --version: the version line. Both return 0, the exit code; any other
/// argument returns kNotStandard and is the tool's to parse.
inline int standardOption(const char* arg, const char* name, UsageWriter usage) {
  if (std::strcmp(arg, "--help") == 0 || std::strcmp(arg, "-h") == 0) {
    usage(stdout);
    return 0;
  }
  if (std::strcmp(arg, "--version") == 0) {
    printVersion(name);
    return 0;
  }
  return kNotStandard;
}

/// The same for a tool whose usage is one fixed text.
inline int standardOption(const char* arg, const char* name, const char* usage_text) {
  if (std::strcmp(arg, "--help") == 0 || std::strcmp(arg, "-h") == 0) {
    std::fputs(usage_text, stdout);
    return 0;
  }
  if (std::strcmp(arg, "--version") == 0) {
    printVersion(name);
    return 0;
  }
  return kNotStandard;
}

}  // namespace visnav::cli
