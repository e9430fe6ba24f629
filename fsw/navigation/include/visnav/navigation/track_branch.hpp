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
//   - confirm_frames consecutive valid frames whose fit is rival-free make it known again; with
//     resume_after_continued, a withheld frame the track went through unbroken (its fit rival-free and
//     accepted by the filter, no jump: `continued`) does not restart that count: after a known branch the
//     next valid rival-free frame confirms it again, and a count under way goes on;
//   - while it is unknown no pose is valid.
#pragma once

#include <algorithm>

namespace visnav::nav {

class TrackBranch {
 public:
  /// confirm_frames <= 0 switches the check off: every valid pose stays valid.
  void init(int confirm_frames, bool resume_after_continued = false) {
    m_confirm_frames = confirm_frames;
    m_resume_after_continued = resume_after_continued;
    setKnown();
  }
  /// The branch is known from outside (a given start pose).
  void setKnown() {
    m_known = true;
    m_rival_free_run = 0;
  }
  /// One frame. `valid`: the pose passed every other check; `rival_free`: its fit had corners and no
  /// mirrored rival; `confirmed`: it comes from an acquisition or reacquisition confirmation; `continued`
  /// (with valid false): the track went through this frame unbroken. Returns whether the pose may be
  /// delivered as valid.
  bool step(bool valid, bool rival_free, bool confirmed, bool continued = false) {
    if (m_confirm_frames <= 0) return valid;
    if (!valid) {
      if (continued && m_resume_after_continued) {
        // A known branch needs one more rival-free frame; a count under way goes on from where it was.
        m_rival_free_run = m_known ? m_confirm_frames - 1 : std::min(m_rival_free_run, m_confirm_frames - 1);
      } else {
        m_rival_free_run = 0;
      }
      m_known = false;
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
  bool m_resume_after_continued = false;
  bool m_known = true;
  int m_rival_free_run = 0;
};

}  // namespace visnav::nav
