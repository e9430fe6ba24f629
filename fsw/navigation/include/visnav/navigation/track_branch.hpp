// Which of two mirror poses a track follows, and whether that is still known (the last word on a pose's
// validity; navigation_pipeline.cpp calls it once per frame).
//
// Under weak perspective a pose and its depth-mirrored twin explain an outline equally well (the near-range
// tracker flags kFlagAmbiguous when the twin refits as well). Continuity with a known track tells them
// apart, but only while it is unbroken: carried through withheld or lost frames, a track can come out on the
// twin's branch, and then every frame fits with a tight covariance while wrong by tens of degrees (campaign
// octagon/174: 26 withheld frames, then 66 valid ones 34-140 deg off). So:
//   - the branch is known at start (the operator's pose) and after a confirmed acquisition or close-range
//     reacquisition (several frames, rivals refitted);
//   - any frame without a valid pose makes it unknown;
//   - confirm_frames consecutive valid frames whose fit is rival-free make it known again;
//   - while it is unknown no pose is valid.
#pragma once

namespace visnav::nav {

class TrackBranch {
 public:
  /// confirm_frames <= 0 switches the check off: every valid pose stays valid.
  void init(int confirm_frames) {
    m_confirm_frames = confirm_frames;
    setKnown();
  }
  /// The branch is known from outside (a given start pose).
  void setKnown() {
    m_known = true;
    m_rival_free_run = 0;
  }
  /// One frame. `valid`: the pose passed every other check; `rival_free`: its fit had corners and no
  /// mirrored rival; `confirmed`: it comes from an acquisition or reacquisition confirmation. Returns
  /// whether the pose may be delivered as valid.
  bool step(bool valid, bool rival_free, bool confirmed) {
    if (m_confirm_frames <= 0) return valid;
    if (!valid) {
      m_known = false;
      m_rival_free_run = 0;
      return false;
    }
    if (confirmed) m_known = true;
    if (!rival_free) {
      m_rival_free_run = 0;
    } else if (m_rival_free_run < m_confirm_frames && ++m_rival_free_run >= m_confirm_frames) {
      m_known = true;  // the count stops at confirm_frames: bounded, no overflow
    }
    return m_known;
  }
  bool known() const { return m_known; }

 private:
  int m_confirm_frames = 0;
  bool m_known = true;
  int m_rival_free_run = 0;
};

}  // namespace visnav::nav
