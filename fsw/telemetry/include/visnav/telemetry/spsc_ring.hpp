// Bounded single-producer / single-consumer ring of fixed-size slots, storage inside the object (no heap).
// The producer fills a slot in place (beginPush / commitPush), the consumer reads it in place (front / pop).
// Both sides are wait-free: one acquire load of the other side's index, one release store of their own, no
// lock, no retry loop. A full ring refuses the new element (drop-newest: what is already queued keeps its
// order and is never overwritten while the consumer may be reading it); the caller counts the refusal.
// Indices run freely (64 bits: no wrap in the life of a mission); slot = index % N.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

namespace visnav::telemetry {

template <typename T, std::size_t N>
class SpscRing {
  static_assert(N > 0, "a ring needs at least one slot");

 public:
  static constexpr std::size_t kCapacity = N;

  // Producer side.
  /// The slot to fill next, or nullptr when the ring is full (the element is to be dropped).
  T* beginPush() {
    const std::uint64_t head = m_head.load(std::memory_order_relaxed);
    if (head - m_tail.load(std::memory_order_acquire) >= N) return nullptr;
    return &m_slots[head % N];
  }
  /// Publishes the slot beginPush() returned to the consumer.
  void commitPush() { m_head.store(m_head.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  // Consumer side.
  /// The oldest queued element, or nullptr when the ring is empty.
  T* front() {
    const std::uint64_t tail = m_tail.load(std::memory_order_relaxed);
    if (tail == m_head.load(std::memory_order_acquire)) return nullptr;
    return &m_slots[tail % N];
  }
  /// Hands the slot front() returned back to the producer.
  void pop() { m_tail.store(m_tail.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

  // Either side, and observers: totals since construction.
  std::uint64_t pushed() const { return m_head.load(std::memory_order_acquire); }
  std::uint64_t popped() const { return m_tail.load(std::memory_order_acquire); }

 private:
  // Separate cache lines: each side writes only its own index.
  alignas(64) std::atomic<std::uint64_t> m_head{0};  ///< next slot to fill (producer)
  alignas(64) std::atomic<std::uint64_t> m_tail{0};  ///< next slot to read (consumer)
  alignas(64) T m_slots[N]{};
};

}  // namespace visnav::telemetry
