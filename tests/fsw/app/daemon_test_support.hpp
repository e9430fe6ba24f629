// Shared by the daemon tests: config text for a replay camera, a per-process DDS partition and the log file.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include "app_test_support.hpp"
#include "visnav/app/daemon.hpp"

namespace visnav::app::test {

inline constexpr int kFrames = VISNAV_APP_TEST_FRAMES;  // far range, acquisition, near range

inline std::string partitionFor(const char* name) {
  return std::string(name) + "-" + std::to_string(getpid());
}

inline std::string replayConfig(const std::string& sequence, const std::string& partition, bool telemetry,
                                const std::string& extra = "") {
  return "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
         "\"\n[telemetry]\nenabled = " + (telemetry ? "true" : "false") + "\npartition = \"" + partition +
         "\"\n" + extra;
}

/// The log of a test: a file the EventLog writes to, read back as text.
struct LogFile {
  TempDir dir{"log"};
  std::string path = dir.path() + "/log.txt";
  int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  EventLog log{fd, false};
  ~LogFile() { ::close(fd); }
  std::string text() const {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
};

}  // namespace visnav::app::test
