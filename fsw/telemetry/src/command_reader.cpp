#include "visnav/telemetry/command_reader.hpp"

#include <algorithm>

#include "visnav/telemetry/dds_topics.hpp"
#include "visnav/telemetry/sample_mapping.hpp"
#include "visnav/telemetry/telemetry_writer_dds.hpp"

namespace visnav::telemetry {

struct CommandReader::Impl {
  dds_entity_t reader = 0;
  std::array<visnav_ModeCommand, kMaxCommandDepth> samples{};
  std::array<void*, kMaxCommandDepth> sample_ptrs{};
  std::array<dds_sample_info_t, kMaxCommandDepth> infos{};
};

CommandReader::CommandReader() = default;
CommandReader::~CommandReader() = default;

LoadError CommandReader::init(const Participant& participant, const TelemetryParams& params) {
  if (!participant.isOpen()) return LoadError::failure("command reader: participant not initialised");
  if (params.command_depth < 1 || params.command_depth > kMaxCommandDepth)
    return LoadError::failure("[telemetry] command_depth must be in 1.." + std::to_string(kMaxCommandDepth));
  if (!m_impl) m_impl = std::make_unique<Impl>();  // the one allocation: init time
  Impl& d = *m_impl;
  m_depth = params.command_depth;
  dds_qos_t* qos = makeReaderQos(Topic::kModeCommand, m_depth);
  d.reader =
      dds_create_reader(participant.subscriber(), participant.topic(Topic::kModeCommand), qos, nullptr);
  dds_delete_qos(qos);
  if (d.reader < 0) return ddsFailure("creating the mode command reader", d.reader);
  // dds_take copies into caller memory when buf[0] is not null: the samples have no pointer member, so no
  // allocation and no loan to return.
  for (int i = 0; i < kMaxCommandDepth; ++i) d.sample_ptrs[i] = &d.samples[i];
  m_counters = CommandCounters{};
  return LoadError::success();
}

int CommandReader::poll(ReceivedCommand* out, int capacity) {
  if (!m_impl || m_impl->reader <= 0 || capacity <= 0) return 0;
  Impl& d = *m_impl;
  const int wanted = std::min(capacity, m_depth);
  const dds_return_t n = dds_take(d.reader, d.sample_ptrs.data(), d.infos.data(), static_cast<size_t>(wanted),
                                  static_cast<std::uint32_t>(wanted));
  if (n < 0) {
    ++m_counters.take_errors;
    return 0;
  }
  int count = 0;
  for (int i = 0; i < n; ++i) {
    if (!d.infos[i].valid_data) continue;  // instance-state notifications carry no command
    out[count] = validateCommand(d.samples[i]);
    ++m_counters.received;
    if (!out[count].valid) ++m_counters.rejected;
    ++count;
  }
  return count;
}

dds_entity_t DdsAccess::reader(const CommandReader& reader) {
  return reader.m_impl ? reader.m_impl->reader : 0;
}

}  // namespace visnav::telemetry
