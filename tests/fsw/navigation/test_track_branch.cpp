// TrackBranch: the mirror branch of a track is known at start, lost by any frame without a valid pose, and
// known again after confirm_frames consecutive rival-free valid frames or one confirmed (re)acquisition.
#include <gtest/gtest.h>

#include <string>

#include "visnav/navigation/track_branch.hpp"

namespace visnav::nav {
namespace {

// One letter per frame: 'V' valid and rival-free, 'A' valid but ambiguous (or a fit without corners),
// 'C' valid and confirmed by (re)acquisition but ambiguous, '-' no valid pose. Returns what was delivered
// as valid, one letter per frame: '1' valid, '0' withheld.
std::string run(TrackBranch& branch, const std::string& frames) {
  std::string out;
  for (const char c : frames) {
    const bool valid = c != '-';
    out += branch.step(valid, c == 'V', c == 'C') ? '1' : '0';
  }
  return out;
}

TEST(TrackBranch, KnownAtStartAmbiguousFramesContinueIt) {
  TrackBranch b;
  b.init(3);
  EXPECT_EQ(run(b, "VAAAVA"), "111111");
}

TEST(TrackBranch, ABreakNeedsConfirmFramesInARowWithoutARival) {
  TrackBranch b;
  b.init(3);
  // After the break: two rival-free frames are not enough, an ambiguous one restarts the count, the third
  // in a row confirms it (that frame is already valid).
  EXPECT_EQ(run(b, "V-VVAVVVA"), "100000011");
  EXPECT_TRUE(b.known());
  // Ambiguous frames alone never confirm (campaign octagon/174: the mirror branch fitted with a rival).
  EXPECT_EQ(run(b, "-AAAAAAAA"), "000000000");
  EXPECT_FALSE(b.known());
}

TEST(TrackBranch, AConfirmedReacquisitionRestoresItAtOnce) {
  TrackBranch b;
  b.init(3);
  EXPECT_EQ(run(b, "V--CAA-A"), "10011100");
}

TEST(TrackBranch, SetKnownIsAGivenPoseAndZeroSwitchesTheCheckOff) {
  TrackBranch b;
  b.init(3);
  EXPECT_EQ(run(b, "-AA"), "000");
  b.setKnown();
  EXPECT_EQ(run(b, "AA"), "11");
  TrackBranch off;
  off.init(0);
  EXPECT_EQ(run(off, "V-AA-A"), "101101");
}

TEST(TrackBranch, ARunLongerThanAnyIntStaysBounded) {
  TrackBranch b;
  b.init(1000);
  for (int i = 0; i < 100000; ++i) b.step(true, true, false);
  EXPECT_TRUE(b.known());
  EXPECT_EQ(run(b, "-"), "0");
  EXPECT_FALSE(b.known());
}

}  // namespace
}  // namespace visnav::nav
