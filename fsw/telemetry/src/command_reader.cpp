#include "visnav/telemetry/command_reader.hpp"

#include <algorithm>

namespace visnav::telemetry {

LoadError CommandReader::init(const Participant& participant, const TelemetryParams& params) {
  if (!participant.isOpen()) return LoadError::failure("command reader: participant not initialised");
  if (params.command_depth < 1 || params.command_depth > kMaxCommandDepth)
    return LoadError::failure("[telemetry] command_depth must be in 1.." + std::to_string(kMaxCommandDepth));
  m_depth = params.command_depth;
  dds_qos_t* qos = makeReaderQos(Topic::kModeCommand, m_depth);
  m_reader =
      dds_create_reader(participant.subscriber(), participant.topic(Topic::kModeCommand), qos, nullptr);
  dds_delete_qos(qos);
  if (m_reader < 0) return ddsFailure("creating the mode command reader", m_reader);
  // dds_take copies into caller memory when buf[0] is not null: the samples have no pointer member, so no
  // allocation and no loan to return.
  for (int i = 0; i < kMaxCommandDepth; ++i) m_sample_ptrs[i] = &m_samples[i];
  m_counters = CommandCounters{};
  return LoadError::success();
}

int CommandReader::poll(ReceivedCommand* out, int capacity) {
  if (m_reader <= 0 || capacity <= 0) return 0;
  const int wanted = std::min(capacity, m_depth);
  const dds_return_t n = dds_take(m_reader, m_sample_ptrs.data(), m_infos.data(), static_cast<size_t>(wanted),
                                  static_cast<std::uint32_t>(wanted));
  if (n < 0) {
    ++m_counters.take_errors;
    return 0;
  }
  int count = 0;
  for (int i = 0; i < n; ++i) {
    if (!m_infos[i].valid_data) continue;  // instance-state notifications carry no command
    out[count] = validateCommand(m_samples[i]);
    ++m_counters.received;
    if (!out[count].valid) ++m_counters.rejected;
    ++count;
  }
  return count;
}

}  // namespace visnav::telemetry
