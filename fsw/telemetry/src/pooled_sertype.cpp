// Pooled sertype for the flight writers: see pooled_sertype.hpp for why, and the Cyclone DDS 0.10.2 headers
// ddsi_sertype.h / ddsi_serdata.h for the contract of each operation.
#include "visnav/telemetry/pooled_sertype.hpp"

#include <dds/ddsi/ddsi_cdrstream.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>
#include <new>

namespace visnav::telemetry {
namespace {

constexpr std::uint32_t kHeaderBytes = 4;  // DDSI encoding header: identifier, options (both big-endian)
constexpr std::uint32_t kXcdrVersion = 1;  // what Cyclone's default sertype writes for @final types
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
constexpr unsigned char kIdentifierLow = 0x01;  // CDR_LE
#else
constexpr unsigned char kIdentifierLow = 0x00;  // CDR_BE
#endif

/// One serialized sample: the serdata Cyclone sees, then the encoding header and the payload. The payload
/// starts 8-aligned because Cyclone's stream writer stores doubles directly.
struct Block {
  ddsi_serdata c;                 // first: Cyclone passes &c around
  PooledSertype* pool = nullptr;  // owner of this block; nullptr: a heap block (pool was empty)
  std::uint32_t size = 0;         // serialized bytes: header + payload + padding to 4
  Block* next_free = nullptr;
};

constexpr std::size_t kPayloadOffset = (sizeof(Block) + kHeaderBytes + 7) / 8 * 8;

unsigned char* payloadOf(Block* b) { return reinterpret_cast<unsigned char*>(b) + kPayloadOffset; }
const unsigned char* serializedOf(const Block* b) {
  return reinterpret_cast<const unsigned char*>(b) + kPayloadOffset - kHeaderBytes;
}
Block* blockOf(ddsi_serdata* d) { return reinterpret_cast<Block*>(d); }
const Block* blockOf(const ddsi_serdata* d) { return reinterpret_cast<const Block*>(d); }

/// What Cyclone holds: its sertype, then the way back to ours (standard layout, so &c converts back).
struct SertypeEntry {
  ddsi_sertype c;
  PooledSertype* owner;
};

}  // namespace

class PooledSertype {
 public:
  PooledSertype(const dds_topic_descriptor_t* descriptor_, std::uint32_t blocks_)
      : descriptor(descriptor_),
        // A keyless struct with no pointer member serializes (XCDR1, the C struct's own alignment) into at
        // most its C size plus a 4-byte length per bounded string: twice the size plus margin bounds that.
        payload_capacity(2U * descriptor_->m_size + 64U),
        block_bytes(kPayloadOffset + payload_capacity),
        blocks(blocks_),
        storage(new std::uint64_t[(block_bytes * blocks_ + 7) / 8]()),
        free_stack(new Block*[blocks_]) {
    for (std::uint32_t i = 0; i < blocks; ++i) {
      auto* b = new (reinterpret_cast<unsigned char*>(storage.get()) + i * block_bytes) Block;
      b->pool = this;
      free_stack[i] = b;
    }
    free_count = blocks;
    entry.owner = this;
  }

  Block* acquire() {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      if (free_count > 0) {
        ++in_use;
        return free_stack[--free_count];
      }
    }
    misses.fetch_add(1, std::memory_order_relaxed);
    auto* raw = static_cast<unsigned char*>(::operator new(block_bytes, std::nothrow));
    return raw == nullptr ? nullptr : new (raw) Block;
  }

  void release(Block* b) {
    const std::lock_guard<std::mutex> lock(mutex);
    free_stack[free_count++] = b;
    --in_use;
  }

  SertypeEntry entry{};  // Cyclone's part; entry.c.ops and .serdata_ops point at the tables below
  const dds_topic_descriptor_t* descriptor;
  std::uint32_t payload_capacity;
  std::size_t block_bytes;
  std::uint32_t blocks;
  std::unique_ptr<std::uint64_t[]> storage;  // uint64_t: 8-aligned blocks
  std::unique_ptr<Block*[]> free_stack;
  std::uint32_t free_count = 0;
  std::uint32_t in_use = 0;
  std::mutex mutex;  // from_sample runs on the cycle's thread, free on Cyclone's (acks, transmit)
  std::atomic<std::uint64_t> misses{0};
};

