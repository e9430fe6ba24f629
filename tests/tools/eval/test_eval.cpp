#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "visnav/eval/envelope.hpp"
#include "visnav/eval/evaluation.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/eval/report.hpp"

namespace visnav::eval {
namespace {

PinholeCamera vga() {
  return PinholeCamera(CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320, 240));
}

// The plate's outward normal is +z in the model frame: roll near 180 deg turns it towards the camera.
Pose plateTruth(double distance_m, double k) {
  return Pose::fromYpr({0.05 * std::sin(k), -0.1 + 0.02 * k, kPi - 0.08}, Vec3(0.3, -0.2, distance_m));
}

std::vector<TruthPose> trajectory(int n) {
  std::vector<TruthPose> truth;
  for (int i = 0; i < n; ++i) {
    const double z = 25.0 - 20.0 * i / (n - 1);
    truth.push_back({i, 1000000000LL * i, plateTruth(z, 0.1 * i)});
  }
  return truth;
}

// Debug + sanitizer builds run the LM ~1000x slower: evaluation tests sample 16 sign patterns per delta.
EvaluationOptions fastOptions() {
  EvaluationOptions o;
  o.envelope.max_exhaustive_offsets = 0;
  o.envelope.sampled_combinations = 8;
  return o;
}

std::vector<ReplayRow> perfectReplay(const std::vector<TruthPose>& truth) {
  std::vector<ReplayRow> rows;
  for (const TruthPose& t : truth)
    rows.push_back({t.frame, t.timestamp_ns, TrackStatus::kTracking, true, t.pose});
  return rows;
}

TEST(ReplayCsv, ColumnsAreFoundByNameInAnyOrder) {
  std::istringstream in(
      "cov_0_0,qz,status,extra,y_m,frame,qx,x_m,timestamp_ns,qw,z_m,qy,yaw_deg\n"
      "1.0,0,tracking,foo,-0.5,7,0,0.25,123,1,10,0,0\n"
      "\n"
      "1.0,,lost,bar,,8,,,456,,,,\n"
      "1.0,0.0,degraded,x,1,9,0.0,2,789,-1,12.5,0.0,0\r\n");
  std::vector<ReplayRow> rows;
  const LoadError err = parseReplayCsv(in, "r.csv", rows);
  ASSERT_TRUE(err.ok) << err.message;
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rows[0].frame, 7);
  EXPECT_EQ(rows[0].timestamp_ns, 123);
  EXPECT_EQ(rows[0].status, TrackStatus::kTracking);
  EXPECT_TRUE(rows[0].has_pose);
  EXPECT_DOUBLE_EQ(rows[0].pose.t_c_m.x(), 0.25);
  EXPECT_DOUBLE_EQ(rows[0].pose.t_c_m.y(), -0.5);
  EXPECT_DOUBLE_EQ(rows[0].pose.t_c_m.z(), 10.0);
  EXPECT_EQ(rows[1].status, TrackStatus::kLost);
  EXPECT_FALSE(rows[1].has_pose);
  EXPECT_EQ(rows[2].status, TrackStatus::kDegraded);
  EXPECT_TRUE(rows[2].pose.R_c_m.isApprox(Mat3::Identity()));  // q and -q are the same rotation
}

TEST(ReplayCsv, MissingColumnNamesFileLineAndColumn) {
  std::istringstream in("frame,status,x_m,y_m,z_m,qx,qy,qz\n0,tracking,0,0,1,0,0,0\n");
  std::vector<ReplayRow> rows;
  const LoadError err = parseReplayCsv(in, "replay.csv", rows);
  ASSERT_FALSE(err.ok);
  EXPECT_NE(err.message.find("replay.csv:1:"), std::string::npos) << err.message;
  EXPECT_NE(err.message.find("'qw'"), std::string::npos) << err.message;
}

