// The mode manager (mode_manager.hpp): hand-over distances, hysteresis, acquisition back-off and retry,
// fall-back, time-outs and commands. The FDIR monitor's tests: test_fdir_monitor.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mode_manager_test_support.hpp"
#include "visnav/core/rng.hpp"
#include "visnav/navigation/mode_manager.hpp"

namespace visnav::nav {
namespace {

using test_support::farAt;

ModeInputs nearAt(double d) {
  ModeInputs in;
  in.depth_known = true;
  in.depth_m = d;
  return in;
}

// The acquisition in its own mode (far -> acquisition -> far or near); beside far range, the default since
// stop 85: test_mode_manager_beside.cpp.
NavigationParams plateHandover() { return test_support::plateHandover(false); }

TEST(ModeManager, HandOverDistancesAreDerivedFromTheTargetsApparentSize) {
  const NavigationParams plate = plateHandover();
  EXPECT_DOUBLE_EQ(plate.acquire_below_m, 30.0);
  EXPECT_DOUBLE_EQ(plate.far_range_above_m, 40.0);
  // The default 35 px: 42.9 m / 57.1 m for the plate, 168 m for the 5.87 m satellite with panels.
  const NavigationParams plate_default = NavigationParams{}.withDerivedHandover(1.5, 1000.0);
  EXPECT_NEAR(plate_default.acquire_below_m, 1500.0 / 35.0, 1e-9);
  EXPECT_NEAR(plate_default.far_range_above_m, 1500.0 / 26.25, 1e-9);
  // The hand-over to acquisition and near range's give-up are independent sizes: an earlier hand-over
  // does not make near range give up earlier.
  NavigationParams early;
  early.handover_radius_px = 50.0;
  const NavigationParams plate_early = early.withDerivedHandover(1.5, 1000.0);
  EXPECT_DOUBLE_EQ(plate_early.acquire_below_m, 30.0);
  EXPECT_NEAR(plate_early.far_range_above_m, plate_default.far_range_above_m, 1e-12);
  early.near_range_min_radius_px = 50.0;
  EXPECT_NE(early.crossCheck(), nullptr) << "no hysteresis gap must be refused";
  const NavigationParams sat = NavigationParams{}.withDerivedHandover(5.87, 1000.0);
  EXPECT_NEAR(sat.acquire_below_m, 5870.0 / 35.0, 1e-9);
  NavigationParams fixed;
  fixed.acquire_below_m = 20.0;
  fixed.far_range_above_m = 25.0;
  EXPECT_DOUBLE_EQ(fixed.withDerivedHandover(5.87, 1000.0).acquire_below_m, 20.0);  // set: kept
  ModeManager m;
  EXPECT_FALSE(m.init(NavigationParams{}).ok) << "underived zero thresholds must not reach the mode manager";
}

TEST(ModeManager, FarRangeHandsOverOnlyAfterEnterFramesBelowTheThreshold) {
  ModeManager m;
  ASSERT_TRUE(m.init(plateHandover()).ok);
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  EXPECT_FALSE(m.step(farAt(29.0), 1));
  EXPECT_FALSE(m.step(farAt(29.0), 2));
  EXPECT_FALSE(m.step(farAt(31.0), 3));  // the count restarts
  EXPECT_FALSE(m.step(farAt(29.0), 4));
  EXPECT_FALSE(m.step(farAt(29.0), 5));
  EXPECT_TRUE(m.step(farAt(29.0), 6));
  EXPECT_EQ(m.mode(), NavMode::kAcquisition);
  EXPECT_EQ(m.lastTransition().frame_number, 6U);
  EXPECT_STREQ(m.lastTransition().reason.data(), "far range: target close enough");
  EXPECT_EQ(m.transitionCount(), 1U);
}

// A frame without a far-range fix (coasting on a dim outline) neither counts nor restarts the count; the
// hand-over itself waits for a fix (close_count_survives_gaps; off by default, a gap restarts the count).
TEST(ModeManager, AFrameWithoutAFixHoldsTheCountBelowTheHandOver) {
  const ModeInputs no_fix;  // far_valid false
  NavigationParams gaps = plateHandover();
  gaps.close_count_survives_gaps = true;
  ModeManager m;
  ASSERT_TRUE(m.init(gaps).ok);
  EXPECT_FALSE(m.step(farAt(29.0), 1));
  EXPECT_FALSE(m.step(no_fix, 2));
  EXPECT_FALSE(m.step(farAt(29.0), 3));
  EXPECT_FALSE(m.step(no_fix, 4));
  EXPECT_FALSE(m.handOverDue(no_fix)) << "two fixes: not yet";
  EXPECT_TRUE(m.handOverDue(farAt(29.0)));
  EXPECT_TRUE(m.step(farAt(29.0), 5));
  EXPECT_EQ(m.mode(), NavMode::kAcquisition);

  ModeManager held;  // two fixes below, a gap, a third fix: handed over (the strict rule starts again)
  ASSERT_TRUE(held.init(gaps).ok);
  NavigationParams strict = plateHandover();
  strict.close_count_survives_gaps = false;
  ModeManager reset;
  ASSERT_TRUE(reset.init(strict).ok);
  for (std::uint64_t f = 1; f <= 2; ++f) {
    EXPECT_FALSE(held.step(farAt(29.0), f));
    EXPECT_FALSE(reset.step(farAt(29.0), f));
  }
  EXPECT_FALSE(held.step(no_fix, 3));
  EXPECT_FALSE(reset.step(no_fix, 3));
  EXPECT_TRUE(held.step(farAt(29.0), 4));
  EXPECT_FALSE(reset.step(farAt(29.0), 4)) << "the gap restarted the count";
  EXPECT_FALSE(reset.step(farAt(29.0), 5));
  EXPECT_TRUE(reset.step(farAt(29.0), 6));
  // A fix beyond the hand-over still restarts it.
  ModeManager beyond;
  ASSERT_TRUE(beyond.init(gaps).ok);
  EXPECT_FALSE(beyond.step(farAt(29.0), 1));
  EXPECT_FALSE(beyond.step(farAt(29.0), 2));
  EXPECT_FALSE(beyond.step(farAt(31.0), 3));
  EXPECT_FALSE(beyond.step(no_fix, 4));
  EXPECT_FALSE(beyond.step(farAt(29.0), 5));
}

TEST(ModeManager, FailedAcquisitionsBackOffExponentially) {
  // A far-range cue that keeps fooling acquisition (campaign box/2: a 750 m approach that flipped far range
  // <-> acquisition 60 times): every failure doubles the wait before the next hand-over, 5, 10, 20, ...
  ModeManager m;
  NavigationParams p = plateHandover();
  p.acquire_retry_holdoff_max_frames = 80;  // the cap this test walks up to
  ASSERT_TRUE(m.init(p).ok);
  ModeInputs failed;
  failed.acquisition_failed = true;
  std::uint64_t frame = 0;
  std::vector<std::uint64_t> far_frames;  // frames spent in far range before each hand-over
  for (int attempt = 0; attempt < 6; ++attempt) {
    std::uint64_t waited = 0;
    while (m.mode() == NavMode::kFarRange && waited < 1000) {
      m.step(farAt(10.0), ++frame);
      ++waited;
    }
    ASSERT_EQ(m.mode(), NavMode::kAcquisition);
    far_frames.push_back(waited);
    m.step(failed, ++frame);
    ASSERT_EQ(m.mode(), NavMode::kFarRange);
  }
  // The first hand-over needs enter_frames (3); then the hold-off (5, 10, 20, 40, 80 frames) plus one.
  const std::vector<std::uint64_t> expected = {3, 6, 11, 21, 41, 81};
  EXPECT_EQ(far_frames, expected);
  // Success clears it: the next failure waits the base hold-off again.
  m.step(farAt(10.0), ++frame);
  for (int i = 0; i < 100 && m.mode() == NavMode::kFarRange; ++i) m.step(farAt(10.0), ++frame);
  ModeInputs ok;
  ok.acquisition_succeeded = true;
  m.step(ok, ++frame);
  ASSERT_EQ(m.mode(), NavMode::kNearRange);
  ModeInputs persisted;
  persisted.near_fault_persisted = true;
  m.step(persisted, ++frame);
  ASSERT_EQ(m.mode(), NavMode::kFarRange);
  std::uint64_t waited = 0;
  while (m.mode() == NavMode::kFarRange && waited < 1000) {
    m.step(farAt(10.0), ++frame);
    ++waited;
  }
  EXPECT_EQ(waited, 3U);
}

// A cue the acquisition would fail on its first frame (no edge structure: check_cue_before_handover) is
// refused in far range: no transition, the same back-off as a failed acquisition, and counted.
TEST(ModeManager, AHandOverRefusedForACueWithoutEdgesBacksOffWithoutLeavingFarRange) {
  NavigationParams p = plateHandover();
  p.refused_handover_escalates_backoff = true;  // the refusals double the wait as failures do
  ModeManager m;
  ASSERT_TRUE(m.init(p).ok);
  ModeInputs bare = farAt(10.0);
  bare.cue_lacks_edges = true;
  std::uint64_t frame = 0;
  std::vector<std::uint64_t> waits;  // frames in far range before each due hand-over
  for (int attempt = 0; attempt < 4; ++attempt) {
    std::uint64_t waited = 0;
    while (!m.handOverDue(farAt(10.0)) && waited < 1000) {
      EXPECT_FALSE(m.step(farAt(10.0), ++frame));
      ++waited;
    }
    EXPECT_FALSE(m.step(bare, ++frame)) << "refused: no mode change";
    EXPECT_EQ(m.mode(), NavMode::kFarRange);
    waits.push_back(waited + 1U);
  }
  // As FailedAcquisitionsBackOffExponentially's hand-overs: 3, then the hold-off (5, 10, 20) plus one.
  EXPECT_EQ(waits, (std::vector<std::uint64_t>{3, 6, 11, 21}));
  EXPECT_EQ(m.refusedHandOvers(), 4U);
  EXPECT_EQ(m.transitionCount(), 0U);
  EXPECT_FALSE(m.handOverDue(nearAt(10.0))) << "no far fix, nothing due";
  // A cue with edges is handed over when due, as before.
  std::uint64_t waited = 0;
  while (m.mode() == NavMode::kFarRange && waited < 1000) {
    m.step(farAt(10.0), ++frame);
    ++waited;
  }
  EXPECT_EQ(waited, 41U);
  EXPECT_EQ(m.mode(), NavMode::kAcquisition);
  m.reset();
  EXPECT_EQ(m.refusedHandOvers(), 0U);
}

TEST(ModeManager, AnUnconfirmedAcquisitionIsRetriedOnceTheTargetHasComeNearer) {
  // Case approach_smallsat: acquisition saw the satellite at 157 m but could confirm no pose (no_candidate),
  // then again at 122 m (ambiguous); at 69 m it succeeded. After such a failure the next hand-over waits
  // until far range reads acquire_retry_growth (2) times nearer than the last hand-over, or for the longest
  // back-off (acquire_retry_holdoff_max_frames) when the target holds its range. A failure without edges
  // (no_target) only backs off.
  for (const bool unconfirmed : {true, false}) {
    ModeManager m;
    NavigationParams approach = plateHandover();
    approach.acquire_retry_holdoff_max_frames = 80;  // longer than the 52 frames to 14 m
    ASSERT_TRUE(m.init(approach).ok);
    std::uint64_t frame = 0;
    for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
    ASSERT_EQ(m.mode(), NavMode::kAcquisition);
    ModeInputs failed;
    failed.acquisition_failed = true;
    failed.acquisition_unconfirmed = unconfirmed;
    m.step(failed, ++frame);
    ASSERT_EQ(m.mode(), NavMode::kFarRange);
    // Approaching 0.25 m a frame from 27 m: the back-off alone hands over after 6 frames (at 25.5 m); the
    // retry rule waits for 14 m (half of 28 m).
    double d = 27.0;
    while (m.mode() == NavMode::kFarRange && d > 5.0) {
      m.step(farAt(d), ++frame);
      d -= 0.25;
    }
    ASSERT_EQ(m.mode(), NavMode::kAcquisition);
    const double handed_over_at = d + 0.25;
    if (unconfirmed) {
      EXPECT_LT(handed_over_at, 14.0);
      EXPECT_GT(handed_over_at, 13.0);
    } else {
      EXPECT_GT(handed_over_at, 25.0);
    }
  }
  // A target that holds its range is tried again after the longest back-off.
  NavigationParams p = plateHandover();
  ModeManager m;
  ASSERT_TRUE(m.init(p).ok);
  std::uint64_t frame = 0;
  for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
  ModeInputs failed;
  failed.acquisition_failed = true;
  failed.acquisition_unconfirmed = true;
  m.step(failed, ++frame);
  std::uint64_t waited = 0;
  while (m.mode() == NavMode::kFarRange && waited < 1000) {
    m.step(farAt(28.0), ++frame);
    ++waited;
  }
  EXPECT_EQ(waited, static_cast<std::uint64_t>(p.acquire_retry_holdoff_max_frames) + 1U);
  // Switched off (<= 1): the back-off alone.
  p.acquire_retry_growth = 1.0;
  ASSERT_TRUE(m.init(p).ok);
  for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
  m.step(failed, ++frame);
  waited = 0;
  while (m.mode() == NavMode::kFarRange && waited < 1000) {
    m.step(farAt(28.0), ++frame);
    ++waited;
  }
  EXPECT_EQ(waited, 6U);
}

TEST(ModeManager, ARefusedHandOverWaitsTheBackOffOfTheFailuresSoFarWithoutDoublingIt) {
  // refused_handover_escalates_backoff off: a refusal changes no mode, so it does not double the wait;
  // it waits what the acquisitions that failed so far earned (campaign approaches: refusals of a few noisy
  // pixels far out had grown the wait to 80 frames by the time the target was near enough).
  NavigationParams p = plateHandover();
  p.refused_handover_escalates_backoff = false;
  ModeManager m;
  ASSERT_TRUE(m.init(p).ok);
  ModeInputs bare = farAt(10.0);
  bare.cue_lacks_edges = true;
  std::uint64_t frame = 0;
  // Frames in far range until the next hand-over is due, counting the frame it is due on.
  const auto waitUntilDue = [&m, &frame]() {
    std::uint64_t waited = 1;
    for (; !m.handOverDue(farAt(10.0)) && waited < 1000; ++waited) m.step(farAt(10.0), ++frame);
    return waited;
  };
  std::vector<std::uint64_t> waits;
  for (int attempt = 0; attempt < 3; ++attempt) {
    waits.push_back(waitUntilDue());
    EXPECT_FALSE(m.step(bare, ++frame)) << "refused: no mode change";
  }
  EXPECT_EQ(waits, (std::vector<std::uint64_t>{3, 6, 6})) << "3, then the base hold-off (5) plus one";
  // A cue with edges is handed over when due; its acquisition fails: that failure doubles the wait.
  waits.clear();
  waits.push_back(waitUntilDue());
  m.step(farAt(10.0), ++frame);
  ASSERT_EQ(m.mode(), NavMode::kAcquisition);
  ModeInputs failed;
  failed.acquisition_failed = true;
  m.step(failed, ++frame);
  ASSERT_EQ(m.mode(), NavMode::kFarRange);
  for (int attempt = 0; attempt < 3; ++attempt) {
    waits.push_back(waitUntilDue());
    EXPECT_FALSE(m.step(bare, ++frame));
  }
  EXPECT_EQ(waits, (std::vector<std::uint64_t>{6, 6, 11, 11}))
      << "after one failed acquisition the refusals wait 10 frames, and no more";
  EXPECT_EQ(m.refusedHandOvers(), 6U);
  EXPECT_EQ(m.transitionCount(), 2U);
}

TEST(ModeManager, NoiseAroundAThresholdNeverChatters) {
  // A range estimate oscillating with +-3 m noise around 35 m, between the two thresholds' midpoint:
  // after the first hand-over no further transition may happen.
  ModeManager m;
  ASSERT_TRUE(m.init(plateHandover()).ok);
  Pcg32 rng(3);
  for (int i = 0; i < 10; ++i) m.step(farAt(25.0), static_cast<std::uint64_t>(i));
  ModeInputs ok;
  ok.acquisition_succeeded = true;
  m.step(ok, 10);
  ASSERT_EQ(m.mode(), NavMode::kNearRange);
  const std::uint64_t before = m.transitionCount();
  for (int i = 11; i < 2000; ++i)
    m.step(nearAt(35.0 + 3.0 * (2.0 * rng.uniform() - 1.0)), static_cast<std::uint64_t>(i));
  EXPECT_EQ(m.transitionCount(), before);
  EXPECT_EQ(m.mode(), NavMode::kNearRange);
}

TEST(ModeManager, NearRangeFallsBackOnPersistentFaultAndOnDistance) {
  ModeManager m;
  NavigationParams p = plateHandover();
  p.start_mode = static_cast<int>(NavMode::kNearRange);
  ASSERT_TRUE(m.init(p).ok);
  ModeInputs fault = nearAt(10.0);
  fault.near_fault_persisted = true;
  EXPECT_TRUE(m.step(fault, 1));
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  EXPECT_STREQ(m.lastTransition().reason.data(), "near range: persistent fault");

  m.transition(NavMode::kNearRange, "test", 2);
  for (int i = 0; i < p.enter_frames - 1; ++i) EXPECT_FALSE(m.step(nearAt(41.0), 3));
  EXPECT_TRUE(m.step(nearAt(41.0), 4));
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
}

TEST(ModeManager, AcquisitionTimesOut) {
  ModeManager m;
  NavigationParams p = plateHandover();
  p.start_mode = static_cast<int>(NavMode::kAcquisition);
  p.acquisition_timeout_frames = 4;
  ASSERT_TRUE(m.init(p).ok);
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(m.step(ModeInputs{}, static_cast<std::uint64_t>(i)));
  EXPECT_TRUE(m.step(ModeInputs{}, 3));
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  EXPECT_STREQ(m.lastTransition().reason.data(), "acquisition: timeout");
}

TEST(ModeManager, CommandsAreValidatedAndAcknowledged) {
  ModeManager m;
  ASSERT_TRUE(m.init(plateHandover()).ok);
  CommandAck ack;
  EXPECT_FALSE(m.command(ModeCommandKind::kResume, 7, false, 1, ack));
  EXPECT_EQ(ack.command_id, 7U);
  EXPECT_STREQ(ack.reason.data(), "not in standby");
  EXPECT_FALSE(m.command(ModeCommandKind::kReacquire, 8, false, 1, ack));
  EXPECT_STREQ(ack.reason.data(), "no far-range fix to acquire from");
  EXPECT_TRUE(m.command(ModeCommandKind::kStandby, 9, false, 2, ack));
  EXPECT_EQ(m.mode(), NavMode::kStandby);
  for (int i = 0; i < 10; ++i) m.step(farAt(5.0), 3);  // standby ignores the estimators
  EXPECT_EQ(m.mode(), NavMode::kStandby);
  EXPECT_FALSE(m.command(ModeCommandKind::kForceFarRange, 10, true, 4, ack));
  EXPECT_TRUE(m.command(ModeCommandKind::kResume, 11, false, 5, ack));
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  EXPECT_TRUE(m.command(ModeCommandKind::kReacquire, 12, true, 6, ack));
  EXPECT_EQ(m.mode(), NavMode::kAcquisition);
  EXPECT_STREQ(ack.reason.data(), "ok");
  EXPECT_FALSE(m.command(static_cast<ModeCommandKind>(42), 13, true, 7, ack));
  EXPECT_STREQ(ack.reason.data(), "unknown command");
}

TEST(ModeManager, InitRejectsThresholdsWithoutHysteresis) {
  ModeManager m;
  NavigationParams p = plateHandover();
  p.far_range_above_m = p.acquire_below_m;
  EXPECT_FALSE(m.init(p).ok);
}

}  // namespace
}  // namespace visnav::nav