namespace {

PooledSertype* sertypeOf(const ddsi_sertype* t) { return reinterpret_cast<const SertypeEntry*>(t)->owner; }

Block* newBlock(PooledSertype* pool, const ddsi_sertype* type, ddsi_serdata_kind kind) {
  Block* b = pool->acquire();
  if (b == nullptr) return nullptr;
  ddsi_serdata_init(&b->c, type, kind);
  b->c.hash = pool->entry.c.serdata_basehash;  // keyless: every sample has the same (empty) key
  b->size = kHeaderBytes;
  unsigned char* header = payloadOf(b) - kHeaderBytes;
  header[0] = 0x00;
  header[1] = kIdentifierLow;
  header[2] = 0x00;
  header[3] = 0x00;
  return b;
}

// --- serdata operations ---------------------------------------------------------------------------------

bool eqkey(const ddsi_serdata*, const ddsi_serdata*) { return true; }  // keyless

std::uint32_t getSize(const ddsi_serdata* d) { return blockOf(d)->size; }

ddsi_serdata* fromSample(const ddsi_sertype* type, ddsi_serdata_kind kind, const void* sample) {
  PooledSertype* pool = sertypeOf(type);
  Block* b = newBlock(pool, type, kind);
  if (b == nullptr) return nullptr;
  if (kind != SDK_DATA) return &b->c;  // keyless: a key or empty serdata has no payload
  unsigned char* payload = payloadOf(b);
  dds_ostream_t os{payload, pool->payload_capacity, 0, kXcdrVersion};
  dds_stream_write(&os, static_cast<const char*>(sample), pool->descriptor->m_ops);
  // The capacity bound makes growth impossible (the stream would realloc our block): checked, not assumed.
  if (os.m_buffer != payload || os.m_index > pool->payload_capacity) std::abort();
  const std::uint32_t pad = (4U - os.m_index % 4U) % 4U;  // DDSI wants 4-byte multiples; options say how many
  std::memset(payload + os.m_index, 0, pad);
  payload[-1] = static_cast<unsigned char>(pad);
  b->size = kHeaderBytes + os.m_index + pad;
  return &b->c;
}

ddsi_serdata* toUntyped(const ddsi_serdata* d) {
  // The instance map's copy of the key, type-less: for a keyless type just the header. It lives in the
  // domain's instance map, possibly beyond this sertype, so it is a heap block of its own, never a pool's.
  // Cyclone makes one per instance (one per topic here, when the first sample is written).
  auto* raw = static_cast<unsigned char*>(::operator new(kPayloadOffset, std::nothrow));
  if (raw == nullptr) return nullptr;
  Block* b = new (raw) Block;
  ddsi_serdata_init(&b->c, d->type, SDK_KEY);
  b->c.type = nullptr;
  b->c.hash = d->hash;
  b->size = kHeaderBytes;
  std::memcpy(payloadOf(b) - kHeaderBytes, serializedOf(blockOf(d)), kHeaderBytes);
  return &b->c;
}

void toSer(const ddsi_serdata* d, std::size_t off, std::size_t sz, void* buf) {
  std::memcpy(buf, serializedOf(blockOf(d)) + off, sz);
}

ddsi_serdata* toSerRef(const ddsi_serdata* d, std::size_t off, std::size_t sz, ddsrt_iovec_t* ref) {
  ref->iov_base = const_cast<unsigned char*>(serializedOf(blockOf(d)) + off);
  ref->iov_len = static_cast<decltype(ref->iov_len)>(sz);
  return ddsi_serdata_ref(d);
}

void toSerUnref(ddsi_serdata* d, const ddsrt_iovec_t*) { ddsi_serdata_unref(d); }

bool toSample(const ddsi_serdata* d, void* sample, void**, void*) {
  if (d->kind != SDK_DATA) return true;  // keyless: no key fields to fill
  const Block* b = blockOf(d);
  const PooledSertype* pool = sertypeOf(d->type);
  dds_istream_t is{};
  dds_istream_init(&is, b->size - kHeaderBytes, serializedOf(b) + kHeaderBytes, kXcdrVersion);
  dds_stream_read(&is, static_cast<char*>(sample), pool->descriptor->m_ops);
  return true;
}

bool untypedToSample(const ddsi_sertype*, const ddsi_serdata*, void*, void**, void*) { return true; }

void freeSerdata(ddsi_serdata* d) {
  Block* b = blockOf(d);
  if (b->pool != nullptr) {
    b->pool->release(b);
  } else {
    b->~Block();
    ::operator delete(b);
  }
}

std::size_t print(const ddsi_sertype*, const ddsi_serdata* d, char* buf, std::size_t size) {
  const int n = std::snprintf(buf, size, "pooled sample, %u serialized bytes", blockOf(d)->size);
  return n < 0 ? 0 : static_cast<std::size_t>(n);
}

void getKeyhash(const ddsi_serdata*, ddsi_keyhash* buf, bool) { std::memset(buf, 0, sizeof(*buf)); }

// Readers never use this sertype (they use Cyclone's default one), so nothing arrives from the network or
// from a keyhash into it: Cyclone calls these for readers only. Returning nullptr is its "cannot" answer.
ddsi_serdata* fromSer(const ddsi_sertype*, ddsi_serdata_kind, const nn_rdata*, std::size_t) {
  return nullptr;
}
ddsi_serdata* fromSerIov(const ddsi_sertype*, ddsi_serdata_kind, ddsrt_msg_iovlen_t, const ddsrt_iovec_t*,
                         std::size_t) {
  return nullptr;
}
ddsi_serdata* fromKeyhash(const ddsi_sertype*, const ddsi_keyhash*) { return nullptr; }

ddsi_serdata_ops makeSerdataOps() {
  ddsi_serdata_ops ops{};
  ops.eqkey = eqkey;
  ops.get_size = getSize;
  ops.from_ser = fromSer;
  ops.from_ser_iov = fromSerIov;
  ops.from_keyhash = fromKeyhash;
  ops.from_sample = fromSample;
  ops.to_ser = toSer;
  ops.to_ser_ref = toSerRef;
  ops.to_ser_unref = toSerUnref;
  ops.to_sample = toSample;
  ops.to_untyped = toUntyped;
  ops.untyped_to_sample = untypedToSample;
  ops.free = freeSerdata;
  ops.print = print;
  ops.get_keyhash = getKeyhash;
  return ops;  // the shared-memory (iceoryx) operations stay null: this build does not enable SHM
}

// --- sertype operations ---------------------------------------------------------------------------------

void freeSertype(ddsi_sertype* t) {
  PooledSertype* pool = sertypeOf(t);
  ddsi_sertype_fini(t);
  delete pool;
}

void zeroSamples(const ddsi_sertype* t, void* samples, std::size_t count) {
  std::memset(samples, 0, sertypeOf(t)->descriptor->m_size * count);
}

void reallocSamples(void** ptrs, const ddsi_sertype* t, void* old, std::size_t old_count, std::size_t count) {
  const std::size_t size = sertypeOf(t)->descriptor->m_size;
  auto* samples = static_cast<char*>(old_count == count ? old : dds_realloc(old, size * count));
  if (samples != nullptr && count > old_count)
    std::memset(samples + size * old_count, 0, size * (count - old_count));
  for (std::size_t i = 0; i < count; ++i) ptrs[i] = samples == nullptr ? nullptr : samples + i * size;
}

void freeSamples(const ddsi_sertype*, void** ptrs, std::size_t, dds_free_op_t op) {
  // No pointer members: there are no contents to free, only the array itself when asked.
  if ((op & DDS_FREE_ALL_BIT) != 0) dds_free(ptrs[0]);
}

bool equalSertypes(const ddsi_sertype* a, const ddsi_sertype* b) { return a == b; }  // one pool per writer

std::uint32_t hashSertype(const ddsi_sertype* t) {
  return static_cast<std::uint32_t>(std::hash<const void*>{}(t));
}

ddsi_sertype_ops makeSertypeOps() {
  ddsi_sertype_ops ops{};
  ops.version = ddsi_sertype_v0;
  ops.free = freeSertype;
  ops.zero_samples = zeroSamples;
  ops.realloc_samples = reallocSamples;
  ops.free_samples = freeSamples;
  ops.equal = equalSertypes;
  ops.hash = hashSertype;
  return ops;  // no type information: remote readers match on the type name, as with pre-XTypes peers
}

const ddsi_serdata_ops kSerdataOps = makeSerdataOps();
const ddsi_sertype_ops kSertypeOps = makeSertypeOps();

}  // namespace