TEST(ReplayCsv, BadNumberNamesLineAndColumn) {
  std::istringstream in(
      "frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,tracking,0,0,1,1,0,0,0\n1,tracking,0,0.1.2,1,1,0,0,0\n");
  std::vector<ReplayRow> rows;
  const LoadError err = parseReplayCsv(in, "replay.csv", rows);
  ASSERT_FALSE(err.ok);
  EXPECT_NE(err.message.find("replay.csv:3:"), std::string::npos) << err.message;
  EXPECT_NE(err.message.find("'y_m'"), std::string::npos) << err.message;
}

TEST(ReplayCsv, RejectsUnknownStatusDuplicatesAndEmptyTrackedPose) {
  const char* bad[] = {"frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,ok,0,0,1,1,0,0,0\n",
                       "frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,lost,,,,,,,\n0,lost,,,,,,,\n",
                       "frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,tracking,,,,,,,\n",
                       "frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,tracking,0,0\n", ""};
  for (const char* text : bad) {
    std::istringstream in(text);
    std::vector<ReplayRow> rows;
    EXPECT_FALSE(parseReplayCsv(in, "r.csv", rows).ok) << text;
  }
}

TEST(Metrics, WrapDegrees) {
  EXPECT_DOUBLE_EQ(wrapDeg180(0.0), 0.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(190.0), -170.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(-190.0), 170.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(-180.0), 180.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(540.0), 180.0);
  EXPECT_DOUBLE_EQ(wrapDeg180(-721.0), -1.0);
}

TEST(Metrics, PoseErrorWrapsAcrossPlusMinus180) {
  const Pose truth = Pose::fromYpr({179.0 * kRadPerDeg, 0.1, 179.5 * kRadPerDeg}, Vec3(1, 2, 3));
  const Pose est = Pose::fromYpr({-179.0 * kRadPerDeg, 0.1, -179.5 * kRadPerDeg}, Vec3(1.5, 2, 2));
  const AxisValues e = poseError(est, truth);
  EXPECT_NEAR(e[0], 0.5, 1e-12);
  EXPECT_NEAR(e[2], -1.0, 1e-12);
  EXPECT_NEAR(e[3], 2.0, 1e-9);
  EXPECT_NEAR(e[4], 0.0, 1e-9);
  EXPECT_NEAR(e[5], 1.0, 1e-9);
  EXPECT_GT(attitudeErrorDeg(est, truth), 1.0);
  EXPECT_LT(attitudeErrorDeg(est, truth), 3.0);
}

TEST(Metrics, StatsOnHandComputedExample) {
  // |values| sorted: 1 2 3 4 5; p95 rank = 0.95 * 4 = 3.8 -> 4 + 0.8 * (5 - 4).
  const ErrorStats s = absStats({3.0, -1.0, 2.0, -5.0, 4.0});
  EXPECT_EQ(s.count, 5);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.p95, 4.8);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  const ErrorStats even = absStats({-4.0, 1.0, 3.0, 2.0});
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.p95, 3.85);
  EXPECT_EQ(absStats({}).count, 0);
}

