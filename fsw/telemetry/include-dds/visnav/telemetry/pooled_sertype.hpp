// A Cyclone DDS sertype whose serialized samples live in a fixed pool sized at init, so that writing a
// sample allocates nothing. Why: Cyclone 0.10.2's default serdata keeps a freed sample buffer for reuse only
// when it is at most 256 bytes; PoseEstimate (6x6 covariance) and Health are larger, so the default path
// allocates twice per dds_write. Same idea as rmw_cyclonedds' own sertype, reduced to what visnav needs.
//
// Scope: only the flight writers use it (TelemetryWriter). Readers keep Cyclone's default sertype; a reader
// in the same process gets each sample through Cyclone's conversion (to_ser here, from_ser_iov there), a
// remote reader gets the same little-endian XCDR1 bytes a default writer would send. The types must be
// keyless with no pointer member (all of idl/visnav.idl's topics), so a sample's serialized size has a fixed
// bound.
#pragma once

#include <dds/dds.h>

#include <cstdint>

namespace visnav::telemetry {

struct PooledSertypeStats {
  std::uint32_t blocks = 0;         ///< pool capacity (serialized samples held at once without allocating)
  std::uint32_t payload_bytes = 0;  ///< payload capacity of one block [bytes]
  std::uint64_t pool_misses = 0;    ///< pool empty: that sample went to a heap block (counted, not hidden)
  std::uint32_t blocks_in_use = 0;  ///< now (Cyclone still holds them: writer history, transmit queue)
};

class PooledSertype;
}  // namespace visnav::telemetry
struct ddsi_sertype;
namespace visnav::telemetry {

/// Init-time: creates topic `name` of type `descriptor` in `participant` backed by a pool of `blocks` sample
/// blocks (allocated here, freed by Cyclone when the last entity using the topic is deleted). `*sertype` is
/// set for stats(). Returns the topic entity, or a negative DDS return code.
dds_entity_t createPooledTopic(dds_entity_t participant, const char* name,
                               const dds_topic_descriptor_t* descriptor, std::uint32_t blocks,
                               const PooledSertype** sertype);

/// Thread-safe snapshot (Cyclone frees blocks from its own threads).
PooledSertypeStats pooledSertypeStats(const PooledSertype* sertype);

/// Cyclone's view of it, for tests that drive the serdata operations directly (ddsi_serdata_from_sample).
const ddsi_sertype* cycloneSertype(const PooledSertype* sertype);

}  // namespace visnav::telemetry
