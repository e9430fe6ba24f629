// Ground commands: a stream of ModeCommand samples as DDS delivers them (any command_id, any kind) through
// validateCommand, the mode manager and the acknowledgment, in every mode the commands can reach.
#include <array>
#include <cstring>

#include "idl/visnav.h"
#include "visnav/navigation/mode_manager.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace {

template <std::size_t N>
void requireTerminated(const std::array<char, N>& text) {
  if (std::memchr(text.data(), '\0', N) == nullptr) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace visnav;
  nav::NavigationParams params;
  params.acquire_below_m = 30.0;  // a hand-over as the pipeline derives for a plate (README, "Modes")
  params.far_range_above_m = 40.0;
  nav::ModeManager modes;
  if (!modes.init(params).ok) __builtin_trap();
  std::uint64_t frame = 0;
  // One record: command_id (4 bytes), kind (1), flags (1: far fix available, frames to advance).
  constexpr std::size_t kRecord = 6;
  for (std::size_t at = 0; at + kRecord <= size; at += kRecord) {
    visnav_ModeCommand sample{};
    std::memcpy(&sample.command_id, data + at, sizeof sample.command_id);
    sample.kind = data[at + 4];
    const std::uint8_t flags = data[at + 5];
    frame += flags >> 1U;
    const telemetry::ReceivedCommand received = telemetry::validateCommand(sample);
    requireTerminated(received.reason);
    nav::CommandAck ack;
    const bool accepted =
        received.valid && modes.command(received.kind, received.command_id, (flags & 1U) != 0U, frame, ack);
    if (!received.valid) ack = received.rejection();
    if (accepted && !received.valid) __builtin_trap();
    if (ack.command_id != received.command_id) __builtin_trap();
    const nav::CommandAck echoed = received.ack(accepted, accepted ? "ok" : "rejected");
    requireTerminated(echoed.reason);
  }
  return 0;
}