TEST(Metrics, FarRangeErrorOnHandComputedCases) {
  FarRangeError e;
  // Truth on the boresight at 100 m; 0.1 deg off in azimuth and 110 m: 0.1 deg, +10 %.
  ASSERT_TRUE(farRangeError(directionFromAzimuthElevation(0.1 * kRadPerDeg, 0.0), 110.0, Vec3(0, 0, 100), e));
  EXPECT_NEAR(e.direction_deg, 0.1, 1e-12);
  EXPECT_NEAR(e.distance_pct, 10.0, 1e-12);
  // t = (3, -4, 12): range 13, distance z = 12. The exact line of sight (az = atan2(3, 12), el =
  // atan2(4, hypot(3, 12))) at 13 m is 0 deg and +8.333 % (distance is along the boresight, not the range).
  const Vec3 u = directionFromAzimuthElevation(std::atan2(3.0, 12.0), std::atan2(4.0, std::hypot(3.0, 12.0)));
  EXPECT_NEAR((u - Vec3(3, -4, 12) / 13.0).norm(), 0.0, 1e-15);
  ASSERT_TRUE(farRangeError(5.0 * u, 13.0, Vec3(3, -4, 12), e));  // the direction need not be unit
  EXPECT_NEAR(e.direction_deg, 0.0, 1e-12);
  EXPECT_NEAR(e.distance_pct, 100.0 / 12.0, 1e-12);
  // Elevation is up-positive: +45 deg is (0, -1, 1) / sqrt(2); the truth (0, 1, 1) is 45 deg below: 90 deg
  // apart.
  ASSERT_TRUE(farRangeError(directionFromAzimuthElevation(0.0, kPi / 4), 9.0, Vec3(0, 1, 1), e));
  EXPECT_NEAR(e.direction_deg, 90.0, 1e-12);
  EXPECT_NEAR(e.distance_pct, 800.0, 1e-9);
  EXPECT_FALSE(farRangeError(Vec3(0, 0, 1), 10.0, Vec3(0, 0, -5), e));  // truth behind the camera
  EXPECT_FALSE(farRangeError(Vec3::Zero(), 10.0, Vec3(0, 0, 5), e));
}

TEST(ReplayCsv, ModeAndFarRangeColumnsAreOptional) {
  std::istringstream in(
      "frame,status,mode,x_m,y_m,z_m,qw,qx,qy,qz,fault_bits,far_valid,far_azimuth_deg,far_elevation_deg,"
      "far_distance_m\n"
      "0,init,standby,,,,,,,,0,0,0,0,0\n"
      "1,init,far_range,,,,,,,,0,1,-1.5,0.25,612.5\n"
      "2,tracking,near_range,0,0,5,1,0,0,0,0,,,,\n");
  std::vector<ReplayRow> rows;
  LoadError err = parseReplayCsv(in, "r.csv", rows);
  ASSERT_TRUE(err.ok) << err.message;
  ASSERT_EQ(rows.size(), 3U);
  EXPECT_EQ(rows[0].mode, ReplayMode::kStandby);
  EXPECT_FALSE(rows[0].far_valid);
  EXPECT_EQ(rows[1].mode, ReplayMode::kFarRange);
  EXPECT_TRUE(rows[1].far_valid);
  EXPECT_DOUBLE_EQ(rows[1].far_azimuth_deg, -1.5);
  EXPECT_DOUBLE_EQ(rows[1].far_elevation_deg, 0.25);
  EXPECT_DOUBLE_EQ(rows[1].far_distance_m, 612.5);
  EXPECT_EQ(rows[2].mode, ReplayMode::kNearRange);
  EXPECT_FALSE(rows[2].far_valid);
  // An old CSV (no mode, no far columns) still loads, with unknown mode.
  std::istringstream old("frame,status,x_m,y_m,z_m,qw,qx,qy,qz\n0,tracking,0,0,1,1,0,0,0\n");
  ASSERT_TRUE(parseReplayCsv(old, "old.csv", rows).ok);
  EXPECT_EQ(rows[0].mode, ReplayMode::kUnknown);
  EXPECT_FALSE(rows[0].far_valid);
  const char* bad[][2] = {
      {"frame,status,x_m,y_m,z_m,qw,qx,qy,qz,mode\n0,init,,,,,,,,far\n", "'mode'"},
      {"frame,status,x_m,y_m,z_m,qw,qx,qy,qz,far_valid,far_azimuth_deg,far_elevation_deg,far_distance_m\n"
       "0,init,,,,,,,,1,,0,100\n",
       "'far_azimuth_deg'"},
      {"frame,status,x_m,y_m,z_m,qw,qx,qy,qz,far_valid,far_azimuth_deg,far_elevation_deg\n",
       "'far_distance_m'"},
      {"frame,status,x_m,y_m,z_m,qw,qx,qy,qz,far_valid,far_azimuth_deg,far_elevation_deg,far_distance_m\n"
       "0,init,,,,,,,,yes,0,0,100\n",
       "'far_valid'"}};
  for (const auto& [text, column] : bad) {
    std::istringstream b(text);
    err = parseReplayCsv(b, "r.csv", rows);
    ASSERT_FALSE(err.ok) << text;
    EXPECT_NE(err.message.find(column), std::string::npos) << err.message;
  }
}

