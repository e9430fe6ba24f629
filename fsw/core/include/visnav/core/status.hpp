// Error reporting without exceptions. Per-frame code returns a Status; init-time loaders return a
// LoadError carrying a human-readable message (they may allocate: they run before the cycle starts).
#pragma once

#include <cstdint>
#include <string>
#include <utility>

namespace visnav {

enum class Status : std::uint8_t {
  kOk = 0,
  kInvalidArgument,
  kCapacityExceeded,
  kNotEnoughData,
  kNotConverged,
  kDegenerate,
  kOutOfImage,
  /// An iterative solver stopped without an accepted step and without meeting its convergence criteria
  /// (e.g. Levenberg-Marquardt damping beyond max_lambda): the result is the last iterate, not a solution.
  kGaveUp,
};

const char* toString(Status status);

/// Result of loading a file or a config at init: ok, or a message naming file, line and problem.
struct LoadError {
  bool ok = true;
  std::string message;

  static LoadError success() { return {}; }
  static LoadError failure(std::string text) { return {false, std::move(text)}; }
};

}  // namespace visnav
