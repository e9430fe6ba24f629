#include "visnav/telemetry/ground_link.hpp"

namespace visnav::telemetry {

GroundLink::~GroundLink() {
  if (m_waitset > 0) dds_delete(m_waitset);
}

LoadError GroundLink::init(const TelemetryParams& params, int reader_depth) {
  if (LoadError e = m_participant.init(params); !e.ok) return e;  // domain, partition, naming
  m_waitset = dds_create_waitset(m_participant.handle());
  if (m_waitset < 0) return ddsFailure("creating the waitset", m_waitset);
  for (Topic topic : kFlightTopics) {
    dds_qos_t* qos = makeReaderQos(topic, reader_depth);
    const dds_entity_t reader =
        dds_create_reader(m_participant.subscriber(), m_participant.topic(topic), qos, nullptr);
    dds_delete_qos(qos);
    if (reader < 0) return ddsFailure(topicName(topic), reader);
    m_readers[static_cast<int>(topic)] = reader;
    // Triggers while the reader holds any sample, so a wake-up is never missed between two takes.
    const dds_entity_t condition = dds_create_readcondition(reader, DDS_ANY_STATE);
    if (condition < 0) return ddsFailure("creating a read condition", condition);
    if (const dds_return_t rc = dds_waitset_attach(m_waitset, condition, reader); rc != DDS_RETCODE_OK)
      return ddsFailure("attaching a read condition", rc);
  }
  dds_qos_t* qos = makeWriterQos(Topic::kModeCommand, params, 0);
  m_command_writer =
      dds_create_writer(m_participant.publisher(), m_participant.topic(Topic::kModeCommand), qos, nullptr);
  dds_delete_qos(qos);
  if (m_command_writer < 0) return ddsFailure("creating the mode command writer", m_command_writer);
  return LoadError::success();
}

bool GroundLink::waitForData(std::int64_t timeout_ns) {
  if (m_waitset <= 0) return false;
  return dds_waitset_wait(m_waitset, nullptr, 0, static_cast<dds_duration_t>(timeout_ns)) > 0;
}

bool GroundLink::allReadersMatched() const {
  for (Topic topic : kFlightTopics) {
    dds_subscription_matched_status_t status{};
    if (dds_get_subscription_matched_status(reader(topic), &status) != DDS_RETCODE_OK) return false;
    if (status.current_count == 0) return false;
  }
  return true;
}

int GroundLink::takeInto(Topic topic, void** buffers, dds_sample_info_t* infos, int count) {
  const dds_entity_t reader = this->reader(topic);
  if (reader <= 0 || count <= 0) return 0;
  return dds_take(reader, buffers, infos, static_cast<size_t>(count), static_cast<std::uint32_t>(count));
}

dds_return_t GroundLink::sendCommand(std::uint32_t command_id, std::uint8_t kind) {
  visnav_ModeCommand command{};
  command.command_id = command_id;
  command.kind = kind;
  return dds_write(m_command_writer, &command);
}

}  // namespace visnav::telemetry