dds_entity_t createPooledTopic(dds_entity_t participant, const char* name,
                               const dds_topic_descriptor_t* descriptor, std::uint32_t blocks,
                               const PooledSertype** sertype) {
  if (blocks == 0 || descriptor == nullptr || descriptor->m_nkeys != 0) return DDS_RETCODE_BAD_PARAMETER;
  auto* pool = new (std::nothrow) PooledSertype(descriptor, blocks);
  if (pool == nullptr) return DDS_RETCODE_OUT_OF_RESOURCES;
  ddsi_sertype_init(&pool->entry.c, descriptor->m_typename, &kSertypeOps, &kSerdataOps, true);
  ddsi_sertype* registered = &pool->entry.c;
  const dds_entity_t topic =
      dds_create_topic_sertype(participant, name, &registered, nullptr, nullptr, nullptr);
  if (topic < 0) {
    ddsi_sertype_unref(&pool->entry.c);  // ours was not taken: drop it (frees the pool through freeSertype)
    return topic;
  }
  *sertype = sertypeOf(registered);
  return topic;
}

PooledSertypeStats pooledSertypeStats(const PooledSertype* sertype) {
  PooledSertypeStats s;
  if (sertype == nullptr) return s;
  auto* pool = const_cast<PooledSertype*>(sertype);
  const std::lock_guard<std::mutex> lock(pool->mutex);
  s.blocks = pool->blocks;
  s.payload_bytes = pool->payload_capacity;
  s.pool_misses = pool->misses.load(std::memory_order_relaxed);
  s.blocks_in_use = pool->in_use;
  return s;
}

const ddsi_sertype* cycloneSertype(const PooledSertype* sertype) {
  return sertype == nullptr ? nullptr : &sertype->entry.c;
}

}  // namespace visnav::telemetry
