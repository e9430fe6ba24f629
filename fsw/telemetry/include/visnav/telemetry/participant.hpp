// The DDS domain participant of one process: one publisher and one subscriber (in the partition, or none with
// ROS 2 naming) and the four topics. Deleting it deletes every reader and writer created under it (Cyclone
// deletes children with the parent). DDS-free header: the entities are opaque handles here (a Cyclone
// dds_entity_t is an int32_t; dds_topics.cpp checks it); only code that includes dds_topics.hpp (the ground
// tools, tests) can do anything with them.
#pragma once

#include <cstdint>

#include "visnav/core/status.hpp"
#include "visnav/telemetry/telemetry_params.hpp"
#include "visnav/telemetry/topics.hpp"

namespace visnav::telemetry {

using EntityHandle = std::int32_t;  ///< a dds_entity_t (0: none)

class Participant {
 public:
  Participant() = default;
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// Init-time: creates the entities (Cyclone reads its own config from CYCLONEDDS_URI): domain, partition
  /// and naming of `params`.
  LoadError init(const TelemetryParams& params);
  /// Same with visnav naming, in `partition`.
  LoadError init(int domain_id, const char* partition);
  void close();
  bool isOpen() const { return m_participant > 0; }
  /// Topic and type names of this participant's topics ([telemetry] naming).
  TopicNaming naming() const { return m_naming; }

  EntityHandle handle() const { return m_participant; }
  EntityHandle publisher() const { return m_publisher; }
  EntityHandle subscriber() const { return m_subscriber; }
  EntityHandle topic(Topic topic) const { return m_topics[static_cast<int>(topic)]; }

 private:
  LoadError create(int domain_id, const char* partition, TopicNaming naming);

  EntityHandle m_participant = 0;
  EntityHandle m_publisher = 0;
  EntityHandle m_subscriber = 0;
  EntityHandle m_topics[kTopicCount] = {};
  TopicNaming m_naming = TopicNaming::kVisnav;
};

}  // namespace visnav::telemetry
