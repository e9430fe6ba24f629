// What the cyclic executive calls: a task is a plain function pointer plus a caller-owned context (no
// std::function, nothing allocated), or an object implementing CycleTask. Tasks run synchronously in the
// executive's one thread, in registration order, and report failure through the returned Status.
#pragma once

#include <cstdint>

#include "visnav/core/status.hpp"

namespace visnav::exec {

/// Capacity of the task table (fixed storage; addTask() past it fails at init).
constexpr int kMaxTasks = 16;

/// Timing of the minor frame a task runs in, all on the executive's clock [ns].
struct CycleInfo {
  std::uint64_t minor_frame = 0;  ///< index of this release since run() started (skipped releases count)
  std::uint64_t cycle = 0;        ///< minor frames actually run before this one
  std::int64_t release_ns = 0;    ///< ideal release time: epoch + minor_frame * period
  std::int64_t wake_ns = 0;       ///< when the executive actually woke for this frame
  std::int64_t deadline_ns = 0;   ///< release_ns + period: the cycle should end before this
};

using TaskFn = Status (*)(void* context, const CycleInfo& cycle);

/// Object form of a task (a "port" with one method).
class CycleTask {
 public:
  virtual ~CycleTask() = default;
  virtual Status runCycle(const CycleInfo& cycle) = 0;
};

}  // namespace visnav::exec
