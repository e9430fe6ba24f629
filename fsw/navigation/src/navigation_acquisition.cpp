// NavigationPipeline's hand-over to the acquisition (fsw/navigation/README.md, "Modes and hysteresis"): the
// cue checked before a hand-over, the acquisition's frame in its own mode or beside far range
// (acquire_beside_far_range), and what its success or failure leaves. The rest of the class:
// navigation_pipeline.cpp.
#include "visnav/navigation/navigation_pipeline.hpp"

namespace visnav::nav {

void NavigationPipeline::checkCueBeforeHandOver(const MonoImage& image, ModeInputs& in) {
  // A cue without edge structure fails the acquisition on its first frame (no_target) and costs two mode
  // changes: 185 of the 341 failed acquisitions on the campaign's approaches (stop 49). Judged here, on this
  // frame's fix, it is refuted as that failure would refute it and the mode manager backs off, far range
  // still delivering.
  if (!m_params.navigation.check_cue_before_handover || !in.far_valid || !m_modes.handOverDue(in)) return;
  double edge_snr = 0.0;
  if (!m_acquisition.cueLacksEdges(m_last_far_fix, image, edge_snr)) return;
  in.cue_lacks_edges = true;
  m_far.refuteLastFix();
  m_far.reset();  // as after a failed acquisition: the next fix is searched afresh
}

void NavigationPipeline::runAcquisition(const MonoImage& image, std::uint64_t frame_number, NavSolution& out,
                                        ModeInputs& in) {
  acq::AcquisitionResult& result = m_acquisition_result;
  m_acquisition.step(image, frame_number, result);
  if (result.state == acq::AcquisitionState::kFailed) {
    in.acquisition_failed = true;
    m_fdir.raise(kFaultAcquisitionFailed);
    // Nothing with edges where far range pointed: that fix was clutter, and far range, restarted, would
    // pick the same region first again (campaign approaches: 12 mode changes on one clutter region). Edges
    // but no model pose confirmed there: the same region at the same size fails the same way, whether it is
    // clutter or a target still too small; far range takes it again once it has grown (farrange README).
    const bool unconfirmed = result.failure == acq::AcquisitionFailure::kNoCandidate ||
                             result.failure == acq::AcquisitionFailure::kNotConfirmed ||
                             result.failure == acq::AcquisitionFailure::kAmbiguous;
    in.acquisition_unconfirmed = unconfirmed;
    const bool refuted = result.failure == acq::AcquisitionFailure::kNoTarget ||
                         (unconfirmed && m_params.navigation.refute_unconfirmed_cue);
    if (refuted) m_far.refuteLastFix();
    // Not refuted: what far range tracked is still the best lead, and a fresh start would take the largest
    // plausible cluster, clutter as often as not (campaign octagon/164).
    m_far_track_kept = unconfirmed && !refuted && m_params.navigation.far_track_survives_unconfirmed;
    return;
  }
  if (result.state != acq::AcquisitionState::kSucceeded) return;
  in.acquisition_succeeded = true;
  m_filter.initialise(result.pose, result.covariance);
  deliver(result.pose, result.covariance, result.quality, out);
  // Not doubted like a reacquisition's find (navigation_reacquisition.cpp): the acquisition confirmed it over
  // its own frames with a rival check, and a far target's attitude 1-sigma stays above the doubted limit (the
  // plate of PipelineTest.AcquiresByItselfAndTracks at 24-26 m never met 1 deg), so its whole track would be
  // withheld.
  m_track_doubted = false;
  m_track_twin_by_continuity = result.twin_resolved_by_continuity;
  // Its confirmation frames all saw the same small target: a wrong pose confirmed there is as consistent
  // with itself as a right one. The first near-range fit, with the filter started from it, is the check
  // (campaign box/40: confirmed 44 deg off at 44.5 m, the next five fits rejected at NIS 79-146).
  if (m_params.navigation.acquisition_awaits_near_range) {
    if (out.pose_valid) out.withheld |= kWithheldAwaitsNearRange;
    out.pose_valid = false;
    m_acquisition_awaits_near = true;
  }
}

void NavigationPipeline::acquisitionBesideFarRange(bool started) {
  if (started) {
    m_acquisition.start(m_last_far_fix);
    return;
  }
  // Failed or timed out: far range restarts as on entering it after a failed acquisition (enterMode), or
  // keeps its track when that acquisition left it (far_track_survives_unconfirmed): here it never stopped.
  if (!m_far_track_kept) m_far.reset();
  m_far_track_kept = false;
}

}  // namespace visnav::nav
