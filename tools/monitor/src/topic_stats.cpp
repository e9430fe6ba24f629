#include "visnav/monitor/topic_stats.hpp"

#include <algorithm>
#include <climits>

#include "visnav/eval/metrics.hpp"

namespace visnav::monitor {

void TopicStats::add(std::uint64_t sample_number, std::int64_t frame_number, std::int64_t receive_ns,
                     std::int64_t publish_latency_ns, std::int64_t exposure_latency_ns) {
  if (m_samples == 0) {
    m_first_receive_ns = receive_ns;  // a late joiner's first sample_number is not a loss
  } else if (sample_number > m_last_sample_number) {
    m_lost_samples += sample_number - m_last_sample_number - 1;
  } else {
    ++m_out_of_order;
  }
  if (sample_number > m_last_sample_number) m_last_sample_number = sample_number;
  if (frame_number >= 0) {
    if (m_last_frame >= 0 && frame_number > m_last_frame + 1)
      m_frame_gaps.push_back(
          {static_cast<std::uint64_t>(m_last_frame + 1), static_cast<std::uint64_t>(frame_number - 1)});
    if (frame_number > m_last_frame) m_last_frame = frame_number;
  }
  m_recent_receive_ns[m_samples % m_recent_receive_ns.size()] = receive_ns;
  ++m_samples;
  m_last_receive_ns = receive_ns;
  if (publish_latency_ns >= 0) m_publish_latency_ms.push_back(static_cast<double>(publish_latency_ns) * 1e-6);
  if (exposure_latency_ns >= 0)
    m_exposure_latency_ms.push_back(static_cast<double>(exposure_latency_ns) * 1e-6);
}

std::uint64_t TopicStats::lostFrames() const {
  std::uint64_t n = 0;
  for (const FrameGap& g : m_frame_gaps) n += g.last - g.first + 1;
  return n;
}

double TopicStats::meanRateHz() const {
  if (m_samples < 2 || m_last_receive_ns <= m_first_receive_ns) return 0.0;
  return static_cast<double>(m_samples - 1) * 1e9 /
         static_cast<double>(m_last_receive_ns - m_first_receive_ns);
}

double TopicStats::recentRateHz() const {
  const std::size_t ring = m_recent_receive_ns.size();
  const std::size_t n = std::min<std::size_t>(m_samples, ring);
  if (n < 2) return 0.0;
  const std::int64_t newest = m_recent_receive_ns[(m_samples - 1) % ring];
  const std::int64_t oldest = m_recent_receive_ns[(m_samples - n) % ring];
  if (newest <= oldest) return 0.0;
  return static_cast<double>(n - 1) * 1e9 / static_cast<double>(newest - oldest);
}

std::string TopicStats::frameGapText(std::size_t max_ranges) const {
  if (m_frame_gaps.empty()) return "none";
  std::string text;
  for (std::size_t i = 0; i < m_frame_gaps.size(); ++i) {
    if (i == max_ranges) return text + ", ...";
    const FrameGap& g = m_frame_gaps[i];
    if (i > 0) text += ", ";
    text += std::to_string(g.first);
    if (g.last != g.first) text += "-" + std::to_string(g.last);
  }
  return text;
}

LatencySummary TopicStats::summarize(const std::vector<double>& values_ms) {
  LatencySummary s;
  if (values_ms.empty()) return s;
  std::vector<double> sorted = values_ms;
  std::sort(sorted.begin(), sorted.end());
  s.count = sorted.size();
  s.median_ms = eval::percentileSorted(sorted, 0.5);
  s.p99_ms = eval::percentileSorted(sorted, 0.99);
  s.max_ms = sorted.back();
  return s;
}

}  // namespace visnav::monitor
