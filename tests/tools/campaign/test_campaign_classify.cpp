// visnav-campaign: symmetry detection, per-frame verdicts on hand-made frames, recovery latency (with
// "never"), visibility, gates and options.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "visnav/campaign/classify.hpp"
#include "visnav/campaign/options.hpp"
#include "visnav/campaign/report.hpp"
#include "visnav/campaign/symmetry.hpp"
#include "visnav/geometry/model_symmetry.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::campaign {
namespace {

std::set<std::string> names(const std::vector<Symmetry>& s) {
  std::set<std::string> out;
  for (const Symmetry& x : s) out.insert(x.name);
  return out;
}

TEST(CampaignSymmetry, RectanglePlate) {
  // One-sided: x180 maps the vertices but turns the face away, so it is not a symmetry.
  EXPECT_EQ(names(modelSymmetries(makeRectanglePlate(2.3, 1.8))),
            (std::set<std::string>{"identity", "z180"}));
  EXPECT_FALSE(ModelSymmetries::isSymmetry(makeRectanglePlate(2.3, 1.8), expSo3(Vec3::UnitX() * kPi), 1e-6));
}

TEST(CampaignSymmetry, SquareAndOctagons) {
  EXPECT_EQ(names(modelSymmetries(makeRectanglePlate(2.0, 2.0))),
            (std::set<std::string>{"identity", "z90", "z180", "z270"}));
  const auto regular = modelSymmetries(makeRegularOctagonPlate(1.0));
  EXPECT_EQ(regular.size(), 8U);
  EXPECT_EQ(names(regular).count("z45"), 1U);
  EXPECT_EQ(names(regular).count("z315"), 1U);
  EXPECT_EQ(names(modelSymmetries(makeOctagonPlate(2.0, 1.2, 0.3))),
            (std::set<std::string>{"identity", "z180"}));
}

TEST(CampaignSymmetry, Boxes) {
  EXPECT_EQ(names(modelSymmetries(makeBox(0.8, 0.6, 0.5))),
            (std::set<std::string>{"identity", "x180", "y180", "z180"}));
  EXPECT_EQ(modelSymmetries(makeBox(0.5, 0.5, 0.5)).size(), 24U);  // the cube's rotation group
  EXPECT_EQ(modelSymmetries(makeBox(0.5, 0.5, 0.8)).size(), 8U);   // square prism: D4
  for (const Symmetry& s : modelSymmetries(makeBox(0.5, 0.5, 0.5)))
    EXPECT_NEAR((s.rotation * s.rotation.transpose() - Mat3::Identity()).norm(), 0.0, 1e-12);
}

TEST(CampaignSymmetry, Smallsat) {
  PolygonModel m;
  ASSERT_TRUE(io::loadModel(std::string(VISNAV_SOURCE_DIR) + "/config/models/smallsat_panels.toml", m).ok);
  EXPECT_EQ(names(modelSymmetries(m)), (std::set<std::string>{"identity", "z180"}));
}

TEST(CampaignSymmetry, AttitudeErrorModuloSymmetries) {
  const auto syms = modelSymmetries(makeRectanglePlate(2.3, 1.8));
  const Mat3 truth = expSo3(Vec3(0.3, -0.2, 2.0));
  const Mat3 twin = truth * expSo3(Vec3::UnitZ() * kPi);
  EXPECT_NEAR(attitudeErrorModuloDeg(twin, truth, syms), 0.0, 1e-9);
  EXPECT_NEAR(attitudeErrorModuloDeg(twin, truth, {}), 180.0, 1e-9);
  const Mat3 off = expSo3(Vec3::UnitX() * (5.0 * kRadPerDeg)) * twin;
  EXPECT_NEAR(attitudeErrorModuloDeg(off, truth, syms), 5.0, 1e-9);
}

FrameOutcome frame(bool valid, double pos_err_m, double att_deg,
                   nav::NavMode mode = nav::NavMode::kNearRange) {
  FrameOutcome f;
  f.visible = true;
  f.range_m = 10.0;
  f.pose_valid = valid;
  f.mode = mode;
  f.position_error_m = pos_err_m;
  f.attitude_error_deg = att_deg;
  classifyFrame(f);
  return f;
}

TEST(CampaignClassify, Verdicts) {
  const FrameOutcome good = frame(true, 0.05, 0.5);  // 0.5 %, 0.5 deg
  EXPECT_TRUE(good.tracked);
  EXPECT_TRUE(good.accurate);
  EXPECT_FALSE(good.wrong);
  const FrameOutcome coarse = frame(true, 0.3, 3.0);  // 3 %, 3 deg: tracked, not accurate
  EXPECT_TRUE(coarse.tracked);
  EXPECT_FALSE(coarse.accurate);
  EXPECT_FALSE(coarse.wrong);
  // A wrong pose is confidently wrong and not tracked: by position (6 % of 10 m) or attitude (6 deg).
  for (const FrameOutcome& w : {frame(true, 0.6, 0.1), frame(true, 0.01, 6.0)}) {
    EXPECT_TRUE(w.wrong);
    EXPECT_FALSE(w.tracked);
    EXPECT_FALSE(w.accurate);
  }
  // A lost frame (no pose) is neither tracked nor wrong, whatever its stale errors say.
  const FrameOutcome lost = frame(false, 5.0, 90.0);
  EXPECT_FALSE(lost.tracked);
  EXPECT_FALSE(lost.wrong);
  // Acquisition's delivered pose counts; far range never delivers a 6-DOF pose.
  EXPECT_TRUE(frame(true, 0.05, 0.5, nav::NavMode::kAcquisition).tracked);
  EXPECT_FALSE(frame(true, 0.05, 0.5, nav::NavMode::kFarRange).tracked);
  // Exactly at the bounds: 5 % and 5 deg are not wrong yet, 1 % and 1 deg still accurate.
  EXPECT_FALSE(frame(true, 0.5, 5.0).wrong);
  EXPECT_TRUE(frame(true, 0.1, 1.0).accurate);
}

std::vector<FrameOutcome> sequence(const std::string& pattern) {
  // T tracked, L visible but lost, E eclipsed, S slew frame (tracked), s slew frame (lost), - not visible.
  std::vector<FrameOutcome> out;
  for (char c : pattern) {
    FrameOutcome f;
    f.frame = static_cast<int>(out.size());
    f.visible = c != 'E' && c != '-';
    f.eclipsed = c == 'E';
    f.tracked = c == 'T' || c == 'S';
    f.slew = c == 'S' || c == 's';
    out.push_back(f);
  }
  return out;
}

TEST(CampaignRecovery, LossLatency) {
  const auto ev = recoveryEvents(sequence("TTLLLTT"), true);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, EventKind::kLoss);
  EXPECT_EQ(ev[0].frame, 2);
  EXPECT_EQ(ev[0].latency, 3);
}

