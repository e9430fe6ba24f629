// The FDIR monitor (fdir_monitor.hpp): each check's fault bit, persistence, the depth band derived from the
// model and the camera, and the image evidence that lets a measurement overrule the filter.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "visnav/geometry/polygon_model.hpp"
#include "visnav/navigation/fdir_monitor.hpp"

namespace visnav::nav {
namespace {

NearRangeResult goodNear() {
  NearRangeResult r;
  r.status = TrackStatus::kTracking;
  r.lines_total = 4;
  r.lines_used = 4;
  r.scanlines = 110;
  r.edge_points = 100;
  r.inlier_points = 95;
  r.rms_px = 0.1;
  r.pose.t_c_m = Vec3(0, 0, 10);
  return r;
}

/// A cube whose bounding sphere has `radius_m`.
PolygonModel cubeOfRadius(double radius_m) {
  const double half = radius_m / std::sqrt(3.0);
  return makeBox(half, half, half);
}

/// The monitor with default limits, a fault persisting after `frames` frames, for a 1.5 m cube at f 1000 px.
void initWithPersistence(FdirMonitor& f, int frames) {
  NavigationParams p;
  p.fault_persistence_frames = frames;
  f.init(p, cubeOfRadius(1.5), 1000.0);
}

TEST(Fdir, EachCheckRaisesItsBit) {
  FdirMonitor f;
  f.init(NavigationParams{}, cubeOfRadius(1.5), 1000.0);  // derived: outside the cube, up to 750 m
  NearRangeResult r = goodNear();
  NearRangeCheck c;
  c.near = &r;
  EXPECT_EQ(f.checkNearRange(c), 0U);
  r.lines_used = 2;
  EXPECT_EQ(f.checkNearRange(c), kFaultTooFewLines);
  r = goodNear();
  r.inlier_points = 40;
  EXPECT_EQ(f.checkNearRange(c), kFaultInlierRatio);
  r = goodNear();
  r.rms_px = 1.5;
  EXPECT_EQ(f.checkNearRange(c), kFaultResidual);
  r = goodNear();
  r.flags = kFlagSolverFailed;
  EXPECT_EQ(f.checkNearRange(c), kFaultNotConverged);
  r = goodNear();
  c.innovation_checked = true;
  c.innovation_accepted = false;
  EXPECT_EQ(f.checkNearRange(c), kFaultInnovation);
  c = NearRangeCheck{};
  c.near = &r;
  r.pose.t_c_m.z() = 0.5;
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  r = goodNear();
  c.centre_in_image = false;
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  // 100 ms of latency beyond one camera period (a free-running 5 Hz cycle takes frames 0-200 ms old).
  EXPECT_EQ(f.checkFrameAge(200.0, 0.0), kFaultFrameAge);  // period not known yet: latency alone
  EXPECT_EQ(f.checkFrameAge(10.0, 0.0), 0U);
  EXPECT_EQ(f.checkFrameAge(290.0, 200.0), 0U);  // the phase offset of free-running clocks is no fault
  EXPECT_EQ(f.checkFrameAge(310.0, 200.0), kFaultFrameAge);
  EXPECT_EQ(f.faultCounts()[2], 1U);  // residual
  EXPECT_EQ(f.faultCounts()[5], 2U);  // implausible twice
}

TEST(Fdir, PersistenceNeedsConsecutiveFaultyFrames) {
  FdirMonitor f;
  initWithPersistence(f, 3);
  NearRangeResult bad = goodNear();
  bad.lines_used = 0;
  NearRangeResult good = goodNear();
  NearRangeCheck cb, cg;
  cb.near = &bad;
  cg.near = &good;
  f.checkNearRange(cb);
  f.checkNearRange(cb);
  f.checkNearRange(cg);  // one good frame clears the run
  f.checkNearRange(cb);
  f.checkNearRange(cb);
  EXPECT_FALSE(f.faultPersisted());
  f.checkNearRange(cb);
  EXPECT_TRUE(f.faultPersisted());
  EXPECT_EQ(f.endFrame(), kFaultTooFewLines);
  EXPECT_EQ(f.endFrame(), 0U);  // the active set is per frame
}

TEST(Fdir, DepthBandIsDerivedFromModelAndCameraUnlessSet) {
  FdirMonitor f;
  f.init(NavigationParams{}, cubeOfRadius(0.25), 800.0);  // a 0.5 m lab object, f = 800 px
  EXPECT_DOUBLE_EQ(f.minDepthM(), 0.0);                   // the model's box is the limit
  EXPECT_DOUBLE_EQ(f.maxDepthM(), 100.0);                 // 0.5 m spans 4 px at 100 m
  NearRangeResult r = goodNear();
  r.pose.t_c_m.z() = 0.6;  // the lab sequence's depth: plausible, where a fixed 1 m band flagged it
  NearRangeCheck c;
  c.near = &r;
  EXPECT_EQ(f.checkNearRange(c), 0U);
  r.pose.t_c_m.z() = 0.1;  // the camera inside the cube (half side 0.144 m)
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  r.pose.t_c_m.z() = -0.6;  // behind the camera
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  r.pose.t_c_m.z() = 100.5;
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  r.pose.t_c_m.z() = 0.6;
  NavigationParams p;
  p.min_depth_m = 2.0;
  p.max_depth_m = 50.0;
  f.init(p, cubeOfRadius(0.25), 800.0);
  EXPECT_DOUBLE_EQ(f.minDepthM(), 2.0);
  EXPECT_DOUBLE_EQ(f.maxDepthM(), 50.0);
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
}

// A satellite with panels (case approach_smallsat): 11 m of panels across a 1.2 m body. In front of the body
// at 5 m the camera is well inside the 5.6 m bounding sphere and outside the target; 5 m along the panels'
// axis it would be inside them.
TEST(Fdir, TheLowerLimitIsTheModelsBoxNotItsBoundingSphere) {
  const PolygonModel panelled = makeBox(5.5, 0.6, 0.6);
  FdirMonitor f;
  f.init(NavigationParams{}, panelled, 1000.0);
  ASSERT_GT(panelled.boundingRadius(), 5.5);
  Pose in_front;
  in_front.t_c_m = Vec3(0.0, 0.0, 5.0);
  EXPECT_FALSE(f.cameraInsideTarget(in_front));
  NearRangeResult r = goodNear();
  r.pose = in_front;
  NearRangeCheck c;
  c.near = &r;
  EXPECT_EQ(f.checkNearRange(c), 0U);
  // The same depth with the model turned a quarter about y: the camera looks along the panels.
  Pose along = in_front;
  along.R_c_m = Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitY()).toRotationMatrix();
  EXPECT_TRUE(f.cameraInsideTarget(along));
  r.pose = along;
  EXPECT_EQ(f.checkNearRange(c), kFaultImplausible);
  along.t_c_m.z() = 5.6;  // just beyond the panel tip
  EXPECT_FALSE(f.cameraInsideTarget(along));
}

TEST(Fdir, EvidenceNeedsLinesInliersResidualAndSupport) {
  const NavigationParams p;
  NearRangeResult r = goodNear();
  EXPECT_TRUE(imageEvidenceGood(r, p));
  r.lines_used = 2;  // half the measured lines
  EXPECT_FALSE(imageEvidenceGood(r, p));
  r = goodNear();
  r.inlier_points = 50;
  EXPECT_FALSE(imageEvidenceGood(r, p));
  r = goodNear();
  r.rms_px = 0.9;
  EXPECT_FALSE(imageEvidenceGood(r, p));
  r = goodNear();
  r.scanlines = 400;  // most scanlines found nothing where the model has an edge
  EXPECT_FALSE(imageEvidenceGood(r, p));
  r = goodNear();
  r.status = TrackStatus::kLost;
  EXPECT_FALSE(imageEvidenceGood(r, p));
}

// The campaign's oracle counts the frames the image does not support by the first test they fail: each
// defect alone is named, in imageEvidenceGood's order, and kGood is exactly imageEvidenceGood.
TEST(Fdir, EvidenceVerdictNamesTheFirstTestAFitFails) {
  const NavigationParams p;
  const auto verdict = [&](const NearRangeResult& r) {
    const EvidenceVerdict v = imageEvidenceVerdict(r, p);
    EXPECT_EQ(v == EvidenceVerdict::kGood, imageEvidenceGood(r, p));
    return v;
  };
  NearRangeResult r = goodNear();
  EXPECT_EQ(verdict(r), EvidenceVerdict::kGood);
  r.status = TrackStatus::kLost;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kLost);
  r = goodNear();
  r.flags |= kFlagResidualFallback | kFlagAmbiguous;  // no corners comes first
  EXPECT_EQ(verdict(r), EvidenceVerdict::kNoCorners);
  r = goodNear();
  r.flags |= kFlagAmbiguous;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kMirrorRival);
  EXPECT_EQ(imageEvidenceVerdict(r, p, true), EvidenceVerdict::kGood);
  r = goodNear();
  r.lines_used = 2;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kFewLines);
  r = goodNear();
  r.inlier_points = 50;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kFewInliers);
  r = goodNear();
  r.rms_px = 0.9;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kHighResidual);
  r.rms_px = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(verdict(r), EvidenceVerdict::kHighResidual);
  r = goodNear();
  r.scanlines = 400;
  EXPECT_EQ(verdict(r), EvidenceVerdict::kWeakSupport);
  r = goodNear();
  r.pose.t_c_m = Vec3(0, 0, 10.0);
  r.covariance.topLeftCorner<3, 3>() = Mat3::Identity() * std::pow(5.0 * kRadPerDeg, 2);
  EXPECT_EQ(verdict(r), EvidenceVerdict::kUncertain);
  for (int v = 0; v < kEvidenceVerdictCount; ++v)
    EXPECT_STRNE(toString(static_cast<EvidenceVerdict>(v)), "?") << v;
}

