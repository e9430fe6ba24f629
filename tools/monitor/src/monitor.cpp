#include "visnav/monitor/monitor.hpp"

#include <unistd.h>

#include <array>
#include <memory>

#include "monitor_view.hpp"
#include "visnav/monitor/csv_recorder.hpp"
#include "visnav/telemetry/ground_link.hpp"

namespace visnav::monitor {
namespace {

constexpr std::int64_t kWaitSliceNs = 100'000'000;  // stop requests are seen within this
constexpr std::int64_t kRedrawPeriodNs = 250'000'000;
constexpr std::int64_t kMaxLingerNs = 1'000'000'000;
constexpr std::int64_t kMaxPlausibleLatencyNs = 60'000'000'000;
constexpr std::int64_t kMatchPollNs = 10'000'000;  // until the ready file is written

struct Buffers {
  std::array<visnav_PoseEstimate, telemetry::kMaxTakeBatch> pose{};
  std::array<visnav_FarRangeEstimate, telemetry::kMaxTakeBatch> far{};
  std::array<visnav_Health, telemetry::kMaxTakeBatch> health{};
  std::array<dds_sample_info_t, telemetry::kMaxTakeBatch> infos{};
};

Reception receptionNow(const dds_sample_info_t& info) {
  Reception r;
  r.receive_mono_ns = telemetry::monotonicNowNs();
  r.receive_wall_ns = dds_time();
  r.source_wall_ns = info.source_timestamp;
  return r;
}

// Takes what one reader holds (one batch) and hands every sample that carries data to `on_sample`.
template <typename Sample, typename Take, typename OnSample>
void drain(std::array<Sample, telemetry::kMaxTakeBatch>& samples,
           std::array<dds_sample_info_t, telemetry::kMaxTakeBatch>& infos, Take take, OnSample on_sample) {
  const int n = take(samples.data(), infos.data(), telemetry::kMaxTakeBatch);
  for (int i = 0; i < n; ++i)
    if (infos[i].valid_data) on_sample(samples[i], receptionNow(infos[i]));
}

LoadError writeReadyFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return LoadError::failure(path + ": cannot create the ready file");
  const bool ok = std::fputs("ready\n", f) >= 0;
  if (std::fclose(f) != 0 || !ok) return LoadError::failure(path + ": cannot write the ready file");
  return LoadError::success();
}

std::string latencyText(const LatencySummary& s) {
  if (s.count == 0) return "n/a";
  char text[96];
  std::snprintf(text, sizeof(text), "median %.3f ms p99 %.3f ms max %.3f ms", s.median_ms, s.p99_ms,
                s.max_ms);
  return text;
}

std::string topicSummary(const char* name, const TopicStats& s, bool has_frames) {
  char head[160];
  std::snprintf(head, sizeof(head), "%s: samples %llu, rate %.3f Hz, lost samples %llu", name,
                static_cast<unsigned long long>(s.samples()), s.meanRateHz(),
                static_cast<unsigned long long>(s.lostSamples()));
  std::string text = head;
  if (has_frames) text += ", lost frames " + std::to_string(s.lostFrames()) + " (" + s.frameGapText() + ")";
  text += "\n  publish->receive latency: " + latencyText(s.publishLatency());
  if (has_frames) text += "\n  exposure->receive latency: " + latencyText(s.exposureLatency());
  return text + "\n";
}

}  // namespace

std::int64_t plausibleLatencyNs(std::int64_t stamp_ns, std::int64_t now_ns) {
  const std::int64_t latency = now_ns - stamp_ns;
  return latency >= 0 && latency <= kMaxPlausibleLatencyNs ? latency : -1;
}

std::string summaryText(const MonitorResult& result) {
  char head[128];
  std::snprintf(head, sizeof(head), "visnav-monitor summary: %.2f s%s\n", result.elapsed_s,
                result.reached_sample_limit ? ", sample limit reached" : "");
  return head + topicSummary("pose", result.pose, true) + topicSummary("far_range", result.far_range, true) +
         topicSummary("health", result.health, false);
}