TEST(Envelope, PlateUsesItsFourVerticesExhaustively) {
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  EXPECT_EQ(envelopeVertices(plate, plateTruth(15.0, 0.0), 50.0).size(), 4U);
  // Back face, and a face beyond 50 deg obliquity, give nothing.
  EXPECT_TRUE(envelopeVertices(plate, Pose::fromYpr({0, 0, 0}, Vec3(0, 0, 15)), 50.0).empty());
  EXPECT_TRUE(envelopeVertices(plate, Pose::fromYpr({0, 0, kPi - 1.0}, Vec3(0, 0, 15)), 50.0).empty());
  EXPECT_EQ(envelopeVertices(plate, Pose::fromYpr({0, 0, kPi - 0.7}, Vec3(0, 0, 15)), 50.0).size(), 4U);
}

TEST(Envelope, MonotonicInDeltaAndZeroAtZero) {
  const PinholeCamera cam = vga();
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  EnvelopeSolver solver(cam, plate, EnvelopeOptions{});
  std::vector<FrameEnvelope> env;
  solver.compute(plateTruth(15.0, 0.3), {1.0, 0.25, 0.0}, env);
  ASSERT_EQ(env.size(), 3U);
  for (const FrameEnvelope& e : env) ASSERT_TRUE(e.valid);
  EXPECT_TRUE(env[0].exhaustive);
  EXPECT_EQ(env[0].combinations, 256);
  EXPECT_EQ(env[0].vertex_count, 4);
  EXPECT_LE(env[0].failed_solves, 8);
  for (int a = 0; a < kAxisCount; ++a) {
    EXPECT_GT(env[0].max_abs[a], 0.0) << axisName(a);
    EXPECT_LT(env[1].max_abs[a], env[0].max_abs[a]) << axisName(a);
    EXPECT_LT(env[2].max_abs[a], 1e-9) << axisName(a);
  }
  // 1 px at 15 m with f = 1000 px is 15 mm laterally; the near-frontal plate's tilt ambiguity couples in
  // more, and the distance error is larger still (paper fig. 6).
  EXPECT_GT(env[0].max_abs[0], 0.01);
  EXPECT_LT(env[0].max_abs[0], 0.1);
  EXPECT_GT(env[0].max_abs[2], env[0].max_abs[0]);
}

TEST(Envelope, BoxIsSampledDeterministically) {
  const PinholeCamera cam = vga();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  // Camera 20 m out along model (1, 1, 0), looking at the origin: faces +x and +y at ~46 deg obliquity,
  // 6 vertices -> 12 offsets -> sampled.
  const double h = 1.0 / std::sqrt(2.0);
  Pose truth;
  truth.R_c_m << -h, h, 0.0, 0.0, 0.0, -1.0, -h, -h, 0.0;  // rows: camera x, y, z in the model frame
  truth.t_c_m = Vec3(0.0, 0.0, 20.0);
  EXPECT_EQ(envelopeVertices(box, truth, 50.0).size(), 6U);
  EnvelopeSolver solver(cam, box, EnvelopeOptions{});
  std::vector<FrameEnvelope> a, b;
  solver.compute(truth, {1.0}, a);
  solver.compute(truth, {1.0}, b);
  ASSERT_TRUE(a[0].valid);
  EXPECT_FALSE(a[0].exhaustive);
  EXPECT_EQ(a[0].vertex_count, 6);
  EXPECT_EQ(a[0].combinations, 256 + 8);
  for (int k = 0; k < kAxisCount; ++k) {
    EXPECT_GT(a[0].max_abs[k], 0.0);
    EXPECT_EQ(a[0].max_abs[k], b[0].max_abs[k]);
  }
}