// deliver_filtered_pose: only a fit with every selected line and no face seen as a narrow strip is complete;
// the other flags (a rival, the texture split) say nothing about how much of the outline it rests on.
TEST(Fdir, AFitIsCompleteWithEverySelectedLineAndNoNarrowFace) {
  NearRangeResult r = goodNear();
  EXPECT_TRUE(fitIsComplete(r));
  r.flags |= kFlagAmbiguous | kFlagTextureFallback;
  EXPECT_TRUE(fitIsComplete(r));
  r = goodNear();
  r.lines_used = 3;
  EXPECT_FALSE(fitIsComplete(r));
  r = goodNear();
  r.flags |= kFlagNarrowFace;
  EXPECT_FALSE(fitIsComplete(r));
  r = goodNear();
  r.status = TrackStatus::kLost;
  EXPECT_FALSE(fitIsComplete(r));
  r = goodNear();
  r.lines_used = r.lines_total = 0;
  EXPECT_FALSE(fitIsComplete(r));
}

// deliver_filtered_pose: a complete fit may be delivered as the filter's estimate; a partial one only with
// deliver_filtered_partial_fit, and never one its lines doubt, one on a track whose find is still doubted, or
// one beside a face seen as a narrow strip.
TEST(Fdir, AFitMayBeFilteredWhenCompleteOrPartialWithoutANarrowFace) {
  NavigationParams p;
  p.deliver_filtered_partial_fit = false;
  NearRangeResult r = goodNear();
  EXPECT_TRUE(fitMayBeFiltered(r, p, false));
  r.lines_total = 8;
  r.lines_used = 7;
  EXPECT_FALSE(fitMayBeFiltered(r, p, false));
  p.deliver_filtered_partial_fit = true;
  EXPECT_TRUE(fitMayBeFiltered(r, p, false));
  EXPECT_FALSE(fitMayBeFiltered(r, p, true)) << "a partial fit on a track whose find is still doubted";
  r.flags |= kFlagNarrowFace;
  EXPECT_FALSE(fitMayBeFiltered(r, p, false));
  r.flags = 0U;
  r.lines_used = 5;  // under doubt_min_line_fraction 0.75 of 8: the lines doubt it
  EXPECT_TRUE(fitDoubtedByItsLines(r, p));
  EXPECT_FALSE(fitMayBeFiltered(r, p, false));
  r.lines_total = 4;  // at most doubt_every_line_up_to: every line counts
  r.lines_used = 3;
  EXPECT_TRUE(fitDoubtedByItsLines(r, p));
  EXPECT_FALSE(fitMayBeFiltered(r, p, false));
  r = goodNear();
  r.status = TrackStatus::kLost;
  EXPECT_FALSE(fitMayBeFiltered(r, p, false));
  r = goodNear();
  EXPECT_TRUE(fitMayBeFiltered(r, p, true))
      << "a complete fit is filtered, its find doubted or not (stop 69)";
  p.deliver_filtered_pose = false;
  EXPECT_FALSE(fitMayBeFiltered(r, p, false)) << "nothing is filtered with deliver_filtered_pose off";
}

