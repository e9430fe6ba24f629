// visnav-monitor pieces without a network: loss and gap detection, rates, latency statistics, the CSV that
// visnav-eval must read back to the same poses.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../../../tools/monitor/src/monitor_view.hpp"
#include "../../fsw/telemetry/process_util.hpp"
#include "../../fsw/telemetry/telemetry_test_data.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/monitor/csv_recorder.hpp"
#include "visnav/monitor/monitor.hpp"
#include "visnav/monitor/topic_stats.hpp"
#include "visnav/telemetry/sample_mapping.hpp"

namespace visnav::monitor {
namespace {

TEST(TopicStats, LateStartIsNoLossButGapsAreCounted) {
  TopicStats s;
  // Joined late (first sample number 40); then 43 and 44 missing; frames 1040..1049 with 1043, 1044 missing.
  const std::int64_t period = 200'000'000;
  int k = 0;
  for (std::uint64_t n : {40, 41, 42, 45, 46, 47, 48, 49}) {
    s.add(n, static_cast<std::int64_t>(1000 + n), k * period, 1'000'000 + k * 1000, -1);
    ++k;
  }
  EXPECT_EQ(s.samples(), 8U);
  EXPECT_EQ(s.lostSamples(), 2U);
  EXPECT_EQ(s.lostFrames(), 2U);
  EXPECT_EQ(s.frameGapText(), "1043-1044");
  EXPECT_NEAR(s.meanRateHz(), 5.0, 1e-9);
  EXPECT_NEAR(s.recentRateHz(), 5.0, 1e-9);
  const LatencySummary pub = s.publishLatency();
  EXPECT_EQ(pub.count, 8U);
  EXPECT_NEAR(pub.median_ms, 1.0035, 1e-9);  // (1.003 + 1.004) / 2
  EXPECT_NEAR(pub.max_ms, 1.007, 1e-9);
  EXPECT_NEAR(pub.p99_ms, 1.00693, 1e-9);    // rank 0.99 * 7 = 6.93: 1.006 + 0.93 * 0.001
  EXPECT_EQ(s.exposureLatency().count, 0U);  // not measurable: none recorded
}

TEST(TopicStats, DuplicatesAndSingleFrameGaps) {
  TopicStats s;
  s.add(1, 10, 0, -1, -1);
  s.add(1, 10, 1, -1, -1);  // duplicate
  s.add(2, 12, 2, -1, -1);  // frame 11 never seen
  s.add(3, 15, 3, -1, -1);  // 13, 14
  EXPECT_EQ(s.outOfOrder(), 1U);
  EXPECT_EQ(s.lostSamples(), 0U);
  EXPECT_EQ(s.frameGapText(), "11, 13-14");
  EXPECT_EQ(s.lostFrames(), 3U);
  EXPECT_EQ(TopicStats{}.frameGapText(), "none");
}

TEST(Monitor, LatencyOnlyWhenTheStampIsFromThisClock) {
  EXPECT_EQ(plausibleLatencyNs(1'000, 3'000), 2'000);
  EXPECT_EQ(plausibleLatencyNs(5'000, 3'000), -1);            // from the future: another clock
  EXPECT_EQ(plausibleLatencyNs(0, 3'600'000'000'000LL), -1);  // a simulated clock starting at 0
}

TEST(Monitor, SiblingPaths) {
  EXPECT_EQ(siblingPath("out/run.csv", "_health"), "out/run_health.csv");
  EXPECT_EQ(siblingPath("out.d/run", "_health"), "out.d/run_health.csv");
}

TEST(CsvRecorder, PoseCsvReadsBackInVisnavEvalWithTheSamePoses) {
  const std::string path = telemetry::test::tempPath("monitor-csv") + ".csv";
  CsvRecorder csv;
  ASSERT_TRUE(csv.open(path).ok);
  std::vector<nav::NavSolution> sent;
  for (std::uint64_t i = 1; i <= 12; ++i) {
    sent.push_back(telemetry::test::makeNavSolution(i));
    visnav_PoseEstimate s{};
    telemetry::fillPoseEstimate(sent.back(), i, 0, s);
    csv.pose(s, Reception{});
    visnav_Health h{};
    telemetry::fillHealth(telemetry::test::makeHealthRecord(i), i, 0, h);
    csv.health(h, Reception{});
  }
  ASSERT_TRUE(csv.close());
  std::vector<eval::ReplayRow> rows;
  const LoadError e = eval::loadReplayCsv(path, rows);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(rows.size(), sent.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const nav::NavSolution& n = sent[k];
    EXPECT_EQ(rows[k].frame, static_cast<std::int64_t>(n.frame_number));
    EXPECT_EQ(rows[k].timestamp_ns, n.exposure_time_ns);
    EXPECT_EQ(eval::isTracked(rows[k].status), n.pose_valid) << k;
    ASSERT_TRUE(rows[k].has_pose);
    EXPECT_LE((rows[k].pose.t_c_m - n.pose.t_c_m).norm(), 1e-10);
    EXPECT_LE((rows[k].pose.R_c_m - n.pose.R_c_m).norm(), 1e-10);
  }
  // The health file has a header and one line per sample; the comma in "acquired, transition" is replaced.
  const std::string health = telemetry::test::readText(siblingPath(path, "_health"));
  EXPECT_EQ(std::count(health.begin(), health.end(), '\n'), 13);
  EXPECT_NE(health.find("acquired; transition 3"), std::string::npos);
}

}  // namespace
TEST(MonitorView, FaultsAreNamedAsInVisnavdsLog) {
  LatestSamples latest;
  latest.have_pose = true;
  latest.pose.fault_bits = kFaultResidual | kFaultInnovation;
  latest.have_health = true;
  latest.health.fault_bits = 0;
  MonitorOptions options;
  MonitorResult result;
  char* text = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&text, &size);
  ASSERT_NE(out, nullptr);
  drawView(out, options, latest, result);
  std::fclose(out);
  const std::string view(text, size);
  std::free(text);
  EXPECT_NE(view.find("faults residual,innovation\n"), std::string::npos) << view;
  EXPECT_NE(view.find("health: mode standby  faults none  "), std::string::npos) << view;
}

}  // namespace visnav::monitor