TEST(CampaignRecovery, NeverWhenTheSceneEndsFirst) {
  const auto ev = recoveryEvents(sequence("TTTLLLL"), true);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].latency, -1);
}

TEST(CampaignRecovery, LostFromTheFirstFrameOfANearScene) {
  // Near scenes start from a given pose: failing at frame 0 is a loss (never recovered here).
  auto ev = recoveryEvents(sequence("LLLL"), true);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].frame, 0);
  EXPECT_EQ(ev[0].latency, -1);
  // Approach scenes have nothing to lose before their first track.
  EXPECT_TRUE(recoveryEvents(sequence("--LLLTT"), false).empty());
}

TEST(CampaignRecovery, EclipseEndAndSlew) {
  // Eclipse 2..4; visible again at 5, tracked at 7: one eclipse-end event of latency 2 (no separate loss).
  auto ev = recoveryEvents(sequence("TTEEELLTTsLTT"), true);
  ASSERT_EQ(ev.size(), 2U);
  EXPECT_EQ(ev[0].kind, EventKind::kEclipseEnd);
  EXPECT_EQ(ev[0].frame, 5);
  EXPECT_EQ(ev[0].latency, 2);
  EXPECT_EQ(ev[1].kind, EventKind::kSlew);
  EXPECT_EQ(ev[1].frame, 9);
  EXPECT_EQ(ev[1].latency, 2);
  // Tracked straight through a slew: latency 0. Tracked right after an eclipse: latency 0.
  ev = recoveryEvents(sequence("TTSTTEETT"), true);
  ASSERT_EQ(ev.size(), 2U);
  EXPECT_EQ(ev[0].latency, 0);
  EXPECT_EQ(ev[1].kind, EventKind::kEclipseEnd);
  EXPECT_EQ(ev[1].latency, 0);
}