TEST(Evaluation, PerfectReplayIsAllInside) {
  const std::vector<TruthPose> truth = trajectory(12);
  const Evaluation ev =
      evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, perfectReplay(truth), fastOptions());
  const EvaluationSummary& s = ev.summary;
  EXPECT_EQ(s.frames_evaluated, 12);
  EXPECT_EQ(s.frames_tracking, 12);
  EXPECT_EQ(s.track_loss_count, 0);
  ASSERT_EQ(s.envelopes.size(), 2U);
  for (const EnvelopeSummary& e : s.envelopes) {
    EXPECT_EQ(e.frames_with_envelope, 12);
    EXPECT_EQ(e.inside_count, 12);
    EXPECT_DOUBLE_EQ(e.inside_fraction, 1.0);
  }
  for (int a = 0; a < kAxisCount; ++a) EXPECT_LT(s.axes[a].max, 1e-9);
  EXPECT_EQ(insideLine(s.envelopes[1]), "inside 0.25 px envelope (all 6 axes): 100.00% (12/12)");
  Requirements req;
  req.require_tracked_all = true;
  req.check_inside = true;
  req.min_inside_fraction = 0.995;
  req.inside_envelope_px = 0.25;
  for (const RequirementResult& r : checkRequirements(ev, req)) EXPECT_TRUE(r.passed) << r.name << r.detail;
}

TEST(Evaluation, OneFrameOffAndLostFramesAreDetected) {
  const std::vector<TruthPose> truth = trajectory(16);
  std::vector<ReplayRow> rows = perfectReplay(truth);
  rows[3].pose.t_c_m.x() += 0.5;
  rows[6].status = TrackStatus::kLost;
  rows.erase(rows.begin() + 10);         // frame 10 has no row
  rows[12].status = TrackStatus::kInit;  // frame 13
  EvaluationOptions options = fastOptions();
  options.envelope_stride = 2;
  const Evaluation ev = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, rows, options);
  const EvaluationSummary& s = ev.summary;
  EXPECT_EQ(s.frames_lost, 1);
  EXPECT_EQ(s.frames_missing, 1);
  EXPECT_EQ(s.frames_init, 1);
  EXPECT_EQ(s.track_loss_count, 2);
  EXPECT_EQ(s.axes[0].count, 13);
  EXPECT_NEAR(s.axes[0].max, 0.5, 1e-12);
  EXPECT_EQ(ev.frames[10].status, TrackStatus::kMissing);
  // Stride 2: envelopes on the 8 even frames; frame 3 has none; even frames 6 and 10 are not scored.
  EXPECT_FALSE(ev.frames[3].envelopes[0].valid);
  EXPECT_EQ(s.envelopes[0].frames_with_envelope, 8);
  EXPECT_EQ(s.envelopes[0].inside_count, 8 - 2);

  options.envelope_stride = 1;
  const Evaluation full = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, rows, options);
  EXPECT_FALSE(full.frames[3].inside[0]);
  EXPECT_TRUE(full.frames[4].inside[0]);
  EXPECT_EQ(full.summary.envelopes[0].inside_count, 16 - 4);
  Requirements req;
  req.require_tracked_all = true;
  req.check_inside = true;
  req.min_inside_fraction = 0.7;
  req.inside_envelope_px = 1.0;
  std::vector<RequirementResult> r = checkRequirements(full, req);
  ASSERT_EQ(r.size(), 2U);
  EXPECT_FALSE(r[0].passed);
  EXPECT_TRUE(r[1].passed);  // 12/16 = 75% >= 70%
  req.min_inside_fraction = 0.8;
  EXPECT_FALSE(checkRequirements(full, req)[1].passed);
  req.inside_envelope_px = 0.5;  // not computed
  r = checkRequirements(full, req);
  EXPECT_FALSE(r[1].passed);
  EXPECT_NE(r[1].detail.find("not computed"), std::string::npos);
}

