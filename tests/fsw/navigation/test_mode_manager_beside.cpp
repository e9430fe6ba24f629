// The mode manager with [navigation] acquire_beside_far_range: the acquisition runs beside far range, so a
// failed or timed-out attempt changes no mode and only a confirmed pose does (far range -> near range).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mode_manager_test_support.hpp"
#include "visnav/navigation/mode_manager.hpp"

namespace visnav::nav {
namespace {

using test_support::farAt;

NavigationParams besideHandover() { return test_support::plateHandover(true); }

TEST(ModeManagerBeside, AHandOverStartsAnAcquisitionBesideFarRangeAndOnlyItsPoseChangesTheMode) {
  ModeManager m;
  ASSERT_TRUE(m.init(besideHandover()).ok);
  std::uint64_t frame = 0;
  for (int i = 0; i < 2; ++i) EXPECT_FALSE(m.step(farAt(28.0), ++frame));
  EXPECT_FALSE(m.acquiringBesideFarRange());
  EXPECT_FALSE(m.step(farAt(28.0), ++frame)) << "the hand-over itself changes no mode";
  EXPECT_TRUE(m.acquiringBesideFarRange());
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  // Frames of the attempt: far range's fixes are no hand-over of their own.
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(m.step(farAt(27.0), ++frame));
  EXPECT_TRUE(m.acquiringBesideFarRange());
  ModeInputs ok = farAt(27.0);
  ok.acquisition_succeeded = true;
  EXPECT_TRUE(m.step(ok, ++frame));
  EXPECT_EQ(m.mode(), NavMode::kNearRange);
  EXPECT_FALSE(m.acquiringBesideFarRange());
  EXPECT_EQ(m.transitionCount(), 1U);
  EXPECT_STREQ(m.lastTransition().reason.data(), "acquisition beside far range: first pose confirmed");
}

TEST(ModeManagerBeside, FailedAttemptsBackOffAsInTheAcquisitionModeWithoutAModeChange) {
  // The same waits as FailedAcquisitionsBackOffExponentially (3, then the hold-off 5, 10, 20, 40 plus one),
  // counted in far range: the failures are no mode changes.
  ModeManager m;
  NavigationParams p = besideHandover();
  p.acquire_retry_holdoff_max_frames = 80;
  ASSERT_TRUE(m.init(p).ok);
  ModeInputs failed = farAt(10.0);
  failed.acquisition_failed = true;
  std::uint64_t frame = 0;
  std::vector<std::uint64_t> far_frames;
  for (int attempt = 0; attempt < 5; ++attempt) {
    std::uint64_t waited = 0;
    while (!m.acquiringBesideFarRange() && waited < 1000) {
      m.step(farAt(10.0), ++frame);
      ++waited;
    }
    far_frames.push_back(waited);
    EXPECT_FALSE(m.step(failed, ++frame));
    EXPECT_FALSE(m.acquiringBesideFarRange());
  }
  EXPECT_EQ(far_frames, (std::vector<std::uint64_t>{3, 6, 11, 21, 41}));
  EXPECT_EQ(m.transitionCount(), 0U);
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
}

TEST(ModeManagerBeside, AnUnconfirmedAttemptIsRetriedNearerAndAnAttemptTimesOut) {
  ModeManager m;
  NavigationParams p = besideHandover();
  p.acquire_retry_holdoff_max_frames = 80;
  p.acquisition_timeout_frames = 4;
  ASSERT_TRUE(m.init(p).ok);
  std::uint64_t frame = 0;
  for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
  ASSERT_TRUE(m.acquiringBesideFarRange());
  ModeInputs unconfirmed = farAt(28.0);
  unconfirmed.acquisition_failed = true;
  unconfirmed.acquisition_unconfirmed = true;
  m.step(unconfirmed, ++frame);
  // Approaching 0.25 m a frame: the next attempt waits for half the hand-over distance (14 m).
  double d = 27.0;
  while (!m.acquiringBesideFarRange() && d > 5.0) {
    m.step(farAt(d), ++frame);
    d -= 0.25;
  }
  const double handed_over_at = d + 0.25;
  EXPECT_LT(handed_over_at, 14.0);
  EXPECT_GT(handed_over_at, 13.0);
  // Neither success nor failure within acquisition_timeout_frames: the attempt ends, far range goes on.
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(m.step(farAt(13.0), ++frame));
  EXPECT_TRUE(m.acquiringBesideFarRange());
  EXPECT_FALSE(m.step(farAt(13.0), ++frame));
  EXPECT_FALSE(m.acquiringBesideFarRange());
  EXPECT_EQ(m.mode(), NavMode::kFarRange);
  EXPECT_EQ(m.transitionCount(), 0U);
}

TEST(ModeManagerBeside, CommandsEndTheAttempt) {
  ModeManager m;
  ASSERT_TRUE(m.init(besideHandover()).ok);
  std::uint64_t frame = 0;
  for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
  ASSERT_TRUE(m.acquiringBesideFarRange());
  CommandAck ack;
  EXPECT_TRUE(m.command(ModeCommandKind::kForceFarRange, 1, true, ++frame, ack));
  EXPECT_FALSE(m.acquiringBesideFarRange()) << "far range alone, as commanded";
  for (int i = 0; i < 3; ++i) m.step(farAt(28.0), ++frame);
  ASSERT_TRUE(m.acquiringBesideFarRange());
  EXPECT_TRUE(m.command(ModeCommandKind::kReacquire, 2, true, ++frame, ack));
  EXPECT_EQ(m.mode(), NavMode::kAcquisition);
  EXPECT_FALSE(m.acquiringBesideFarRange()) << "the commanded acquisition replaces it";
  EXPECT_TRUE(m.command(ModeCommandKind::kStandby, 3, true, ++frame, ack));
  EXPECT_FALSE(m.acquiringBesideFarRange());
}

}  // namespace
}  // namespace visnav::nav