TEST(CampaignRecovery, ReappearAfterLeavingTheView) {
  const auto ev = recoveryEvents(sequence("TT---LLT"), true);
  ASSERT_EQ(ev.size(), 1U);
  EXPECT_EQ(ev[0].kind, EventKind::kReappear);
  EXPECT_EQ(ev[0].frame, 5);
  EXPECT_EQ(ev[0].latency, 2);
}

TEST(CampaignVisibility, Rules) {
  CameraIntrinsics k;
  k.width_px = 640;
  k.height_px = 480;
  k.fx_px = k.fy_px = 1000.0;
  k.cx_px = 320.0;
  k.cy_px = 240.0;
  const PinholeCamera cam(k);
  const PolygonModel plate = makeRectanglePlate(2.0, 1.5);
  const Pose facing = Pose::fromYpr({0.0, 0.0, kPi}, Vec3(0.0, 0.0, 10.0));  // normal towards the camera
  EXPECT_TRUE(targetVisible(cam, plate, facing, false));
  EXPECT_FALSE(targetVisible(cam, plate, facing, true));                   // eclipsed
  const Pose back = Pose::fromYpr({0.0, 0.0, 0.0}, Vec3(0.0, 0.0, 10.0));  // seen from behind
  EXPECT_FALSE(targetVisible(cam, plate, back, false));
  Pose behind = facing;
  behind.t_c_m.z() = -10.0;
  EXPECT_FALSE(targetVisible(cam, plate, behind, false));
  Pose outside = facing;
  outside.t_c_m.x() = 4.0;  // centre 400 px right of the principal point
  EXPECT_FALSE(targetVisible(cam, plate, outside, false));
  Pose far = facing;
  far.t_c_m.z() = 130.0;  // 2 f R / z = 2 * 1000 * 1.25 / 130 = 19.2 px
  EXPECT_FALSE(targetVisible(cam, plate, far, false));
  far.t_c_m.z() = 120.0;  // 20.8 px
  EXPECT_TRUE(targetVisible(cam, plate, far, false));
  // In view, whatever its size (far range's yardstick): only the eclipse, the side and the image count.
  far.t_c_m.z() = 750.0;  // 3.3 px
  EXPECT_FALSE(targetVisible(cam, plate, far, false));
  EXPECT_TRUE(targetInView(cam, far, false));
  EXPECT_TRUE(targetInView(cam, back, false)) << "a plate seen from behind is still where far range looks";
  EXPECT_FALSE(targetInView(cam, far, true));
  EXPECT_FALSE(targetInView(cam, behind, false));
  EXPECT_FALSE(targetInView(cam, outside, false));
}

SceneRun fakeRun(const std::string& name, std::uint64_t seed, const std::string& pattern, int wrong_frames,
                 int mode_changes) {
  SceneRun r;
  r.scene.name = name;
  r.scene.seed = seed;
  r.scene.family = Family::kBox;
  r.result.frames = sequence(pattern);
  for (int i = 0; i < wrong_frames; ++i) r.result.frames[static_cast<std::size_t>(i)].wrong = true;
  for (FrameOutcome& f : r.result.frames) f.range_m = 10.0;
  r.result.mode_changes = mode_changes;
  summariseScene(r.scene, Thresholds{}, r.result);
  return r;
}

TEST(CampaignClassify, FarFixesOffTheTargetAreCountedOnFramesWithTheTargetInView) {
  SceneRun r = fakeRun("box/1", 1, "TTTTTTTTTT", 0, 0);
  for (std::size_t i = 0; i < r.result.frames.size(); ++i) {
    FrameOutcome& f = r.result.frames[i];
    f.in_view = i != 9;         // the last frame: eclipsed
    f.far_valid = i >= 4;       // fixes on frames 4-9
    f.far_off_target = i >= 7;  // 7 and 8 in view and off; 9 off but not in view
  }
  summariseScene(r.scene, Thresholds{}, r.result);
  EXPECT_EQ(r.result.far_fixes, 5);
  EXPECT_EQ(r.result.far_off_target, 2) << "frame 9's fix is off but the target was not in view";
}

