// TEST-ONLY: the DDS entities behind TelemetryWriter and CommandReader, for tests and benchmarks that drive
// Cyclone directly (match waits, dds_write controls, status queries), and a gate that stalls the writer's
// publisher thread on the test's command (a full ring without relying on timing). Flight code never
// includes it (fsw/app does not have this include folder; scripts/check-deps.sh refuses it there): the
// flight interface is telemetry_writer.hpp and command_reader.hpp.
#pragma once

#include <dds/dds.h>

#include "visnav/telemetry/command_reader.hpp"
#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/telemetry_writer.hpp"

namespace visnav::telemetry {

struct DdsAccess {
  /// The DDS writer of a flight topic (0: kModeCommand, or before init()).
  static dds_entity_t writer(const TelemetryWriter& writer, Topic topic);
  /// The ModeCommand reader (0 before init()).
  static dds_entity_t reader(const CommandReader& reader);
  /// Stalls the publisher thread between two samples: returns once it is parked (true) and takes no slot
  /// until releasePublisher() or stop(); false when it did not park within `timeout_ns` (or is not running).
  static bool holdPublisher(TelemetryWriter& writer, std::int64_t timeout_ns);
  static void releasePublisher(TelemetryWriter& writer);
};

inline dds_entity_t ddsWriter(const TelemetryWriter& writer, Topic topic) {
  return DdsAccess::writer(writer, topic);
}
inline dds_entity_t ddsReader(const CommandReader& reader) { return DdsAccess::reader(reader); }

}  // namespace visnav::telemetry
