// visnav-eval --far-range: a monitor recording's far-range file joined into the pose rows by frame.
#include <gtest/gtest.h>

#include <sstream>

#include "visnav/eval/replay_csv.hpp"

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

}  // namespace
}  // namespace visnav::eval