TEST(CampaignRecovery, TheSummaryCountsEachKindAgainstTheFiveFrameTarget) {
  // The target per event: tracked again within kRecoveryTargetFrames (5) of a slew, an eclipse's
  // end, a reappearance or a loss. Scene 1: an eclipse end recovered in 2, a slew in 6; scene 2: a loss in
  // 1 and a loss never recovered. Printed as one summary line and in the JSON's groups.
  std::vector<SceneRun> runs;
  runs.push_back(fakeRun("box/1", 1, "TTEEELLTTsLLLLLLTT", 0, 0));
  runs.push_back(fakeRun("box/2", 2, "TTLTTTLLL", 0, 0));
  const auto groups = summariseAll(runs);
  ASSERT_FALSE(groups.empty());
  const GroupSummary& all = groups[0];
  const auto kind = [&](EventKind k) { return all.recovery_by_kind[static_cast<std::size_t>(k)]; };
  EXPECT_EQ(kind(EventKind::kEclipseEnd).events, 1);
  EXPECT_EQ(kind(EventKind::kEclipseEnd).within_target, 1);
  EXPECT_EQ(kind(EventKind::kSlew).events, 1);
  EXPECT_EQ(kind(EventKind::kSlew).within_target, 0) << "6 frames: over the target";
  EXPECT_EQ(kind(EventKind::kSlew).never, 0);
  EXPECT_EQ(kind(EventKind::kLoss).events, 2);
  EXPECT_EQ(kind(EventKind::kLoss).within_target, 1);
  EXPECT_EQ(kind(EventKind::kLoss).never, 1);
  EXPECT_EQ(kind(EventKind::kReappear).events, 0);
  EXPECT_EQ(all.recovery_events, 4);
  const std::string text = summaryTable(groups, runs, false);
  EXPECT_NE(text.find("slew 0/1 (0); eclipse_end 1/1 (0); reappear 0/0 (0); loss 1/2 (1)"), std::string::npos)
      << text;
  CampaignOptions o;
  o.timing = false;
  std::ostringstream json;
  writeJson(json, o, runs, groups, checkGates(runs, Gates{}));
  EXPECT_NE(json.str().find("\"loss\": {\"events\": 2, \"within_target\": 1, \"never\": 1}"),
            std::string::npos);
}

