// Which cluster is the target: the published rule (most circular, eq. 15), the robust rule (size and
// shape checks, gate around the prediction, size consistency) and the robust track's recheck against the
// whole frame. Design notes: fsw/farrange/README.md.
#include <algorithm>
#include <cmath>

#include "visnav/farrange/far_range_estimator.hpp"

namespace visnav::far {
Vec2 FarRangeEstimator::usedCentre(const Cluster& c) const {
  return m_params.fill_holes && c.filled_count > 0 ? c.filled_com_px : c.com_px;
}

bool FarRangeEstimator::touchesImageBorder(const Cluster& c) const {
  return c.x_min == 0 || c.y_min == 0 || c.x_max == m_camera.width() - 1 || c.y_max == m_camera.height() - 1;
}

int FarRangeEstimator::usedPixels(const Cluster& c) const {
  if (!m_robust || !m_params.fill_holes || c.filled_count <= 0) return c.pixel_count;
  const double n = c.filled_count - m_params.outline_discount * c.boundary_count;
  return std::max(1, static_cast<int>(std::lround(n)));
}

OutlineSharpness FarRangeEstimator::sharpnessOf(const Cluster& c) const {
  if (c.sharpness_known) return c.sharpness;
  // Only a solid cluster: rays from the centre of a sparse one (a satellite's thin panels at a few hundred
  // metres, 315 px over a 20 px radius) cross thin strips, whose 2 h step is no body's edge.
  constexpr double kPi = 3.141592653589793;
  const int n = c.filled_count > 0 ? c.filled_count : c.pixel_count;
  if (m_frame.empty()) return {};
  c.sharpness = n < kMinSharpnessFill * kPi * c.max_radius_px * c.max_radius_px
                    ? OutlineSharpness{}
                    : measureOutlineSharpness(m_frame, usedCentre(c), c.max_radius_px);
  c.sharpness_known = true;
  return c.sharpness;
}

bool FarRangeEstimator::lacksSharpOutline(const Cluster& c) const {
  if (!(m_params.min_outline_sharpness > 0.0)) return false;
  const OutlineSharpness s = sharpnessOf(c);
  return s.measured && s.ratio < m_params.min_outline_sharpness;
}

bool FarRangeEstimator::passedOver(const Cluster& c, std::uint32_t& flags) const {
  if (!refuted(usedCentre(c), usedPixels(c))) return false;
  flags |= kFlagRefutedSkipped;
  return true;
}

int FarRangeEstimator::selectPaper() const {
  // Sec. III-B: "we pick the cluster with the highest circularity measure".
  int best = -1;
  double best_c = -1.0;
  const auto& clusters = m_finder.clusters();
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    if (clusters[i].circularity > best_c) {
      best_c = clusters[i].circularity;
      best = static_cast<int>(i);
    }
  }
  return best;
}

void FarRangeEstimator::prepareCandidates() {
  if (!m_params.fill_holes) return;
  for (Cluster& c : m_finder.clusters()) {
    if (c.pixel_count >= m_params.min_cluster_px) m_finder.fillHoles(c);
  }
}

FarRangeEstimator::Gate FarRangeEstimator::currentGate() const {
  Gate g;
  const Track& t = m_track;
  if (m_has_prediction) {
    g.active = true;
    g.centre_px = m_prediction_px;
    g.size_px = m_prediction_size_px;
    g.half_extent_px = t.active ? t.half_extent_px : std::sqrt(m_prediction_size_px);
  } else if (t.active) {
    g.active = true;
    // Constant velocity in the image over the frames since the last accepted target.
    g.centre_px = t.position_px + t.velocity_px * static_cast<double>(1 + t.misses);
    g.size_px = t.size_px;
    g.half_extent_px = t.half_extent_px;
  }
  // The gate widens with every frame without a target.
  g.radius_px = (m_params.gate_radius_px + m_params.gate_extent_factor * g.half_extent_px) *
                static_cast<double>(1 + t.misses);
  return g;
}

