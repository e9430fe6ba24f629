// NavigationPipeline's fusion of a near-range fit with the filter: the innovation gate, and the restart
// from a fit whose image evidence overrules it. The rest of the class: navigation_pipeline.cpp.
#include "visnav/navigation/navigation_pipeline.hpp"

namespace visnav::nav {

bool NavigationPipeline::fuseNearRange(const NearRangeResult& r, NearRangeCheck& check) {
  // The filter judges the measurement (NIS gate), but an innovation fault alone never throws away a
  // measurement whose image evidence is good: the image wins and the filter restarts from it.
  if (!(m_filter.initialised() && m_filter.attitudeKnown())) {
    // Nothing to check it against: an ambiguous fit does not start a track (box/9 began 20 deg off on a
    // flat-lit outline whose depth-mirrored pose fitted as well, and the filter then defended that pose).
    if ((r.flags & kFlagAmbiguous) != 0U) return false;
    m_filter.initialise(r.pose, r.covariance);
    return true;
  }
  // An ambiguous fit's mirrored rival judged by the same prediction, before the update moves it
  // (confirmBranch, mirror_resolved_by_prediction).
  if ((r.flags & kFlagAmbiguous) != 0U && m_params.navigation.mirror_resolved_by_prediction)
    m_mirror_nis = m_filter.poseNis(r.mirrored_rival, r.covariance);
  // Only a measurement with good image evidence may say the target moved more than the model allows (it
  // then also restarts the filter below); a weak one that disagrees may simply be wrong.
  const FilterUpdate u = m_filter.update(
      r.pose, r.covariance,
      check.evidence_good ? RejectedInnovation::kRaisesProcessNoise : RejectedInnovation::kIgnored);
  m_last_pose_update = u;
  check.innovation_checked = true;
  check.innovation_accepted = u.accepted;
  if (u.accepted) return true;
  const bool diverged = r.status == TrackStatus::kTracking &&
                        m_filter.consecutiveRejections() >=
                            static_cast<std::uint32_t>(m_params.navigation.filter_diverged_rejections);
  if (check.evidence_good || diverged) {
    restartFilter(r.pose, r.covariance);
    m_fit_restarted_filter = true;
    return true;
  }
  return false;  // weak evidence the filter also disputes: not delivered
}

void NavigationPipeline::restartFilter(const Pose& pose, const Mat6& covariance) {
  // With poses delivered on the two frames before, the filter restarts with the motion the three agree on
  // (a target approaching at 7 m/s, restarted at rest, was rejected again and again: case
  // approach_smallsat: 45 fits rejected, NIS 23-194); otherwise from this pose alone. Not from two: one fit
  // 0.7 m apart in depth from the one before read as 3.5 m/s, and the prediction runs away (campaign box/17).
  const DeliveredPose& middle = m_delivered[m_delivered_newest];
  const DeliveredPose& oldest = m_delivered[m_delivered_newest ^ 1U];
  if (m_previous_exposure_ns != 0 && middle.exposure_ns == m_previous_exposure_ns &&
      oldest.exposure_ns != 0 && oldest.exposure_ns < middle.exposure_ns &&
      m_filter.initialiseFromThree(
          oldest.pose, oldest.covariance, middle.pose, middle.covariance, pose, covariance,
          static_cast<double>(middle.exposure_ns - oldest.exposure_ns) * 1e-9,
          static_cast<double>(m_last_exposure_ns - middle.exposure_ns) * 1e-9) == Status::kOk)
    return;
  m_filter.initialise(pose, covariance);
}

}  // namespace visnav::nav