TEST(CampaignLossBudget, EachUntrackedFrameHasOneCauseAndTheyAddUpToTheUntracked) {
  // One expected frame per cause, in lossCause's order, then a tracked frame and an unexpected one.
  SceneRun r = fakeRun("box/1", 1, "LLLLLLLLLLT-", 0, 0);
  std::vector<FrameOutcome>& f = r.result.frames;
  for (FrameOutcome& x : f) {
    x.expected = x.visible;
    x.mode = nav::NavMode::kNearRange;
    x.has_candidate = true;
  }
  f[0].pose_valid = true;  // confidently wrong: valid, not tracked
  f[0].wrong = true;
  f[1].mode = nav::NavMode::kFarRange;
  f[2].has_candidate = false;
  f[3].withheld = nav::kWithheldUncertain | nav::kWithheldBranchUnknown;  // the first bit decides
  f[4].withheld = nav::kWithheldDoubted | nav::kWithheldBranchUnknown;
  f[5].withheld = nav::kWithheldFindDoubted;
  f[6].withheld = nav::kWithheldJumped | nav::kWithheldBranchUnknown;  // not the branch alone
  f[7].withheld = nav::kWithheldBranchUnknown;
  f[8].withheld = 0;  // computed, refused without a withheld reason
  f[9].withheld = nav::kWithheldEdgeOn;
  const LossCause want[] = {LossCause::kWrong,         LossCause::kNotNearRange, LossCause::kNoCandidate,
                            LossCause::kUncertain,     LossCause::kDoubted,      LossCause::kFindDoubted,
                            LossCause::kWithheldOther, LossCause::kBranch,       LossCause::kRejected,
                            LossCause::kWithheldOther};
  for (int i = 0; i < 10; ++i) EXPECT_EQ(lossCause(f[static_cast<std::size_t>(i)]), want[i]) << "frame " << i;
  summariseScene(r.scene, Thresholds{}, r.result);
  const std::vector<SceneRun> runs{r};
  const auto groups = summariseAll(runs);
  const GroupSummary& all = groups[0];
  int total = 0;
  for (const int n : all.untracked_by_cause) total += n;
  EXPECT_EQ(total, all.expected - all.tracked);
  EXPECT_EQ(total, 10);
  EXPECT_EQ(all.untracked_by_cause[static_cast<std::size_t>(LossCause::kWithheldOther)], 2);
  EXPECT_EQ(all.untracked_by_cause[static_cast<std::size_t>(LossCause::kBranch)], 1);
  const std::string table = lossTable(groups);
  EXPECT_NE(table.find("no_candidate"), std::string::npos) << table;
  std::ostringstream json;
  CampaignOptions o;
  o.timing = false;
  writeJson(json, o, runs, groups, checkGates(runs, Gates{}));
  EXPECT_NE(
      json.str().find("\"untracked_by_cause\": {\"wrong\": 1, \"not_near_range\": 1, \"no_candidate\": 1, "
                      "\"uncertain\": 1, \"doubted\": 1, \"find_doubted\": 1, \"withheld_other\": 2, "
                      "\"branch\": 1, \"rejected\": 1}"),
      std::string::npos);
}

TEST(CampaignGates, WorstSceneAndVerdicts) {
  std::vector<SceneRun> runs;
  runs.push_back(fakeRun("box/1", 1, "TTTTTTTTTT", 0, 0));
  runs.push_back(fakeRun("box/2", 2, "TTLLLLTTTT", 0, 1));
  runs.push_back(fakeRun("box/3", 3, "TTTTTTTTLL", 2, 6));
  Gates g;
  g.tracked_fraction = true;
  g.min_tracked_fraction = 0.99;
  g.no_confident_wrong = true;
  g.recovery = true;
  g.max_recovery_frames = 5;
  g.mode_changes = true;
  g.max_mode_changes = 4;
  const auto res = checkGates(runs, g);
  ASSERT_EQ(res.size(), 4U);
  EXPECT_FALSE(res[0].passed);
  EXPECT_EQ(res[0].worst->scene.name, "box/2");  // 6/10 tracked
  EXPECT_FALSE(res[1].passed);
  EXPECT_EQ(res[1].worst->scene.name, "box/3");
  EXPECT_FALSE(res[2].passed);  // box/3 never recovers
  EXPECT_EQ(res[2].worst->scene.name, "box/3");
  EXPECT_FALSE(res[3].passed);
  EXPECT_EQ(res[3].worst->scene.name, "box/3");
  g.min_tracked_fraction = 0.5;
  g.max_recovery_frames = 4;
  g.max_mode_changes = 6;
  std::vector<SceneRun> first_two(runs.begin(), runs.begin() + 2);
  for (const GateResult& r : checkGates(first_two, g)) EXPECT_TRUE(r.passed) << r.name << ": " << r.detail;
  // The outputs are deterministic text.
  const auto groups = summariseAll(runs);
  CampaignOptions o;
  o.runs = 3;
  o.timing = false;
  std::ostringstream a, b;
  writeJson(a, o, runs, groups, res);
  writeJson(b, o, runs, summariseAll(runs), checkGates(runs, g));
  EXPECT_NE(a.str().find("\"confidently_wrong_frames\": 2"), std::string::npos);
  std::ostringstream c1, c2;
  writeCsv(c1, runs);
  writeCsv(c2, runs);
  EXPECT_EQ(c1.str(), c2.str());
}

