// visnav-eval's optional inputs: --far-range (a monitor recording's far-range file joined into the pose rows
// by frame) and the replay's `nis` column (the filter's consistency, summarised).
#include <gtest/gtest.h>

#include <sstream>

#include "visnav/eval/evaluation.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/eval/report.hpp"

namespace visnav::eval {
namespace {

std::vector<ReplayRow> poseRows() {
  std::istringstream in(
      "frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n"
      "0,init,,,,,,,\n"
      "1,init,,,,,,,\n"
      "2,tracking,0,0,5,1,0,0,0\n");
  std::vector<ReplayRow> rows;
  EXPECT_TRUE(parseReplayCsv(in, "pose.csv", rows).ok);
  return rows;
}

TEST(FarRangeJoin, ValuesLandOnTheRowWithTheSameFrame) {
  std::vector<ReplayRow> rows = poseRows();
  // Monitor column order, with columns the join does not use; frame 7 has no pose row (a lost pose sample).
  std::istringstream in(
      "frame,timestamp_ns,mode,valid,flags,azimuth_deg,elevation_deg,distance_m,quality\n"
      "1,10,far_range,1,0,0.5,-0.25,700.5,1.0\n"
      "0,0,far_range,1,0,-1.5,2.0,750.0,1.0\n"
      "2,20,near_range,0,0,0,0,0,0\n"
      "7,70,far_range,1,0,1,1,1,1\n");
  int unmatched = -1;
  const LoadError err = parseFarRangeCsv(in, "far.csv", rows, unmatched);
  ASSERT_TRUE(err.ok) << err.message;
  EXPECT_EQ(unmatched, 1);
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_TRUE(rows[0].far_valid);
  EXPECT_DOUBLE_EQ(rows[0].far_azimuth_deg, -1.5);
  EXPECT_DOUBLE_EQ(rows[0].far_elevation_deg, 2.0);
  EXPECT_DOUBLE_EQ(rows[0].far_distance_m, 750.0);
  EXPECT_TRUE(rows[1].far_valid);
  EXPECT_DOUBLE_EQ(rows[1].far_azimuth_deg, 0.5);
  EXPECT_DOUBLE_EQ(rows[1].far_distance_m, 700.5);
  EXPECT_FALSE(rows[2].far_valid);
  EXPECT_TRUE(rows[2].has_pose);  // the pose columns are untouched
  EXPECT_DOUBLE_EQ(rows[2].pose.t_c_m.z(), 5.0);
}

TEST(FarRangeJoin, BadFilesNameLineAndProblemAndChangeNothing) {
  const char* bad[][2] = {
      {"frame,valid,azimuth_deg,elevation_deg\n0,1,0,0\n", "'distance_m'"},
      {"frame,valid,azimuth_deg,elevation_deg,distance_m\n0,1,0,x,5\n", "far.csv:2:"},
      {"frame,valid,azimuth_deg,elevation_deg,distance_m\n0,1,0,0,5\n0,1,0,0,5\n", "duplicate frame 0"},
      {"frame,valid,azimuth_deg,elevation_deg,distance_m\n0,yes,0,0,5\n", "'valid'"},
      {"frame,valid,azimuth_deg,elevation_deg,distance_m\n0,1,0,0,inf\n", "'distance_m'"},
      {"frame,valid,azimuth_deg,elevation_deg,distance_m\n0,1\n", "fields"},
      {"", "empty file"}};
  for (const auto& [text, expected] : bad) {
    std::vector<ReplayRow> rows = poseRows();
    std::istringstream in(text);
    int unmatched = 0;
    const LoadError err = parseFarRangeCsv(in, "far.csv", rows, unmatched);
    ASSERT_FALSE(err.ok) << text;
    EXPECT_NE(err.message.find(expected), std::string::npos) << err.message;
    for (const ReplayRow& row : rows) EXPECT_FALSE(row.far_valid) << text;
  }
  std::vector<ReplayRow> rows = poseRows();
  int unmatched = 0;
  const LoadError err = joinFarRangeCsv("/nonexistent/far.csv", rows, unmatched);
  ASSERT_FALSE(err.ok);
  EXPECT_NE(err.message.find("/nonexistent/far.csv"), std::string::npos) << err.message;
}

TEST(NisColumn, ParsedWhenPresentAndSummarised) {
  std::istringstream in(
      "frame,status,x_m,y_m,z_m,qw,qx,qy,qz,nis\n"
      "0,init,,,,,,,,\n"
      "1,tracking,0,0,5,1,0,0,0,2.5\n"
      "2,tracking,0,0,5,1,0,0,0,30\n"
      "3,tracking,0,0,5,1,0,0,0,4.5\n");
  std::vector<ReplayRow> rows;
  const LoadError err = parseReplayCsv(in, "r.csv", rows);
  ASSERT_TRUE(err.ok) << err.message;
  EXPECT_FALSE(rows[0].has_nis);
  ASSERT_TRUE(rows[2].has_nis);
  EXPECT_DOUBLE_EQ(rows[2].nis, 30.0);

  const PinholeCamera camera(CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320, 240));
  const PolygonModel plate = makeRectanglePlate(1.0, 1.0);
  std::vector<TruthPose> truth;
  for (int i = 0; i < 4; ++i) truth.push_back({i, 0, Pose::fromYpr({0, 0, kPi}, Vec3(0, 0, 5))});
  EvaluationOptions options;
  options.envelope_px.clear();
  const Evaluation ev = evaluate(camera, plate, truth, rows, options);
  const EvaluationSummary& s = ev.summary;
  EXPECT_EQ(s.nis.count, 3);
  EXPECT_DOUBLE_EQ(s.nis_mean, 37.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.nis.median, 4.5);
  EXPECT_DOUBLE_EQ(s.nis.max, 30.0);
  EXPECT_EQ(s.nis_above_gate, 1);
  EXPECT_NE(summaryText(ev).find("filter NIS (3 6-DOF updates)"), std::string::npos) << summaryText(ev);
}

TEST(NisColumn, AbsentOrBadValues) {
  std::istringstream old_replay("frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n1,tracking,0,0,5,1,0,0,0\n");
  std::vector<ReplayRow> rows;
  ASSERT_TRUE(parseReplayCsv(old_replay, "r.csv", rows).ok);
  EXPECT_FALSE(rows[0].has_nis);
  for (const char* bad : {"-1", "x", "nan", "inf"}) {
    std::istringstream in(std::string("frame,status,x_m,y_m,z_m,qw,qx,qy,qz,nis\n1,tracking,0,0,5,1,0,0,0,") +
                          bad + "\n");
    const LoadError err = parseReplayCsv(in, "r.csv", rows);
    ASSERT_FALSE(err.ok) << bad;
    EXPECT_NE(err.message.find("r.csv:2: column 'nis'"), std::string::npos) << err.message;
  }
}

}  // namespace
}  // namespace visnav::eval
