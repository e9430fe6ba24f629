// Deterministic random numbers for RANSAC and the synthetic renderer: PCG32 (O'Neill 2014), identical on
// every platform and compiler, unlike std::uniform_int_distribution.
#pragma once

#include <cstdint>

namespace visnav {

class Pcg32 {
 public:
  explicit Pcg32(std::uint64_t seed = 0x853c49e6748fea9bULL, std::uint64_t stream = 0xda3e39cb94b95bdbULL) {
    reseed(seed, stream);
  }
  void reseed(std::uint64_t seed, std::uint64_t stream = 0xda3e39cb94b95bdbULL) {
    m_state = 0U;
    m_inc = (stream << 1U) | 1U;
    next();
    m_state += seed;
    next();
  }
  std::uint32_t next() {
    const std::uint64_t old = m_state;
    m_state = old * 6364136223846793005ULL + m_inc;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18U) ^ old) >> 27U);
    const auto rot = static_cast<std::uint32_t>(old >> 59U);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1U) & 31U));
  }
  /// Uniform integer in [0, bound) without modulo bias: the reference pcg32_boundedrand_r (reject draws below
  /// 2^32 mod bound, then take the remainder); bounded: expected < 2 draws, modulo after 64 rejections.
  std::uint32_t below(std::uint32_t bound) {
    if (bound == 0U) return 0U;
    const std::uint32_t threshold = (~bound + 1U) % bound;
    for (int guard = 0; guard < 64; ++guard) {
      const std::uint32_t r = next();
      if (r >= threshold) return r % bound;
    }
    return next() % bound;
  }
  /// Uniform double in [0, 1).
  double uniform() { return static_cast<double>(next()) * (1.0 / 4294967296.0); }

 private:
  std::uint64_t m_state = 0;
  std::uint64_t m_inc = 0;
};

}  // namespace visnav
