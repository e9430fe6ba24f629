// Pcg32 against the PCG32 reference (O'Neill, pcg-c-basic): seeding is pcg32_srandom_r(seed, stream), the
// output pcg32_random_r, below() pcg32_boundedrand_r.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>

#include "visnav/core/rng.hpp"

namespace visnav {
namespace {

TEST(Pcg32, MatchesThePcg32DemoReferenceOutput) {
  // pcg32-demo: pcg32_srandom_r(&rng, 42u, 54u), first six pcg32_random_r outputs.
  Pcg32 rng(42U, 54U);
  const std::array<std::uint32_t, 6> expected = {0xa15c02b7U, 0x7b47f409U, 0xba1d3330U,
                                                 0x83d2f293U, 0xbfa4784bU, 0xcbed606eU};
  for (const std::uint32_t value : expected) EXPECT_EQ(rng.next(), value);
}

TEST(Pcg32, DefaultSeedIsTheReferenceSeedingOfTheDocumentedConstants) {
  // The defaults are passed through pcg32_srandom_r as (seed, stream); note this is NOT the reference's
  // PCG32_INITIALIZER, which stores the same two constants directly as (state, inc). Values from the
  // reference algorithm with pcg32_srandom_r(0x853c49e6748fea9b, 0xda3e39cb94b95bdb).
  Pcg32 rng;
  EXPECT_EQ(rng.next(), 0x1bbeb4f2U);
  EXPECT_EQ(rng.next(), 0xe82e89e9U);
  EXPECT_EQ(rng.next(), 0x681cfdebU);
  EXPECT_EQ(rng.next(), 0xe00fa2ecU);
}

TEST(Pcg32, BelowMatchesTheReferenceBoundedRand) {
  // pcg32_boundedrand_r(&rng, 6) + 1 after the six outputs above (reference algorithm).
  Pcg32 rng(42U, 54U);
  for (int i = 0; i < 6; ++i) rng.next();
  const std::array<int, 12> expected = {6, 4, 1, 3, 1, 2, 5, 2, 4, 4, 1, 4};
  for (const int value : expected) EXPECT_EQ(static_cast<int>(rng.below(6U)) + 1, value);
}

TEST(Pcg32, SameSeedAndStreamGiveTheSameSequence) {
  Pcg32 a(12345U, 7U);
  Pcg32 b(12345U, 7U);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next(), b.next()) << "draw " << i;
}

TEST(Pcg32, ReseedRestartsTheSequence) {
  Pcg32 rng(99U, 3U);
  std::array<std::uint32_t, 16> first{};
  for (auto& value : first) value = rng.next();
  rng.reseed(99U, 3U);
  for (const std::uint32_t value : first) EXPECT_EQ(rng.next(), value);
  // reseed(seed) keeps the default stream, like the constructor's default.
  Pcg32 defaulted(5U);
  rng.reseed(5U);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(rng.next(), defaulted.next());
}

TEST(Pcg32, DifferentStreamsOrSeedsDiffer) {
  Pcg32 a(42U, 54U);
  Pcg32 b(42U, 55U);
  Pcg32 c(43U, 54U);
  int same_ab = 0;
  int same_ac = 0;
  for (int i = 0; i < 1000; ++i) {
    const std::uint32_t x = a.next();
    same_ab += x == b.next() ? 1 : 0;
    same_ac += x == c.next() ? 1 : 0;
  }
  EXPECT_LE(same_ab, 1);  // a chance coincidence of 32-bit values is ~1e-6 per draw
  EXPECT_LE(same_ac, 1);
}

TEST(Pcg32, UniformIsInTheHalfOpenUnitInterval) {
  Pcg32 rng(2024U, 1U);
  Pcg32 raw(2024U, 1U);
  double lo = 1.0;
  double hi = 0.0;
  double sum = 0.0;
  constexpr int kDraws = 100000;
  for (int i = 0; i < kDraws; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ASSERT_EQ(u, static_cast<double>(raw.next()) / 4294967296.0);
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    sum += u;
  }
  EXPECT_LT(lo, 1e-3);
  EXPECT_GT(hi, 1.0 - 1e-3);
  EXPECT_NEAR(sum / kDraws, 0.5, 0.005);  // sigma of the mean: 0.29 / sqrt(1e5) = 0.0009
}

TEST(Pcg32, BelowStaysInRangeAndCoversIt) {
  Pcg32 rng(7U, 11U);
  EXPECT_EQ(rng.below(0U), 0U);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(rng.below(1U), 0U);
  std::array<int, 10> counts{};
  constexpr int kDraws = 100000;
  for (int i = 0; i < kDraws; ++i) {
    const std::uint32_t v = rng.below(10U);
    ASSERT_LT(v, 10U);
    ++counts[v];
  }
  for (const int count : counts) EXPECT_NEAR(count, kDraws / 10, 600);  // ~6.3 sigma of a binomial
  // A bound just above 2^31 rejects almost half the raw outputs; results still in range.
  const std::uint32_t big = 0x80000001U;
  for (int i = 0; i < 1000; ++i) ASSERT_LT(rng.below(big), big);
}

}  // namespace
}  // namespace visnav