LoadError runMonitor(const MonitorOptions& options, const std::atomic<bool>& stop, MonitorResult& result,
                     std::FILE* summary_out) {
  result = MonitorResult{};
  telemetry::GroundLink link;
  if (LoadError e = link.init(options.link, options.reader_depth); !e.ok) {
    result.link_failed = true;
    return e;
  }
  CsvRecorder csv;
  if (!options.csv_path.empty())
    if (LoadError e = csv.open(options.csv_path); !e.ok) return e;
  const bool view = options.live_view && isatty(fileno(stdout)) != 0;
  auto buffers = std::make_unique<Buffers>();
  LatestSamples latest;
  const std::int64_t start_ns = telemetry::monotonicNowNs();
  std::int64_t next_draw_ns = start_ns;
  std::int64_t linger_end_ns = 0;
  auto& infos = buffers->infos;
  bool ready_written = options.ready_file.empty();
  while (!stop.load()) {
    if (!ready_written && link.allReadersMatched()) {
      if (LoadError e = writeReadyFile(options.ready_file); !e.ok) return e;
      ready_written = true;
    }
    const bool got_data = link.waitForData(ready_written ? kWaitSliceNs : kMatchPollNs);
    drain(
        buffers->pose, infos,
        [&](visnav_PoseEstimate* out, dds_sample_info_t* si, int capacity) {
          return link.takePose(out, si, capacity);
        },
        [&](const visnav_PoseEstimate& s, const Reception& r) {
          result.pose.add(s.sample_number, static_cast<std::int64_t>(s.frame_number), r.receive_mono_ns,
                          plausibleLatencyNs(s.publish_time_ns, r.receive_mono_ns),
                          plausibleLatencyNs(s.exposure_time_ns, r.receive_mono_ns));
          csv.pose(s, r);
          latest.pose = s;
          latest.have_pose = true;
        });
    drain(
        buffers->far, infos,
        [&](visnav_FarRangeEstimate* out, dds_sample_info_t* si, int capacity) {
          return link.takeFarRange(out, si, capacity);
        },
        [&](const visnav_FarRangeEstimate& s, const Reception& r) {
          result.far_range.add(s.sample_number, static_cast<std::int64_t>(s.frame_number), r.receive_mono_ns,
                               plausibleLatencyNs(s.publish_time_ns, r.receive_mono_ns),
                               plausibleLatencyNs(s.exposure_time_ns, r.receive_mono_ns));
          csv.farRange(s, r);
          latest.far = s;
          latest.have_far = true;
        });
    drain(
        buffers->health, infos,
        [&](visnav_Health* out, dds_sample_info_t* si, int capacity) {
          return link.takeHealth(out, si, capacity);
        },
        [&](const visnav_Health& s, const Reception& r) {
          result.health.add(s.sample_number, -1, r.receive_mono_ns,
                            plausibleLatencyNs(s.publish_time_ns, r.receive_mono_ns), -1);
          csv.health(s, r);
          latest.health = s;
          latest.have_health = true;
        });
    const std::int64_t now_ns = telemetry::monotonicNowNs();
    result.elapsed_s = static_cast<double>(now_ns - start_ns) * 1e-9;
    if (options.stop_after_pose_samples > 0 && result.pose.samples() >= options.stop_after_pose_samples &&
        !result.reached_sample_limit) {
      result.reached_sample_limit = true;
      linger_end_ns = now_ns + kMaxLingerNs;
    }
    // After the limit, the same cycles' far-range and health samples may still be on their way: keep
    // draining until they caught up, the link went quiet for one wait slice, or the linger time is over.
    if (result.reached_sample_limit && ((result.far_range.samples() >= result.pose.samples() &&
                                         result.health.samples() >= result.pose.samples()) ||
                                        !got_data || now_ns >= linger_end_ns))
      break;
    if (options.duration_s > 0.0 && result.elapsed_s >= options.duration_s) break;
    if (view && now_ns >= next_draw_ns) {
      drawView(stdout, options, latest, result);
      next_draw_ns = now_ns + kRedrawPeriodNs;
    }
  }
  if (view) drawView(stdout, options, latest, result);
  const bool csv_ok = csv.close();
  std::fputs(summaryText(result).c_str(), summary_out);
  std::fflush(summary_out);
  if (!csv_ok) return LoadError::failure(options.csv_path + ": write failed");
  return LoadError::success();
}

}  // namespace visnav::monitor
