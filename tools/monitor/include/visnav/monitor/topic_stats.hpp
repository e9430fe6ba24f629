// What visnav-monitor learns about one topic from the samples it receives: counts, rates, samples lost in
// transport (gaps in sample_number), frames never seen (gaps in frame_number) and latencies. Ground code:
// it may allocate (latency lists grow with the run).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace visnav::monitor {

/// Inclusive range of frame numbers never received.
struct FrameGap {
  std::uint64_t first = 0;
  std::uint64_t last = 0;
};

struct LatencySummary {
  std::size_t count = 0;
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
};

class TopicStats {
 public:
  /// One received sample. `frame_number` < 0: the topic has none (Health). Latencies in ns, < 0 or absent
  /// (INT64_MIN) when not measurable.
  void add(std::uint64_t sample_number, std::int64_t frame_number, std::int64_t receive_ns,
           std::int64_t publish_latency_ns, std::int64_t exposure_latency_ns);

  std::uint64_t samples() const { return m_samples; }
  /// Samples missing between the first and the last received (sample_number gaps).
  std::uint64_t lostSamples() const { return m_lost_samples; }
  /// Samples that arrived with a sample_number not above the previous one (duplicates or reordering).
  std::uint64_t outOfOrder() const { return m_out_of_order; }
  const std::vector<FrameGap>& frameGaps() const { return m_frame_gaps; }
  std::uint64_t lostFrames() const;
  /// Mean rate over the whole reception [Hz]; 0 with fewer than two samples.
  double meanRateHz() const;
  /// Rate over the last (up to) 16 samples [Hz].
  double recentRateHz() const;
  std::int64_t lastReceiveNs() const { return m_last_receive_ns; }
  LatencySummary publishLatency() const { return summarize(m_publish_latency_ms); }
  LatencySummary exposureLatency() const { return summarize(m_exposure_latency_ms); }

  /// "17, 40-42" (at most `max_ranges` ranges, then "..."), "none" when there is no gap.
  std::string frameGapText(std::size_t max_ranges = 10) const;

 private:
  static LatencySummary summarize(const std::vector<double>& values_ms);

  std::uint64_t m_samples = 0;
  std::uint64_t m_last_sample_number = 0;
  std::uint64_t m_lost_samples = 0;
  std::uint64_t m_out_of_order = 0;
  std::int64_t m_last_frame = -1;
  std::vector<FrameGap> m_frame_gaps;
  std::int64_t m_first_receive_ns = 0;
  std::int64_t m_last_receive_ns = 0;
  std::array<std::int64_t, 16> m_recent_receive_ns{};
  std::vector<double> m_publish_latency_ms;
  std::vector<double> m_exposure_latency_ms;
};

}  // namespace visnav::monitor