// Every row of scenes.csv and frames.csv has as many fields as its header names (frames.csv once named two
// far-range columns its rows did not have), with frames that have a far fix, a candidate, or neither.
TEST(CampaignReport, CsvRowsHaveTheHeadersFieldCount) {
  std::vector<SceneRun> runs;
  runs.push_back(fakeRun("box/1", 1, "TTLLTT", 1, 0));
  runs[0].result.frames[1].far_valid = true;
  runs[0].result.frames[1].far_distance_m = 123.0;
  runs[0].result.frames[2].has_candidate = true;
  runs[0].result.frames[2].attitude_sigma_deg = 3.0;
  runs[0].result.frames[3].has_nis = true;
  auto fields = [](const std::string& line) {
    int n = 1;
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') quoted = !quoted;
      n += (c == ',' && !quoted) ? 1 : 0;
    }
    return n;
  };
  for (const bool frames : {false, true}) {
    std::ostringstream o;
    if (frames)
      writeFramesCsv(o, runs);
    else
      writeCsv(o, runs);
    std::istringstream in(o.str());
    std::string header;
    ASSERT_TRUE(std::getline(in, header));
    int rows = 0;
    for (std::string line; std::getline(in, line); ++rows)
      EXPECT_EQ(fields(line), fields(header)) << (frames ? "frames.csv" : "scenes.csv") << " row " << rows;
    EXPECT_EQ(rows, frames ? 6 : 1);
  }
}

TEST(CampaignOptionsTest, Parsing) {
  CampaignOptions o;
  EXPECT_TRUE(parseArguments({"--runs", "3", "--seed", "9", "--families", "box,plate", "--jobs", "2"}, o).ok);
  EXPECT_EQ(o.runs, 3);
  EXPECT_EQ(o.seed, 9U);
  ASSERT_EQ(o.families.size(), 2U);
  EXPECT_EQ(o.families[0], Family::kBox);
  EXPECT_TRUE(parseArguments({"--case", "all"}, o).ok);
  EXPECT_EQ(o.cases.size(), caseNames().size());
  EXPECT_TRUE(
      parseArguments({"--runs", "1", "--require-tracked-fraction", "0.99", "--require-no-confident-wrong",
                      "--require-recovery-frames", "5", "--require-max-mode-changes", "4"},
                     o)
          .ok);
  EXPECT_TRUE(o.gates.tracked_fraction && o.gates.no_confident_wrong && o.gates.recovery &&
              o.gates.mode_changes);
  EXPECT_EQ(o.kind, SceneKind::kAny);
  EXPECT_TRUE(parseArguments({"--runs", "4", "--kind", "approach"}, o).ok);
  EXPECT_EQ(o.kind, SceneKind::kApproach);
  EXPECT_TRUE(parseArguments({"--runs", "4", "--kind", "near"}, o).ok);
  EXPECT_EQ(o.kind, SceneKind::kNear);
  EXPECT_FALSE(o.trace);
  EXPECT_TRUE(parseArguments({"--runs", "1", "--trace"}, o).ok);
  EXPECT_TRUE(o.trace);
  EXPECT_TRUE(o.dump_frames_dir.empty());
  EXPECT_TRUE(parseArguments({"--runs", "1", "--dump-frames", "/tmp/frames"}, o).ok);
  EXPECT_EQ(o.dump_frames_dir, "/tmp/frames");
  for (const std::vector<std::string>& bad :
       std::vector<std::vector<std::string>>{{},
                                             {"--runs", "0"},
                                             {"--runs", "x"},
                                             {"--runs", "2", "--families", "box,ball"},
                                             {"--runs", "2", "--families", "box,box"},
                                             {"--runs", "2", "--require-tracked-fraction", "1.5"},
                                             {"--runs", "2", "--seed", "-1"},
                                             {"--case", "nope"},
                                             {"--runs", "1", "--dump-frames"},
                                             {"--runs", "1", "--dump-frames", ""},
                                             {"--case", "slew_box", "--runs", "2"},
                                             {"--case", "slew_box", "--kind", "near"},
                                             {"--runs", "2", "--kind", "far"},
                                             {"--runs", "2", "--kind"},
                                             {"--runs", "2", "--bogus"},
                                             {"--runs"}}) {
    CampaignOptions x;
    EXPECT_FALSE(parseArguments(bad, x).ok) << (bad.empty() ? "(none)" : bad.back());
  }
}

}  // namespace
}  // namespace visnav::campaign
