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

/// A task of the table, as Executive::addTask() hands it out. The caller keeps it and names the task by it
/// (statistics, failure events, simulated durations), never by its position in the table. Default: invalid.
class TaskId {
 public:
  constexpr TaskId() = default;
  constexpr bool valid() const { return m_index >= 0; }
  /// Slot in the executive's fixed tables (0 .. kMaxTasks-1; -1 when invalid).
  constexpr int index() const { return m_index; }
  friend constexpr bool operator==(TaskId a, TaskId b) { return a.m_index == b.m_index; }
  friend constexpr bool operator!=(TaskId a, TaskId b) { return a.m_index != b.m_index; }

 private:
  friend class Executive;
  constexpr explicit TaskId(int index) : m_index(index) {}
  int m_index = -1;
};

using TaskFn = Status (*)(void* context, const CycleInfo& cycle);

/// Object form of a task (a "port" with one method).
class CycleTask {
 public:
  virtual ~CycleTask() = default;
  virtual Status runCycle(const CycleInfo& cycle) = 0;
};

}  // namespace visnav::exec
