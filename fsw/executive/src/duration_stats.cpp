#include "visnav/executive/duration_stats.hpp"

#include <cmath>
#include <cstdint>

namespace visnav::exec {

void DurationStats::reset() { *this = DurationStats{}; }

int DurationStats::binIndex(std::int64_t value_ns) {
  if (value_ns < kSubBins) return value_ns < 0 ? 0 : static_cast<int>(value_ns);
  const auto v = static_cast<std::uint64_t>(value_ns);
  const int exponent = 63 - __builtin_clzll(v);  // 2^exponent <= v, exponent >= kSubBits
  if (exponent > kMaxExponent) return kBinCount - 1;
  const auto sub = static_cast<int>(v >> (exponent - kSubBits)) - kSubBins;  // 0 .. kSubBins - 1
  return kSubBins + (exponent - kSubBits) * kSubBins + sub;
}

std::int64_t DurationStats::binUpperNs(int bin) {
  if (bin < kSubBins) return bin;
  if (bin >= kBinCount - 1) return INT64_MAX;  // the overflow bin: quantiles clamp to the exact max
  const int exponent = (bin - kSubBins) / kSubBins + kSubBits;
  const int sub = (bin - kSubBins) % kSubBins;
  const std::int64_t width = std::int64_t{1} << (exponent - kSubBits);
  return (kSubBins + sub) * width + width - 1;
}

void DurationStats::add(std::int64_t value_ns) {
  if (m_count == 0 || value_ns < m_min_ns) m_min_ns = value_ns;
  if (m_count == 0 || value_ns > m_max_ns) m_max_ns = value_ns;
  ++m_count;
  m_sum_ns += static_cast<long double>(value_ns);
  ++m_bins[static_cast<std::size_t>(binIndex(value_ns))];
}

double DurationStats::meanNs() const {
  return m_count == 0 ? 0.0 : static_cast<double>(m_sum_ns / static_cast<long double>(m_count));
}

std::int64_t DurationStats::quantileNs(double q) const {
  if (m_count == 0) return 0;
  if (!(q > 0.0)) return m_min_ns;
  if (q >= 1.0) return m_max_ns;
  // Nearest rank: the smallest sample with at least q * count samples at or below it.
  auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(m_count)));
  if (rank < 1U) rank = 1U;
  std::uint64_t seen = 0;
  for (int bin = 0; bin < kBinCount; ++bin) {
    seen += m_bins[static_cast<std::size_t>(bin)];
    if (seen >= rank) {
      const std::int64_t upper = binUpperNs(bin);
      if (upper < m_min_ns) return m_min_ns;
      return upper > m_max_ns ? m_max_ns : upper;
    }
  }
  return m_max_ns;
}

}  // namespace visnav::exec
