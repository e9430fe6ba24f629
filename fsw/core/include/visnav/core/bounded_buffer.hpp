// A contiguous buffer whose capacity is fixed once at init (from config) and never grows afterwards:
// push() past capacity fails and reports it instead of allocating. Used for every per-frame container.
#pragma once

#include <cstddef>
#include <memory>

namespace visnav {

template <typename T>
class BoundedBuffer {
 public:
  BoundedBuffer() = default;
  explicit BoundedBuffer(std::size_t capacity) { reserve(capacity); }

  /// Init-time only: allocates. Clears the contents.
  void reserve(std::size_t capacity) {
    m_storage = std::make_unique<T[]>(capacity);
    m_capacity = capacity;
    m_size = 0;
  }

  /// Appends unless full; returns false (and keeps the contents) when the capacity is exhausted.
  bool push(const T& value) {
    if (m_size >= m_capacity) return false;
    m_storage[m_size++] = value;
    return true;
  }
  void clear() { m_size = 0; }
  /// Shrinks to n (n <= size); used by in-place filtering.
  void truncate(std::size_t n) {
    if (n < m_size) m_size = n;
  }

  T& operator[](std::size_t i) { return m_storage[i]; }
  const T& operator[](std::size_t i) const { return m_storage[i]; }
  T* begin() { return m_storage.get(); }
  T* end() { return m_storage.get() + m_size; }
  const T* begin() const { return m_storage.get(); }
  const T* end() const { return m_storage.get() + m_size; }
  T* data() { return m_storage.get(); }
  const T* data() const { return m_storage.get(); }
  std::size_t size() const { return m_size; }
  std::size_t capacity() const { return m_capacity; }
  bool empty() const { return m_size == 0; }
  bool full() const { return m_size == m_capacity; }

 private:
  std::unique_ptr<T[]> m_storage;
  std::size_t m_capacity = 0;
  std::size_t m_size = 0;
};

}  // namespace visnav
