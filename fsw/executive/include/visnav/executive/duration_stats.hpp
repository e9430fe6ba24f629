// Fixed-storage statistics of a duration [ns]: count, exact min/max/mean and quantiles from a log-linear
// histogram (HdrHistogram's layout, small): values below 16 ns have one bin each; above, every power of two
// [2^e, 2^(e+1)) is split into 16 equal bins, so a bin is at most 1/16 = 6.25 % of its values wide. A
// quantile is reported as the upper edge of the bin holding the nearest-rank sample, clamped to [min, max]:
// never below the true value and at most 6.25 % above it (e.g. +-33 us resolution around 1 ms, +-4 us
// around 100 us). Values above 2^41 ns (~37 min) share the last bin (max stays exact). add() is O(1), no
// allocation; the object is ~5 KB.
#pragma once

#include <array>
#include <cstdint>

namespace visnav::exec {

class DurationStats {
 public:
  static constexpr int kSubBins = 16;      ///< bins per power of two (relative width <= 1/16)
  static constexpr int kSubBits = 4;       ///< log2(kSubBins)
  static constexpr int kMaxExponent = 40;  ///< highest power of two with its own bins
  static constexpr int kBinCount = kSubBins + (kMaxExponent - kSubBits + 1) * kSubBins;

  void reset();
  /// Negative values (a simulated clock may produce none, a real one should not) count as 0 in the
  /// histogram but keep their sign in min/mean.
  void add(std::int64_t value_ns);

  std::uint64_t count() const { return m_count; }
  std::int64_t minNs() const { return m_count == 0 ? 0 : m_min_ns; }
  std::int64_t maxNs() const { return m_count == 0 ? 0 : m_max_ns; }
  double meanNs() const;
  /// Nearest-rank quantile q in [0, 1] (see the header comment for its resolution); 0 when empty.
  std::int64_t quantileNs(double q) const;

  static int binIndex(std::int64_t value_ns);
  /// Largest value that falls into `bin` (inclusive).
  static std::int64_t binUpperNs(int bin);

 private:
  std::array<std::uint64_t, kBinCount> m_bins{};
  std::uint64_t m_count = 0;
  std::int64_t m_min_ns = 0;
  std::int64_t m_max_ns = 0;
  long double m_sum_ns = 0.0L;  // exact for any realistic run (64-bit mantissa)
};

/// Writes min/mean/max/p99 in microseconds into any struct with those fields (e.g.
/// visnav::nav::TaskTimingSummary) without the executive depending on the navigation library.
template <typename Summary>
void fillTimingSummary(const DurationStats& stats, Summary& out) {
  out.min_us = static_cast<double>(stats.minNs()) * 1e-3;
  out.mean_us = stats.meanNs() * 1e-3;
  out.max_us = static_cast<double>(stats.maxNs()) * 1e-3;
  out.p99_us = static_cast<double>(stats.quantileNs(0.99)) * 1e-3;
}

}  // namespace visnav::exec
