// Refuted fixes: regions acquisition looked at and found no edge structure in, passed over by the robust
// selection for refuted_fix_frames (longer when refuted again), following their cluster where it drifts
// (refuted_follow). Design notes: fsw/farrange/README.md, "Refuted fixes".
#include <algorithm>
#include <limits>

#include "visnav/farrange/far_range_estimator.hpp"

namespace visnav::far {

bool FarRangeEstimator::refuteLastFix() {
  if (m_params.refuted_fix_frames <= 0 || !m_has_last_fix) return false;
  // A fix found by its outline is edge structure: acquisition's no_target there says its window's edge SNR
  // is low, which a dim target still far off has too (campaign octagon/7022's approach: never acquired when
  // such fixes are refuted, 9 of 36 frames tracked when not).
  if (m_last_fix_outline && !m_params.outline_fix_refutable) return false;
  // The region refuted before that this fix lies in (refuted_follow: it followed its cluster), else the slot
  // that expires first, a free or expired one first.
  Refuted* slot = nullptr;
  if (m_params.refuted_follow)
    for (Refuted& r : m_refuted)
      if (r.refutations > 0 && sameRegion(r, m_last_fix_px, m_last_fix_pixels)) slot = &r;
  if (slot == nullptr) {
    slot = &m_refuted[0];
    for (Refuted& r : m_refuted)
      if (r.frames_left < slot->frames_left) slot = &r;
    slot->refutations = 0;
  }
  // Refuted again only counts for a cluster that did not grow since: an approaching target grows between
  // two refutations (campaign octagon/172: n 96 then 180, acquisition's edge SNR 3.9 and 4.4, under its 5),
  // clutter does not (plate/23's glint: 3921 then 3712).
  const bool static_since = slot->refutations > 0 && m_last_fix_pixels < kRefutedStaticGrowth * slot->pixels;
  slot->refutations = m_params.refuted_follow && static_since ? slot->refutations + 1 : 1;
  slot->centre_px = m_last_fix_px;
  slot->radius_px = std::max(m_last_fix_extent_px, m_params.gate_radius_px);
  slot->pixels = m_last_fix_pixels;
  slot->frames_left = m_params.refuted_fix_frames
                      << std::min(slot->refutations - 1, static_cast<int>(kMaxRefutedDoublings));
  m_has_last_fix = false;
  return true;
}

void FarRangeEstimator::clearRefuted() { m_refuted = {}; }

int FarRangeEstimator::refutedCount() const {
  int n = 0;
  for (const Refuted& r : m_refuted) n += r.frames_left > 0 ? 1 : 0;
  return n;
}

bool FarRangeEstimator::sameRegion(const Refuted& r, const Vec2& centre_px, double pixels) {
  // The same cluster again: centred within the refuted one's extent (its centre of mass wanders with the
  // threshold from frame to frame) and of a like size. A much smaller cluster beside a large clutter region
  // is something else: campaign plate/35's plate lay inside the extent of the glow refuted next to it.
  const double ratio = std::max(pixels, 1.0) / std::max(r.pixels, 1.0);
  return (centre_px - r.centre_px).norm() <= r.radius_px && ratio <= kRefutedSizeRatio &&
         ratio * kRefutedSizeRatio >= 1.0;
}

bool FarRangeEstimator::refuted(const Vec2& centre_px, double pixels) const {
  for (const Refuted& r : m_refuted)
    if (r.frames_left > 0 && sameRegion(r, centre_px, pixels)) return true;
  return false;
}

void FarRangeEstimator::followRefuted() {
  // Clutter that moves (glints drifting across the image) would leave its region within a few frames and be
  // handed over again; each remembered region moves with the like-sized cluster nearest its centre. Bounded:
  // kMaxRefuted x max_clusters distance tests.
  if (!m_params.refuted_follow) return;
  const auto& clusters = m_finder.clusters();
  for (Refuted& r : m_refuted) {
    if (r.refutations == 0) continue;
    double nearest = std::numeric_limits<double>::infinity();
    Vec2 centre = r.centre_px;
    for (const Cluster& c : clusters) {
      if (c.pixel_count < m_params.min_cluster_px) continue;
      const Vec2 at = usedCentre(c);
      const double distance = (at - r.centre_px).norm();
      if (distance < nearest && sameRegion(r, at, usedPixels(c))) {
        nearest = distance;
        centre = at;
      }
    }
    r.centre_px = centre;
  }
}

}  // namespace visnav::far
