// Child processes for the multi-process telemetry tests (posix_spawn, bounded waits, signals).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace visnav::telemetry::test {

/// Starts `argv[0]` with the arguments; stdout goes to `stdout_path` when not empty. Returns the pid (-1 on
/// failure). The child inherits the environment (CYCLONEDDS_URI set by ctest).
pid_t spawnProcess(const std::vector<std::string>& argv, const std::string& stdout_path = "");
/// Waits up to `timeout_s` for the child to exit. Returns its exit code, 128 + signal when killed by one, or
/// -1 on timeout (the child then gets SIGINT, so it can still write its summary, and SIGKILL 5 s later;
/// it is reaped either way).
int waitProcess(pid_t pid, double timeout_s);
/// Whole text of a file ("" when missing).
std::string readText(const std::string& path);
/// A fresh file path in the build's temporary area ("<dir>/<name>-<pid>-<counter>").
std::string tempPath(const std::string& name);

}  // namespace visnav::telemetry::test