TEST(Report, CsvAndJsonCarryEveryFrameAndEnvelope) {
  const std::vector<TruthPose> truth = trajectory(5);
  const Evaluation ev =
      evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, perfectReplay(truth), fastOptions());
  std::ostringstream csv;
  writeFrameCsv(csv, ev);
  std::istringstream lines(csv.str());
  std::string header, line;
  std::getline(lines, header);
  EXPECT_NE(header.find("env_0p25px_z_m"), std::string::npos) << header;
  EXPECT_NE(header.find("inside_1px"), std::string::npos) << header;
  const std::size_t columns = splitCsvLine(header).size();
  int n = 0;
  while (std::getline(lines, line)) {
    EXPECT_EQ(splitCsvLine(line).size(), columns);
    ++n;
  }
  EXPECT_EQ(n, 5);
  std::ostringstream json;
  writeSummaryJson(json, ev, {}, "seq", "r.csv");
  EXPECT_NE(json.str().find("\"inside_fraction\": 1"), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("\"passed\": true"), std::string::npos);
}

// Frames 0..7 at z = 25 - 2.5 i, y = 0 (elevation 0, so an azimuth offset is the direction error): standby,
// 3 far-range frames with hand-set errors, acquisition (far_valid 0), 3 tracked near-range frames.
TEST(Evaluation, FarRangeErrorsModesAndTransitions) {
  std::vector<TruthPose> truth;
  std::vector<ReplayRow> rows;
  const ReplayMode modes[8] = {ReplayMode::kStandby,   ReplayMode::kFarRange,    ReplayMode::kFarRange,
                               ReplayMode::kFarRange,  ReplayMode::kAcquisition, ReplayMode::kNearRange,
                               ReplayMode::kNearRange, ReplayMode::kNearRange};
  const double az_offset_deg[8] = {0, 0.03, 0.01, 0.2, 0.5, 0, 0, 0};
  const double distance_factor[8] = {1, 1.02, 1.05, 0.90, 1.5, 1, 1, 1};
  for (int i = 0; i < 8; ++i) {
    Pose p = plateTruth(25.0 - 2.5 * i, 0.1 * i);
    p.t_c_m.y() = 0.0;
    truth.push_back({i, 1000000LL * i, p});
    ReplayRow r{i, 1000000LL * i, i >= 5 ? TrackStatus::kTracking : TrackStatus::kInit, i >= 5, p};
    r.mode = modes[i];
    r.far_valid = i >= 1 && i <= 3;  // frame 4's far values are there but not valid: not scored
    r.far_azimuth_deg = std::atan2(p.t_c_m.x(), p.t_c_m.z()) * kDegPerRad + az_offset_deg[i];
    r.far_distance_m = p.t_c_m.z() * distance_factor[i];
    rows.push_back(r);
  }
  EvaluationOptions options = fastOptions();
  options.envelope_px.clear();
  const Evaluation ev = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, rows, options);
  const EvaluationSummary& s = ev.summary;
  // |direction| sorted 0.01 0.03 0.2: median 0.03, p95 at rank 1.9 = 0.03 + 0.9 * 0.17 = 0.183, max 0.2.
  EXPECT_EQ(s.far_direction_deg.count, 3);
  EXPECT_NEAR(s.far_direction_deg.median, 0.03, 1e-9);
  EXPECT_NEAR(s.far_direction_deg.p95, 0.183, 1e-9);
  EXPECT_NEAR(s.far_direction_deg.max, 0.2, 1e-9);
  // |distance| 2 5 10 [%]: median 5, p95 5 + 0.9 * 5 = 9.5, max 10; frame 3 is -10 % (signed per frame).
  EXPECT_NEAR(s.far_distance_pct.median, 5.0, 1e-9);
  EXPECT_NEAR(s.far_distance_pct.p95, 9.5, 1e-9);
  EXPECT_NEAR(ev.frames[3].far_error.distance_pct, -10.0, 1e-9);
  EXPECT_FALSE(ev.frames[4].far_scored);
  EXPECT_TRUE(s.has_modes);
  EXPECT_EQ(s.mode_frames, (std::array<int, kReplayModeCount>{1, 3, 1, 3}));
  EXPECT_EQ(s.final_mode, ReplayMode::kNearRange);
  ASSERT_EQ(s.transitions.size(), 3U);
  EXPECT_EQ(s.transitions[1].frame, 4);
  EXPECT_EQ(s.transitions[1].from, ReplayMode::kFarRange);
  EXPECT_EQ(s.transitions[1].to, ReplayMode::kAcquisition);
  EXPECT_NE(summaryText(ev).find("mode transitions: 3 (frame 1 standby -> far_range, frame 4 far_range -> "
                                 "acquisition, frame 5 acquisition -> near_range)"),
            std::string::npos)
      << summaryText(ev);

  Requirements req;
  req.check_far_direction = req.check_far_distance = req.check_final_mode = true;
  req.max_far_direction_median_deg = 0.0301;
  req.max_far_distance_median_pct = 5.001;
  for (const RequirementResult& r : checkRequirements(ev, req)) EXPECT_TRUE(r.passed) << r.name << r.detail;
  req.max_far_direction_median_deg = 0.0299;
  req.max_far_distance_median_pct = 4.999;
  req.final_mode = ReplayMode::kFarRange;
  for (const RequirementResult& r : checkRequirements(ev, req)) EXPECT_FALSE(r.passed) << r.name << r.detail;
  // No far-range frame to score and no mode column: the requirements fail instead of passing vacuously.
  std::vector<ReplayRow> plain = perfectReplay(truth);
  const Evaluation none = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, plain, options);
  for (const RequirementResult& r : checkRequirements(none, req))
    EXPECT_FALSE(r.passed) << r.name << r.detail;

  std::ostringstream csv, json;
  writeFrameCsv(csv, ev);
  EXPECT_NE(csv.str().find(",mode,far_scored,err_far_dir_deg,err_far_dist_pct\n"), std::string::npos);
  EXPECT_NE(csv.str().find(",far_range,1,0.2,-10\n"), std::string::npos) << csv.str();
  writeSummaryJson(json, ev, {}, "seq", "r.csv");
  EXPECT_NE(json.str().find("\"final\": \"near_range\""), std::string::npos) << json.str();
  EXPECT_NE(json.str().find("{\"frame\": 4, \"from\": \"far_range\", \"to\": \"acquisition\"}"),
            std::string::npos);
  EXPECT_NE(json.str().find("\"distance_pct\": {\"count\": 3, \"median\": 5"), std::string::npos);
}

// Issue 13 item 14: an empty replay scored medians of 0 and exit 0; now there is "nothing to score".
TEST(Evaluation, EmptyReplayHasNothingToScore) {
  const std::vector<TruthPose> truth = trajectory(5);
  const Evaluation empty = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, {}, fastOptions());
  ASSERT_NE(nothingToScore(empty.summary), nullptr);
  EXPECT_NE(std::string(nothingToScore(empty.summary)).find("nothing to score"), std::string::npos);
  std::vector<ReplayRow> rows = perfectReplay(truth);
  for (ReplayRow& r : rows) r.frame += 1000;  // rows on no truth frame
  const Evaluation elsewhere = evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, rows, fastOptions());
  EXPECT_NE(nothingToScore(elsewhere.summary), nullptr);
  const Evaluation scored =
      evaluate(vga(), makeRectanglePlate(2.3, 1.8), truth, perfectReplay(truth), fastOptions());
  EXPECT_EQ(nothingToScore(scored.summary), nullptr);
}

}  // namespace
}  // namespace visnav::eval
