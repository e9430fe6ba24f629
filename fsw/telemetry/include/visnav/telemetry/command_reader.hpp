// Flight side, once per cycle: takes the ModeCommand samples that arrived since the last cycle (non-blocking,
// into storage sized at init) and returns them validated. Accepting a valid command is the mode manager's
// decision; its answer goes into HealthRecord::last_command and so back to the ground in Health.
// DDS-free header: the reader and its sample storage live in an implementation object allocated once, in
// init().
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "visnav/navigation/nav_solution.hpp"
#include "visnav/telemetry/participant.hpp"

namespace visnav::telemetry {

struct DdsAccess;  // telemetry_writer_dds.hpp

constexpr int kMaxCommandDepth = 64;  ///< upper bound of TelemetryParams::command_depth

/// A ModeCommand as the flight side sees it after validation (validateCommand, sample_mapping.hpp).
struct ReceivedCommand {
  std::uint32_t command_id = 0;
  std::uint8_t raw_kind = 0;                                  ///< as received, even when unknown
  nav::ModeCommandKind kind = nav::ModeCommandKind::kResume;  ///< meaningful only when valid
  bool valid = false;
  std::array<char, 64> reason{};  ///< "ok" or why it was rejected (NUL-terminated)

  /// The acknowledgment to put in HealthRecord::last_command: `accepted` and `why` come from the mode manager
  /// for a valid command; an invalid one is always rejected with this->reason.
  nav::CommandAck ack(bool accepted, const char* why) const;
  nav::CommandAck rejection() const { return ack(false, reason.data()); }
};

struct CommandCounters {
  std::uint64_t received = 0;  ///< valid data samples taken
  std::uint64_t rejected = 0;  ///< of which failed validation
  std::uint64_t take_errors = 0;
};

class CommandReader {
 public:
  CommandReader();
  ~CommandReader();
  CommandReader(const CommandReader&) = delete;
  CommandReader& operator=(const CommandReader&) = delete;

  LoadError init(const Participant& participant, const TelemetryParams& params);

  /// Takes at most min(capacity, command_depth) commands, oldest first; never waits. Returns how many were
  /// written to `out` (0 when none arrived or on a take error, which is counted).
  int poll(ReceivedCommand* out, int capacity);

  const CommandCounters& counters() const { return m_counters; }

 private:
  friend struct DdsAccess;
  struct Impl;  // command_reader.cpp: the DDS reader and kMaxCommandDepth samples with their infos

  std::unique_ptr<Impl> m_impl;  ///< allocated once, by the first init()
  int m_depth = 0;
  CommandCounters m_counters;
};

}  // namespace visnav::telemetry
