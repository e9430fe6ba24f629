// DurationStats: bin layout, exact min/max/mean, quantiles within the documented 1/16 resolution against a
// sorted reference, and the conversion into the navigation summary.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "visnav/core/rng.hpp"
#include "visnav/executive/duration_stats.hpp"
#include "visnav/navigation/nav_solution.hpp"

namespace visnav::exec {
namespace {

std::int64_t nearestRank(std::vector<std::int64_t> values, double q) {
  std::sort(values.begin(), values.end());
  auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  if (rank < 1U) rank = 1U;
  return values[rank - 1U];
}

void expectQuantileWithinResolution(const DurationStats& stats, const std::vector<std::int64_t>& values,
                                    double q) {
  const std::int64_t truth = nearestRank(values, q);
  const std::int64_t reported = stats.quantileNs(q);
  EXPECT_GE(reported, truth) << "q " << q;
  EXPECT_LE(static_cast<double>(reported), static_cast<double>(truth) * (1.0 + 1.0 / 16.0) + 1.0)
      << "q " << q;
}

TEST(DurationStats, BinsCoverEveryValueWithBoundedRelativeWidth) {
  std::vector<std::int64_t> probes;
  for (std::int64_t v = 0; v < 5000; ++v) probes.push_back(v);
  for (int e = 4; e < 45; ++e) {
    const std::int64_t p = std::int64_t{1} << e;
    probes.insert(probes.end(), {p - 1, p, p + 1, p + p / 3});
  }
  std::sort(probes.begin(), probes.end());
  int previous_bin = -1;
  for (const std::int64_t v : probes) {
    const int bin = DurationStats::binIndex(v);
    ASSERT_GE(bin, 0);
    ASSERT_LT(bin, DurationStats::kBinCount);
    EXPECT_GE(DurationStats::binUpperNs(bin), v);
    if (bin > 0) {
      EXPECT_LT(DurationStats::binUpperNs(bin - 1), v) << "value " << v << " in too high a bin";
    }
    EXPECT_GE(bin, previous_bin);  // monotonic
    if (v >= 16 && bin < DurationStats::kBinCount - 1) {
      const std::int64_t lower = DurationStats::binUpperNs(bin - 1) + 1;
      const std::int64_t width = DurationStats::binUpperNs(bin) - lower + 1;
      EXPECT_LE(static_cast<double>(width), static_cast<double>(lower) / 16.0) << v;
    }
    previous_bin = bin;
  }
  EXPECT_EQ(DurationStats::binIndex(15), 15);  // exact below 16 ns
  EXPECT_EQ(DurationStats::binIndex(std::int64_t{1} << 50), DurationStats::kBinCount - 1);
}

TEST(DurationStats, UniformMicrosecondsGiveExactMomentsAndResolvedQuantiles) {
  DurationStats stats;
  std::vector<std::int64_t> values;
  for (int us = 1000; us >= 1; --us) {  // descending: order must not matter
    stats.add(us * 1000LL);
    values.push_back(us * 1000LL);
  }
  EXPECT_EQ(stats.count(), 1000U);
  EXPECT_EQ(stats.minNs(), 1000);
  EXPECT_EQ(stats.maxNs(), 1000000);
  EXPECT_DOUBLE_EQ(stats.meanNs(), 500500.0);
  EXPECT_EQ(nearestRank(values, 0.99), 990000);
  for (const double q : {0.01, 0.5, 0.9, 0.99, 0.999}) expectQuantileWithinResolution(stats, values, q);
  EXPECT_EQ(stats.quantileNs(1.0), 1000000);
  EXPECT_EQ(stats.quantileNs(0.0), 1000);
}

TEST(DurationStats, LogUniformRandomSamplesMatchSortedReference) {
  Pcg32 rng(42);
  DurationStats stats;
  std::vector<std::int64_t> values;
  for (int i = 0; i < 20000; ++i) {
    const auto v = static_cast<std::int64_t>(std::pow(10.0, 2.0 + 7.0 * rng.uniform()));  // 100 ns .. 1 s
    stats.add(v);
    values.push_back(v);
  }
  for (const double q : {0.5, 0.9, 0.99, 0.999}) expectQuantileWithinResolution(stats, values, q);
  EXPECT_EQ(stats.maxNs(), *std::max_element(values.begin(), values.end()));
}

TEST(DurationStats, EmptyNegativeAndHugeValues) {
  DurationStats stats;
  EXPECT_EQ(stats.count(), 0U);
  EXPECT_EQ(stats.quantileNs(0.99), 0);
  EXPECT_EQ(stats.meanNs(), 0.0);
  stats.add(-50);
  stats.add(150);
  EXPECT_EQ(stats.minNs(), -50);
  EXPECT_DOUBLE_EQ(stats.meanNs(), 50.0);
  EXPECT_EQ(stats.quantileNs(0.5), 0);  // the negative sample sits in bin 0, reported as 0
  const std::int64_t huge = std::int64_t{1} << 50;
  stats.add(huge);
  EXPECT_EQ(stats.maxNs(), huge);
  EXPECT_EQ(stats.quantileNs(0.99), huge);  // overflow bin clamps to the exact max
  stats.reset();
  EXPECT_EQ(stats.count(), 0U);
  EXPECT_EQ(stats.maxNs(), 0);
}

TEST(DurationStats, FillsNavigationTaskTimingSummaryInMicroseconds) {
  DurationStats stats;
  for (int i = 1; i <= 100; ++i) stats.add(i * 10000LL);  // 10 us .. 1000 us
  nav::TaskTimingSummary summary;
  fillTimingSummary(stats, summary);
  EXPECT_DOUBLE_EQ(summary.min_us, 10.0);
  EXPECT_DOUBLE_EQ(summary.max_us, 1000.0);
  EXPECT_DOUBLE_EQ(summary.mean_us, 505.0);
  EXPECT_GE(summary.p99_us, 990.0);  // nearest rank 99 of 100
  EXPECT_LE(summary.p99_us, 990.0 * (1.0 + 1.0 / 16.0));
}

}  // namespace
}  // namespace visnav::exec