// An acquisition's hand-over is not confirmed by an outline-only fit that missed a line (campaign
// octagon/62: 120 deg off, 5 of 7 outline lines); an outline-only fit of every line, or a partial fit with
// interior edges, still confirms it.
TEST(Fdir, AHandOverIsNotConfirmedByAPartialOutline) {
  NavigationParams p;
  NearRangeResult r = goodNear();
  EXPECT_TRUE(fitConfirmsHandOver(r, p));
  r.flags = kFlagSilhouetteOnly;
  EXPECT_TRUE(fitConfirmsHandOver(r, p)) << "the whole outline";
  r.flags = kFlagLineRejected;
  EXPECT_TRUE(fitConfirmsHandOver(r, p)) << "a partial fit with interior edges";
  r.flags = kFlagSilhouetteOnly | kFlagLineRejected | kFlagTextureFallback;
  EXPECT_FALSE(fitConfirmsHandOver(r, p));
  p.handover_needs_whole_outline = false;
  EXPECT_TRUE(fitConfirmsHandOver(r, p)) << "off: any fit";
}

// A fit whose depth-mirrored rival fits as well overrules nothing on its own, but it may continue a fit
// that had no such rival (a reacquisition's confirmation); everything else is asked of it still.
TEST(Fdir, AnAmbiguousFitIsGoodEvidenceOnlyWhereItContinuesARivalFreeOne) {
  const NavigationParams p;
  NearRangeResult r = goodNear();
  ASSERT_TRUE(imageEvidenceGood(r, p));
  r.flags |= kFlagAmbiguous;
  EXPECT_FALSE(imageEvidenceGood(r, p));
  EXPECT_TRUE(imageEvidenceGood(r, p, true));
  r.rms_px = 0.9;
  EXPECT_FALSE(imageEvidenceGood(r, p, true));
  r = goodNear();
  r.flags |= kFlagAmbiguous | kFlagResidualFallback;  // no corners: continuity does not help
  EXPECT_FALSE(imageEvidenceGood(r, p, true));
}

