// BoundedBuffer: capacity fixed at reserve(), push() past it fails without reallocating.
#include <gtest/gtest.h>

#include <numeric>

#include "visnav/core/bounded_buffer.hpp"

namespace visnav {
namespace {

TEST(BoundedBuffer, DefaultIsEmptyWithNoCapacity) {
  BoundedBuffer<int> buffer;
  EXPECT_TRUE(buffer.empty());
  EXPECT_TRUE(buffer.full());  // zero of zero
  EXPECT_EQ(buffer.size(), 0U);
  EXPECT_EQ(buffer.capacity(), 0U);
  EXPECT_EQ(buffer.begin(), buffer.end());
  EXPECT_FALSE(buffer.push(1));
  EXPECT_EQ(buffer.size(), 0U);
}

TEST(BoundedBuffer, PushUntilFullThenRefuses) {
  BoundedBuffer<int> buffer(3);
  EXPECT_EQ(buffer.capacity(), 3U);
  EXPECT_TRUE(buffer.empty());
  EXPECT_FALSE(buffer.full());
  EXPECT_TRUE(buffer.push(10));
  EXPECT_TRUE(buffer.push(11));
  EXPECT_FALSE(buffer.full());
  EXPECT_TRUE(buffer.push(12));
  EXPECT_TRUE(buffer.full());
  EXPECT_FALSE(buffer.push(13));
  EXPECT_FALSE(buffer.push(14));
  // The refused values changed nothing.
  ASSERT_EQ(buffer.size(), 3U);
  EXPECT_EQ(buffer[0], 10);
  EXPECT_EQ(buffer[1], 11);
  EXPECT_EQ(buffer[2], 12);
  EXPECT_EQ(buffer.capacity(), 3U);
}

TEST(BoundedBuffer, IndexingReadsAndWrites) {
  BoundedBuffer<double> buffer(4);
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(buffer.push(i * 0.5));
  buffer[2] = 42.0;
  const BoundedBuffer<double>& view = buffer;
  EXPECT_EQ(view[0], 0.0);
  EXPECT_EQ(view[1], 0.5);
  EXPECT_EQ(view[2], 42.0);
  EXPECT_EQ(view[3], 1.5);
  EXPECT_EQ(&view[0], buffer.data());
  EXPECT_EQ(&view[3], buffer.data() + 3);
}

TEST(BoundedBuffer, IterationCoversExactlyTheStoredElements) {
  BoundedBuffer<int> buffer(8);
  for (int i = 1; i <= 5; ++i) ASSERT_TRUE(buffer.push(i));
  EXPECT_EQ(buffer.end() - buffer.begin(), 5);
  EXPECT_EQ(std::accumulate(buffer.begin(), buffer.end(), 0), 15);
  int expected = 1;
  for (int& value : buffer) {
    EXPECT_EQ(value, expected++);
    value *= 2;
  }
  const BoundedBuffer<int>& view = buffer;
  int sum = 0;
  for (const int value : view) sum += value;
  EXPECT_EQ(sum, 30);
}

TEST(BoundedBuffer, ClearKeepsTheCapacityAndTheStorage) {
  BoundedBuffer<int> buffer(2);
  const int* storage = buffer.data();
  ASSERT_TRUE(buffer.push(1));
  ASSERT_TRUE(buffer.push(2));
  buffer.clear();
  EXPECT_TRUE(buffer.empty());
  EXPECT_EQ(buffer.size(), 0U);
  EXPECT_EQ(buffer.capacity(), 2U);
  EXPECT_EQ(buffer.begin(), buffer.end());
  EXPECT_TRUE(buffer.push(7));
  EXPECT_EQ(buffer[0], 7);
  EXPECT_EQ(buffer.data(), storage);
}

TEST(BoundedBuffer, TruncateOnlyShrinks) {
  BoundedBuffer<int> buffer(5);
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(buffer.push(i));
  buffer.truncate(6);  // larger than size: no effect
  EXPECT_EQ(buffer.size(), 4U);
  buffer.truncate(4);
  EXPECT_EQ(buffer.size(), 4U);
  buffer.truncate(2);
  ASSERT_EQ(buffer.size(), 2U);
  EXPECT_EQ(buffer[1], 1);
  EXPECT_TRUE(buffer.push(9));
  EXPECT_EQ(buffer[2], 9);
}

TEST(BoundedBuffer, NoReallocationAfterReserve) {
  BoundedBuffer<int> buffer;
  buffer.reserve(64);
  const int* storage = buffer.data();
  ASSERT_NE(storage, nullptr);
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 64; ++i) ASSERT_TRUE(buffer.push(i));
    EXPECT_FALSE(buffer.push(64));  // full: refused, not grown
    EXPECT_EQ(buffer.data(), storage);
    EXPECT_EQ(buffer.begin(), storage);
    buffer.truncate(10);
    EXPECT_EQ(buffer.data(), storage);
    buffer.clear();
    EXPECT_EQ(buffer.data(), storage);
  }
  EXPECT_EQ(buffer.capacity(), 64U);
}

TEST(BoundedBuffer, ReserveAgainResetsTheContents) {
  BoundedBuffer<int> buffer(2);
  ASSERT_TRUE(buffer.push(1));
  buffer.reserve(5);
  EXPECT_TRUE(buffer.empty());
  EXPECT_EQ(buffer.capacity(), 5U);
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(buffer.push(i));
  EXPECT_FALSE(buffer.push(5));
}

TEST(BoundedBuffer, HoldsNonTrivialValueTypes) {
  struct Item {
    int id = -1;
    double weight = 0.0;
  };
  BoundedBuffer<Item> buffer(2);
  ASSERT_TRUE(buffer.push({3, 0.25}));
  EXPECT_EQ(buffer[0].id, 3);
  EXPECT_EQ(buffer[0].weight, 0.25);
  // Slots past size() are default-constructed by reserve().
  EXPECT_EQ(buffer.data()[1].id, -1);
}

}  // namespace
}  // namespace visnav
