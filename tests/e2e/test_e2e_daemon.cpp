// End-to-end (fsw/app/README.md, Tests): visnavd on a replay sequence publishes over real Cyclone DDS on
// loopback; visnav-monitor, a separate process, receives every PoseEstimate, FarRangeEstimate and Health
// sample (none lost) and records CSV; that CSV holds exactly visnav-replay's numbers for the same sequence
// (same pipeline code): equal pose, attitude, covariance and mode columns frame by frame, and equal
// visnav-eval summaries.
//
// visnavd runs on the simulated clock (deterministic, like visnav-replay) at the sequence's own rate, with a
// real pause of --pace-ms per cycle so the monitor keeps up, after waiting for the monitor's readers.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../fsw/app/app_test_support.hpp"
#include "../fsw/telemetry/process_util.hpp"
#include "visnav/eval/replay_csv.hpp"

namespace visnav::app {
namespace {

using telemetry::test::readText;
using telemetry::test::spawnProcess;
using telemetry::test::waitProcess;

constexpr int kFrames = VISNAV_APP_TEST_FRAMES;  // through every mode into near range

/// A CSV file as rows of named columns.
struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
  const std::string& at(std::size_t row, const std::string& name) const {
    static const std::string kMissing = "<no such column>";
    const int c = column(name);
    return c < 0 || static_cast<std::size_t>(c) >= rows[row].size() ? kMissing
                                                                    : rows[row][static_cast<std::size_t>(c)];
  }
};

Table readCsv(const std::string& path) {
  Table table;
  std::ifstream in(path);
  std::string line;
  if (std::getline(in, line)) table.header = eval::splitCsvLine(line);
  while (std::getline(in, line))
    if (!line.empty()) table.rows.push_back(eval::splitCsvLine(line));
  return table;
}

std::string writeCsv(const std::string& path, const Table& table) {
  std::ofstream out(path);
  for (std::size_t c = 0; c < table.header.size(); ++c) out << (c > 0 ? "," : "") << table.header[c];
  out << "\n";
  for (const std::vector<std::string>& row : table.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) out << (c > 0 ? "," : "") << row[c];
    out << "\n";
  }
  return path;
}

/// visnav-eval's JSON summary without the lines naming the input files (those differ by design).
// The summary without the input paths and the filter's NIS (a replay column the telemetry does not carry).
std::string summaryWithoutPaths(const std::string& path) {
  std::istringstream in(readText(path));
  std::string out;
  for (std::string line; std::getline(in, line);)
    if (line.find("\"replay\"") == std::string::npos && line.find("\"sequence\"") == std::string::npos &&
        line.find("\"filter_nis\"") == std::string::npos)
      out += line + "\n";
  return out;
}

int run(const std::vector<std::string>& argv, const std::string& out, double timeout_s) {
  const pid_t pid = spawnProcess(argv, out);
  return pid > 0 ? waitProcess(pid, timeout_s) : -1;
}