TEST(Fdir, EvidenceNeedsAPoseCertainEnoughToBeDelivered) {
  // Lines, inliers, residual and support all good, but the fit's own covariance is looser than a valid pose
  // may be: it may not overrule the filter (the limits are the delivery limits, so it is read from them).
  const NavigationParams p;
  ASSERT_GT(p.max_valid_attitude_sigma_deg, 0.0);
  ASSERT_GT(p.max_valid_position_sigma_rel, 0.0);
  const double range = 10.0;
  const auto withSigmas = [&](double attitude_deg, double position_rel) {
    NearRangeResult r = goodNear();
    r.pose.t_c_m = Vec3(0, 0, range);
    // Equal per axis: sqrt(trace) = the given 1-sigma (nav_solution.hpp poseSigmas).
    const double a = attitude_deg * kRadPerDeg;
    const double t = position_rel * range;
    r.covariance.topLeftCorner<3, 3>() = Mat3::Identity() * (a * a / 3.0);
    r.covariance.bottomRightCorner<3, 3>() = Mat3::Identity() * (t * t / 3.0);
    return r;
  };
  const double limit_deg = p.max_valid_attitude_sigma_deg;
  const double limit_rel = p.max_valid_position_sigma_rel;
  EXPECT_TRUE(imageEvidenceGood(withSigmas(0.95 * limit_deg, 0.95 * limit_rel), p));
  EXPECT_FALSE(imageEvidenceGood(withSigmas(1.05 * limit_deg, 0.5 * limit_rel), p));
  EXPECT_FALSE(imageEvidenceGood(withSigmas(0.5 * limit_deg, 1.05 * limit_rel), p));
  // With the delivery limits switched off (0), so is this test.
  NavigationParams off = p;
  off.max_valid_attitude_sigma_deg = 0.0;
  off.max_valid_position_sigma_rel = 0.0;
  EXPECT_TRUE(imageEvidenceGood(withSigmas(10.0 * limit_deg, 10.0 * limit_rel), off));
}