int FarRangeEstimator::selectRobust(const Gate& gate, std::uint32_t& flags) {
  const auto& clusters = m_finder.clusters();
  int best = -1;
  int second = -1;
  double best_score = 0.0;
  double second_score = 0.0;
  if (gate.active) {
    // Tracked: inside the gate and of the expected size; score = normalised distance + size mismatch.
    const double log_ratio_limit = std::log(std::max(m_params.max_size_ratio, 1.000001));
    for (std::size_t i = 0; i < clusters.size(); ++i) {
      const Cluster& c = clusters[i];
      if (c.pixel_count < m_params.min_cluster_px) continue;
      if (passedOver(c, flags) || lacksSharpOutline(c)) continue;
      const double offset = (usedCentre(c) - gate.centre_px).norm();
      if (offset > gate.radius_px) continue;
      const double log_ratio = std::abs(std::log(usedPixels(c) / std::max(gate.size_px, 1.0)));
      if (log_ratio > log_ratio_limit) continue;
      const double score = offset / gate.radius_px + log_ratio / log_ratio_limit;  // lower is better
      if (best < 0 || score < best_score) {
        second = best;
        second_score = best_score;
        best = static_cast<int>(i);
        best_score = score;
      } else if (second < 0 || score < second_score) {
        second = static_cast<int>(i);
        second_score = score;
      }
    }
    if (best >= 0) flags |= kFlagGated;
    if (second >= 0 && second_score < best_score + 0.25) flags |= kFlagAmbiguous;
    return best;
  }
  // No track: the largest cluster that is neither tiny (noise, glints) nor line-like (clutter edges).
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const Cluster& c = clusters[i];
    if (c.pixel_count < m_params.min_cluster_px || c.axis_ratio > m_params.max_axis_ratio) continue;
    if (passedOver(c, flags) || lacksSharpOutline(c)) continue;
    const double size = usedPixels(c);
    if (best < 0 || size > best_score) {
      second = best;
      second_score = best_score;
      best = static_cast<int>(i);
      best_score = size;
    } else if (second < 0 || size > second_score) {
      second = static_cast<int>(i);
      second_score = size;
    }
  }
  if (best >= 0) flags |= kFlagUnconfirmed;
  if (second >= 0 && second_score >= 0.7 * best_score) flags |= kFlagAmbiguous;
  return best;
}

int FarRangeEstimator::recheckTrack(const MonoImage& image, const Gate& gate, FarRangeResult& out) {
  // A track holds what it was started on. Taken before the target was visible (or while it was a few
  // pixels), that is clutter, and the gate then never looks anywhere else: campaign plate/64 held a blob 22
  // deg off, read at 40 m, for the whole approach while the plate came from 750 m to 6 m (never handed
  // over). The whole frame's largest plausible cluster, the rule without a track, takes the track over
  // only when it lies outside the gate, is far larger than the tracked n and reads near enough for the
  // acquisition to look at it, and only from a track that did not grow since the last check: an
  // approaching target grows (plate/64 closed 2 % of its range a frame, 750 -> 631.6 m in 8 frames: n 1.5
  // times in 10 frames), a stationary glow or
  // blob does not. Acquisition, which refutes a cue without edge structure (refuteLastFix), judges it.
  m_track.frames_since_check = 0;
  const double tracked_n = std::max(m_track.size_px, 1.0);
  const double grown = tracked_n / std::max(m_track.size_at_check, 1.0);
  m_track.size_at_check = tracked_n;
  if (grown > m_params.recheck_static_growth) return -1;
  searchRegion(image, Roi::full(m_camera.width(), m_camera.height()), out);
  std::uint32_t untracked_flags = 0U;
  const int rival = preferSilhouette(selectRobust(Gate{}, untracked_flags), untracked_flags);
  if (!takesTheTrackOver(rival, gate, tracked_n)) return -1;
  m_track = Track{};
  out.flags |= untracked_flags | kFlagRecheckSwitched;
  return rival;
}

bool FarRangeEstimator::takesTheTrackOver(int rival, const Gate& gate, double tracked_n) const {
  if (rival < 0) return false;
  const Cluster& r = m_finder.clusters()[static_cast<std::size_t>(rival)];
  if ((usedCentre(r) - gate.centre_px).norm() <= gate.radius_px) return false;  // the tracked target itself
  if (usedPixels(r) < m_params.recheck_switch_ratio * tracked_n) return false;
  return !(m_recheck_max_distance_m > 0.0 && distancesOf(r).delivered() > m_recheck_max_distance_m);
}

}  // namespace visnav::far