TEST(EndToEnd, MonitorReceivesEverySampleAndScoresLikeReplay) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("e2e");
  const std::string partition = "e2e-" + std::to_string(getpid());
  // approach_ci is recorded at 0.625 Hz: the simulated executive runs at that rate, so every frame is
  // processed at its exposure time, exactly as visnav-replay does.
  const std::string config =
      dir.write("e2e.toml", "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                "\"\n[executive]\nmajor_frame_hz = 0.625\n[telemetry]\npartition = \"" +
                                partition + "\"\n");
  const std::string replay_csv = dir.path() + "/replay.csv";
  ASSERT_EQ(run({VISNAV_REPLAY, "--sequence", sequence, "--config", config, "--out", replay_csv,
                 "--no-timing", "--no-progress"},
                dir.path() + "/replay.txt", 120.0),
            0)
      << readText(dir.path() + "/replay.txt");

  const std::string monitor_csv = dir.path() + "/monitor.csv";
  const pid_t monitor = spawnProcess(
      {VISNAV_MONITOR, "--config", config, "--csv", monitor_csv, "--samples", std::to_string(kFrames),
       "--duration", "90", "--no-view", "--ready-file", dir.path() + "/monitor.ready"},
      dir.path() + "/monitor.txt");
  ASSERT_GT(monitor, 0);
  const std::string daemon_log = dir.path() + "/visnavd.txt";
  // 25 ms per cycle: the keep-last-1 writer overwrites a sample the reader has not acknowledged yet, and at
  // 5 ms a loaded machine (a full parallel ctest) lost 6 of 80. The flight rate is 200 ms.
  const pid_t daemon = spawnProcess({"/bin/sh", "-c",
                                     std::string("exec ") + VISNAV_DAEMON + " --config " + config +
                                         " --simulated-clock --pace-ms 25 --wait-subscribers 1 --wait-file " +
                                         dir.path() + "/monitor.ready 2> " + daemon_log});
  ASSERT_GT(daemon, 0);
  EXPECT_EQ(waitProcess(daemon, 90.0), 0) << readText(daemon_log);
  EXPECT_EQ(waitProcess(monitor, 30.0), 0) << readText(dir.path() + "/monitor.txt");
  const std::string log = readText(daemon_log);
  EXPECT_NE(log.find("event=stop reason=end_of_stream cycles=" + std::to_string(kFrames + 1) +
                     " frames=" + std::to_string(kFrames)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("write_failures=0 sample_pool_misses=0"), std::string::npos) << log;
  std::printf("%s\n", readText(dir.path() + "/monitor.txt").c_str());

  // Every sample of every topic arrived, in order, none lost.
  const std::string stem = monitor_csv.substr(0, monitor_csv.size() - 4);
  const Table pose = readCsv(monitor_csv);
  const Table far = readCsv(stem + "_far_range.csv");
  const Table health = readCsv(stem + "_health.csv");
  ASSERT_EQ(pose.rows.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(far.rows.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(health.rows.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < static_cast<std::size_t>(kFrames); ++i) {
    const std::string n = std::to_string(i + 1);
    EXPECT_EQ(pose.at(i, "sample_number"), n);
    EXPECT_EQ(far.at(i, "sample_number"), n);
    EXPECT_EQ(health.at(i, "sample_number"), n);
    EXPECT_EQ(pose.at(i, "frame"), std::to_string(i));
    EXPECT_EQ(health.at(i, "frames_processed"), n);
  }

  // Same code path, same numbers: frame by frame, the pose (where the solution has one) and the far-range
  // fix of the monitor's recording equal visnav-replay's CSV to the last printed digit.
  const Table replay = readCsv(replay_csv);
  ASSERT_EQ(replay.rows.size(), static_cast<std::size_t>(kFrames));
  int near_range_rows = 0;
  int pose_rows = 0;
  int far_rows = 0;
  for (std::size_t i = 0; i < static_cast<std::size_t>(kFrames); ++i) {
    for (const char* column : {"frame", "timestamp_ns", "mode", "symmetric_twins", "twin_by_continuity"})
      EXPECT_EQ(pose.at(i, column), replay.at(i, column)) << "frame " << i << " column " << column;
    if (!replay.at(i, "x_m").empty()) {  // replay leaves the pose empty when there is none
      ++pose_rows;
      for (const char* column : {"x_m", "y_m", "z_m", "qw", "qx", "qy", "qz", "yaw_deg", "pitch_deg",
                                 "roll_deg", "cov_0_0", "cov_2_3", "cov_5_5", "quality"})
        EXPECT_EQ(pose.at(i, column), replay.at(i, column)) << "frame " << i << " column " << column;
    }
    EXPECT_EQ(far.at(i, "valid"), replay.at(i, "far_valid")) << "frame " << i;
    if (far.at(i, "valid") == "1") {
      ++far_rows;
      for (const auto& [ours, theirs] : {std::pair{"azimuth_deg", "far_azimuth_deg"},
                                         {"elevation_deg", "far_elevation_deg"},
                                         {"distance_m", "far_distance_m"},
                                         {"cluster_pixels", "far_cluster_px"},
                                         {"cluster_count", "far_clusters"}})
        EXPECT_EQ(far.at(i, ours), replay.at(i, theirs)) << "frame " << i << " column " << ours;
    }
    near_range_rows += replay.at(i, "mode") == "near_range" ? 1 : 0;
  }
  std::printf("e2e: %d frames, %d with a pose, %d with a far-range fix, %d in near range\n", kFrames,
              pose_rows, far_rows, near_range_rows);
  EXPECT_GT(near_range_rows, 0) << "the sequence should reach near range (far range -> acquisition -> near)";
  EXPECT_GT(far_rows, 0);

  // ...so visnav-eval scores both the same. Two differences are by design and are bridged here, not hidden:
  // - status: visnav-replay reports the near-range tracker's verdict (a coasted frame is "lost", the
  //   acquisition's first pose "init"), telemetry the solution's (fsw/telemetry trackStatus: a valid pose is
  //   "tracking" without a fault, else "degraded"; no pose: "lost" in near range, else "init"). The replay
  //   rows are relabelled with the telemetry rule from their own mode, pose and fault_bits columns, and the
  //   monitor's status must be exactly that.
  // - the monitor records the far-range fix in its own file: its columns join the pose rows for visnav-eval.
  Table relabelled = replay;
  const int status_column = relabelled.column("status");
  ASSERT_GE(status_column, 0);
  for (std::size_t i = 0; i < relabelled.rows.size(); ++i) {
    const std::string status = !replay.at(i, "x_m").empty()
                                   ? (replay.at(i, "fault_bits") == "0" ? "tracking" : "degraded")
                                   : (replay.at(i, "mode") == "near_range" ? "lost" : "init");
    EXPECT_EQ(pose.at(i, "status"), status) << "frame " << i;
    relabelled.rows[i][static_cast<std::size_t>(status_column)] = status;
  }
  Table joined = pose;
  for (const char* column : {"far_valid", "far_azimuth_deg", "far_elevation_deg", "far_distance_m"})
    joined.header.push_back(column);
  for (std::size_t i = 0; i < joined.rows.size(); ++i)
    for (const char* column : {"valid", "azimuth_deg", "elevation_deg", "distance_m"})
      joined.rows[i].push_back(far.at(i, column));
  const std::string replay_for_eval = writeCsv(dir.path() + "/replay_telemetry_status.csv", relabelled);
  const std::string monitor_for_eval = writeCsv(dir.path() + "/monitor_with_far_range.csv", joined);
  const std::string eval_replay = dir.path() + "/eval_replay.json";
  const std::string eval_monitor = dir.path() + "/eval_monitor.json";
  // The envelopes depend on the truth only (not under test here) and cost seconds in the debug build: one
  // size (0 px, a single solve) on every 10th frame.
  for (const auto& [csv, json] : {std::pair{replay_for_eval, eval_replay}, {monitor_for_eval, eval_monitor}})
    EXPECT_EQ(run({VISNAV_EVAL, "--sequence", sequence, "--replay", csv, "--json", json, "--envelope-px", "0",
                   "--envelope-stride", "10"},
                  dir.path() + "/eval.txt", 120.0),
              0)
        << readText(dir.path() + "/eval.txt");
  const std::string summary = summaryWithoutPaths(eval_replay);
  EXPECT_NE(summary.find("\"tracking\": "), std::string::npos) << summary;
  EXPECT_EQ(summary, summaryWithoutPaths(eval_monitor));
}

}  // namespace
}  // namespace visnav::app
