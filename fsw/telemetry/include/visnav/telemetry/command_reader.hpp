// Flight side, once per cycle: takes the ModeCommand samples that arrived since the last cycle (non-blocking,
// into storage sized at init) and returns them validated. Accepting a valid command is the mode manager's
// decision; its answer goes into HealthRecord::last_command and so back to the ground in Health.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::telemetry {

constexpr int kMaxCommandDepth = 64;  ///< upper bound of TelemetryParams::command_depth

struct CommandCounters {
  std::uint64_t received = 0;  ///< valid data samples taken
  std::uint64_t rejected = 0;  ///< of which failed validation
  std::uint64_t take_errors = 0;
};

class CommandReader {
 public:
  LoadError init(const Participant& participant, const TelemetryParams& params);

  /// Takes at most min(capacity, command_depth) commands, oldest first; never waits. Returns how many were
  /// written to `out` (0 when none arrived or on a take error, which is counted).
  int poll(ReceivedCommand* out, int capacity);

  const CommandCounters& counters() const { return m_counters; }
  dds_entity_t reader() const { return m_reader; }

 private:
  dds_entity_t m_reader = 0;
  int m_depth = 0;
  CommandCounters m_counters;
  std::array<visnav_ModeCommand, kMaxCommandDepth> m_samples{};
  std::array<void*, kMaxCommandDepth> m_sample_ptrs{};
  std::array<dds_sample_info_t, kMaxCommandDepth> m_infos{};
};

}  // namespace visnav::telemetry