// A fit that left out part of its outline is doubted: a quarter of its lines (doubt_min_line_fraction
// 0.75), or any line of a small outline (doubt_every_line_up_to 6; campaign box/191: 4 of 5 lines, 5.0-5.5
// deg off at 1.7-2.3 deg 1-sigma).
TEST(Fdir, AFitThatLeftOutPartOfItsOutlineIsDoubted) {
  const NavigationParams params;
  NearRangeResult r;
  r.status = TrackStatus::kTracking;
  const auto doubtedAt = [&](int used, int total, const NavigationParams& p) {
    r.lines_used = used;
    r.lines_total = total;
    return nearFitDoubted(r, 0U, p);
  };
  EXPECT_FALSE(doubtedAt(4, 4, params));
  EXPECT_FALSE(doubtedAt(6, 6, params));
  EXPECT_TRUE(doubtedAt(4, 5, params));
  EXPECT_TRUE(doubtedAt(5, 6, params));
  EXPECT_FALSE(doubtedAt(6, 7, params));
  EXPECT_FALSE(doubtedAt(6, 8, params)) << "a chamfered plate whose contrast passes through zero on 2 edges";
  EXPECT_TRUE(doubtedAt(5, 8, params));
  EXPECT_TRUE(doubtedAt(10, 14, params));
  NavigationParams fraction_only = params;  // the rule until 2026-12-01
  fraction_only.doubt_every_line_up_to = 0;
  EXPECT_FALSE(doubtedAt(4, 5, fraction_only));
  EXPECT_FALSE(doubtedAt(5, 6, fraction_only));
  EXPECT_TRUE(doubtedAt(2, 4, fraction_only));
  // The other two reasons, on a fit with all its lines.
  r.lines_used = r.lines_total = 6;
  EXPECT_TRUE(nearFitDoubted(r, kFaultInnovation, params));
  EXPECT_FALSE(nearFitDoubted(r, kFaultResidual, params));
  r.flags = kFlagNarrowFace;
  EXPECT_TRUE(nearFitDoubted(r, 0U, params));
  NavigationParams no_strip_doubt = params;
  no_strip_doubt.doubt_narrow_face = false;
  EXPECT_FALSE(nearFitDoubted(r, 0U, no_strip_doubt));
}

// A fit on 4 lines has no line to spare: where its pose predicts more than minimal_fit_max_missing_lines
// (2) selected lines the image did not give, it is not valid (campaign box/5030: 4 of 7, 10-13 deg off).
TEST(Fdir, AMinimalFitWhosePosePredictsLinesNotFoundIsNotValid) {
  const NavigationParams params;
  ASSERT_EQ(params.minimal_fit_max_missing_lines, 2);
  NearRangeResult r;
  r.status = TrackStatus::kTracking;
  const auto missesAt = [&](int used, int total, const NavigationParams& p) {
    r.lines_used = used;
    r.lines_total = total;
    return minimalFitMissesOutline(r, p);
  };
  EXPECT_FALSE(missesAt(4, 4, params)) << "a plate: its whole outline";
  EXPECT_FALSE(missesAt(4, 6, params)) << "two lines missing: allowed";
  EXPECT_TRUE(missesAt(4, 7, params)) << "the box/5030 case";
  EXPECT_TRUE(missesAt(3, 6, params));
  EXPECT_FALSE(missesAt(5, 9, params)) << "a fifth line checks the other four";
  EXPECT_FALSE(missesAt(6, 12, params));
  NavigationParams strict = params;
  strict.minimal_fit_max_missing_lines = 0;
  EXPECT_TRUE(missesAt(4, 5, strict));
  EXPECT_FALSE(missesAt(4, 4, strict));
  NavigationParams off = params;
  off.minimal_fit_max_missing_lines = -1;
  EXPECT_FALSE(missesAt(4, 12, off));
}

TEST(Fdir, InnovationAloneOnGoodEvidenceNeverPersists) {
  FdirMonitor f;
  initWithPersistence(f, 3);
  NearRangeResult r = goodNear();
  NearRangeCheck c;
  c.near = &r;
  c.innovation_checked = true;
  c.innovation_accepted = false;
  c.evidence_good = true;
  for (int i = 0; i < 10; ++i) EXPECT_EQ(f.checkNearRange(c), kFaultInnovation);  // flagged every frame...
  EXPECT_FALSE(f.faultPersisted());                                               // ...never persisting
  c.evidence_good = false;  // the same innovation on weak evidence counts
  for (int i = 0; i < 3; ++i) f.checkNearRange(c);
  EXPECT_TRUE(f.faultPersisted());
}

}  // namespace
}  // namespace visnav::nav
