// The outline searches of an extended target: clusters of the edge response (eq. 10) alone, holes filled,
// where eq. 13 fails because the target's own grey levels are no longer rare (eq. 12). With a track, inside
// its gate (searchExtended, preferEnclosingOutline); without one, only a closed, sharp outline
// (searchSilhouette, preferSilhouette). Design notes: fsw/farrange/README.md, robust method items 6 and 9.
#include <algorithm>
#include <cmath>

#include "visnav/farrange/far_range_estimator.hpp"

namespace visnav::far {

void FarRangeEstimator::clusterEdgeResponse(int min_keep_px) {
  const Roi& roi = m_edge_response.roi();
  std::uint8_t* row_max = m_edge_row_max.data();
  for (int ry = 0; ry < roi.height; ++ry) {
    const std::uint8_t* s = m_edge_response.row(ry);
    row_max[ry] = *std::max_element(s, s + roi.width);
  }
  m_finder.find(m_edge_response, row_max, m_ext_spawn_q, m_ext_grow_q, min_keep_px);
}

int FarRangeEstimator::restoreEq13Clusters(const Gate& gate) {
  // Same response, same thresholds: the same clusters and the same selection as before the outline search.
  m_finder.find(m_combined, m_row_max.data(), m_t_in_q, m_t_out_q);
  prepareCandidates();
  std::uint32_t again = 0;
  return selectRobust(gate, again);
}

int FarRangeEstimator::preferEnclosingOutline(const Gate& gate, int selected, std::uint32_t& flags) {
  // eq. 13 may hold only a fragment of a target that grew (plate/50: n = 1 to 3 at 50 m in noise 0.11, read
  // as 1200-2100 m), and the gate's size consistency then keeps the fragment. An outline on the edge response
  // that encloses the fragment and is extended_enclose_ratio times its size is the target; a smaller ratio
  // is a whole target's own outline with its halo, or with parts eq. 13 rightly leaves out (a satellite's
  // dark panels), whose n gamma was not calibrated on.
  if (!gate.active || !(m_params.extended_min_half_px > 0.0)) return selected;
  const Cluster fragment = m_finder.clusters()[static_cast<std::size_t>(selected)];
  const Vec2 at = usedCentre(fragment);
  std::uint32_t outline_flags = 0;
  const int outline = searchExtended(gate, outline_flags);
  if (outline >= 0) {
    const Cluster& c = m_finder.clusters()[static_cast<std::size_t>(outline)];
    if (at.x() >= c.x_min && at.x() <= c.x_max + 1.0 && at.y() >= c.y_min && at.y() <= c.y_max + 1.0 &&
        usedPixels(c) >= m_params.extended_enclose_ratio * usedPixels(fragment)) {
      flags |= outline_flags;
      return outline;
    }
  }
  return restoreEq13Clusters(gate);
}

int FarRangeEstimator::searchExtended(const Gate& gate, std::uint32_t& flags) {
  // Close in, the target's own grey levels fill the histogram and eq. 12 no longer calls them rare: with
  // t_in 0.9 and equal weights no pixel spawns a cluster although the outline is a strong edge (campaign
  // octagon/26: tracked from 750 m to 48 m, then nothing), or only a fragment of the target does, and the
  // track then holds that fragment's size (plate/3: n = 42 at 53 m, read as 408 m). A tracked target is then
  // looked for by its outline alone: clusters of strong edge response, holes filled, inside the gate.
  // Without a track only a closed, sharp outline will do (searchSilhouette).
  if (!(m_params.extended_min_half_px > 0.0) || !gate.active) return -1;
  clusterEdgeResponse(m_params.min_cluster_px);
  // The gate as in selectRobust, but the silhouette may be up to extended_max_growth times the tracked
  // size (a fragment's track), never smaller than max_size_ratio allows, at least extended_min_half_px in
  // half extent (a small outline is the eq. 13 search's job), and not cut by the image border (the limb's
  // arc is).
  auto& clusters = m_finder.clusters();
  const double down_limit = std::log(std::max(m_params.max_size_ratio, 1.000001));
  const double up_limit = std::log(std::max(m_params.extended_max_growth, m_params.max_size_ratio));
  int best = -1;
  double best_score = 0.0;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    Cluster& c = clusters[i];
    if (c.pixel_count < m_params.min_cluster_px || c.halfExtentPx() < m_params.extended_min_half_px) continue;
    if (touchesImageBorder(c)) continue;
    // Holes are filled (twice the bounding box's area) only for an outline that can reach the gate: the
    // filled centre lies in the bounding box.
    const double gap_x = std::max({c.x_min - gate.centre_px.x(), gate.centre_px.x() - (c.x_max + 1.0), 0.0});
    const double gap_y = std::max({c.y_min - gate.centre_px.y(), gate.centre_px.y() - (c.y_max + 1.0), 0.0});
    if (std::hypot(gap_x, gap_y) > gate.radius_px) continue;
    if (m_params.fill_holes) m_finder.fillHoles(c);
    const double offset = (usedCentre(c) - gate.centre_px).norm();
    if (offset > gate.radius_px) continue;
    if (passedOver(c, flags) || lacksSharpOutline(c)) continue;
    const double log_ratio = std::log(usedPixels(c) / std::max(gate.size_px, 1.0));
    if (log_ratio < -down_limit || log_ratio > up_limit) continue;
    const double score = offset / gate.radius_px + std::abs(log_ratio) / up_limit;  // lower is better
    if (best < 0 || score < best_score) {
      best = static_cast<int>(i);
      best_score = score;
    }
  }
  if (best < 0 && m_params.outline_min_coverage <= 1.0 && m_params.untracked_outline_fill_ratio > 0.0) {
    // No closed outline in the gate: an outline with gaps whose hull the track's size and place fit.
    HullChoice hull;
    bestHullShape(gate, flags, hull);
    if (hull.index >= 0 &&
        !hullLacksSharpOutline(clusters[static_cast<std::size_t>(hull.index)], hull.shape)) {
      best = hull.index;
      adoptHull(clusters[static_cast<std::size_t>(best)], hull.shape);
    }
  }
  if (best >= 0) flags |= kFlagExtended | kFlagGated;
  return best;
}

int FarRangeEstimator::searchSilhouette(std::uint32_t& flags) {
  // Without a track, eq. 13 on an extended target over a background of like grey levels (a gradient, a
  // limb) keeps only noise specks, and the largest speck became the track (campaign box/13: 1-2 px clusters
  // read at 1190 m from 750 m to 8 m, never handed over). A strong edge anywhere is no target, but a closed
  // one is: its filled area holds at least untracked_outline_fill_ratio times its own edge pixels (a sharp
  // outline around an interior without edges), or, for an outline with gaps, its convex hull does and the
  // outline runs along outline_min_coverage of the hull. An open arc covers little of its hull, a soft glow
  // or a drifting blob has no edge response above the noise's, a ragged noise cluster is all edge pixels,
  // and the limb's arc is cut by the image border.
  if (!(m_params.untracked_outline_fill_ratio > 0.0) || !(m_params.extended_min_half_px > 0.0) ||
      !m_params.fill_holes)
    return -1;
  // A closed outline of half extent h has at least 4 h edge pixels, a part of it at least half that: the
  // whole frame's noise speckle, smaller, is dropped at once so it cannot use up max_clusters first.
  clusterEdgeResponse(
      std::max(m_params.min_cluster_px, static_cast<int>(std::ceil(2.0 * m_params.extended_min_half_px))));
  auto& clusters = m_finder.clusters();
  int best = -1;
  double best_n = 0.0;
  double second_n = 0.0;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    Cluster& c = clusters[i];
    if (c.halfExtentPx() < m_params.extended_min_half_px || touchesImageBorder(c)) continue;
    m_finder.fillHoles(c);
    if (c.filled_count < m_params.untracked_outline_fill_ratio * c.pixel_count) continue;
    if (c.axis_ratio > m_params.max_axis_ratio || passedOver(c, flags) || lacksSharpOutline(c)) continue;
    const double n = usedPixels(c);
    if (best < 0 || n > best_n) {
      second_n = best_n;
      best = static_cast<int>(i);
      best_n = n;
    } else if (n > second_n) {
      second_n = n;
    }
  }
  HullChoice hull;
  bestHullShape(Gate{}, flags, hull);
  if (hull.index >= 0 && hullLacksSharpOutline(clusters[static_cast<std::size_t>(hull.index)], hull.shape))
    hull.index = -1;
  if (hull.index >= 0 && hull.n > best_n) {
    second_n = std::max(best_n, hull.second_n);
    best_n = hull.n;
    best = hull.index;
    adoptHull(clusters[static_cast<std::size_t>(best)], hull.shape);
  } else if (hull.index >= 0) {
    second_n = std::max(second_n, hull.n);
  }
  if (best >= 0) flags |= kFlagExtended | kFlagUnconfirmed;
  if (best >= 0 && second_n >= 0.7 * best_n) flags |= kFlagAmbiguous;
  return best;
}

void FarRangeEstimator::bestHullShape(const Gate& gate, std::uint32_t& flags, HullChoice& choice) {
  // The outline's fragments: the largest clusters not cut by the image border that reach half the smallest
  // half extent (an outline broken in two leaves two such parts).
  constexpr int kMaxFragments = 8;
  auto& clusters = m_finder.clusters();
  int fragments[kMaxFragments];
  int count = 0;
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const Cluster& c = clusters[i];
    if (c.halfExtentPx() < 0.5 * m_params.extended_min_half_px || touchesImageBorder(c)) continue;
    int at = count < kMaxFragments ? count++ : kMaxFragments;
    while (at > 0 && clusters[static_cast<std::size_t>(fragments[at - 1])].pixel_count < c.pixel_count) {
      if (at < kMaxFragments) fragments[at] = fragments[at - 1];
      --at;
    }
    if (at < kMaxFragments) fragments[at] = static_cast<int>(i);
  }
  const double down_limit = std::log(std::max(m_params.max_size_ratio, 1.000001));
  const double up_limit = std::log(std::max(m_params.extended_max_growth, m_params.max_size_ratio));
  double best_score = 0.0;
  for (int a = 0; a < count; ++a) {
    for (int b = a; b < count; ++b) {
      const Cluster& ca = clusters[static_cast<std::size_t>(fragments[a])];
      const Cluster& cb = clusters[static_cast<std::size_t>(fragments[b])];
      const int members[2] = {fragments[a], fragments[b]};
      const int member_count = a == b ? 1 : 2;
      if (member_count == 2) {
        // Two parts of one outline lie next to each other.
        const int gap =
            std::max({ca.x_min - cb.x_max, cb.x_min - ca.x_max, ca.y_min - cb.y_max, cb.y_min - ca.y_max, 0});
        if (gap > std::max(ca.halfExtentPx(), cb.halfExtentPx())) continue;
      }
      OutlineHull h;
      if (!m_finder.outlineHull(members, member_count, kHullReachPx, m_params.outline_min_coverage, h))
        continue;
      const double half = 0.5 * std::max(h.x_max - h.x_min + 1, h.y_max - h.y_min + 1);
      const double aspect = static_cast<double>(std::max(h.x_max - h.x_min + 1, h.y_max - h.y_min + 1)) /
                            std::min(h.x_max - h.x_min + 1, h.y_max - h.y_min + 1);
      if (half < m_params.extended_min_half_px || aspect > m_params.max_axis_ratio) continue;
      // The outline runs along the hull, and the hull along the outline (a line with noise attached covers
      // its hull's boundary with the noise, but most of its pixels lie inside).
      if (h.coverage < m_params.outline_min_coverage || h.concentration < m_params.outline_min_concentration)
        continue;
      if (h.area_px < m_params.untracked_outline_fill_ratio * h.pixel_count) continue;
      const double n = std::max(1.0, h.area_px - m_params.outline_discount * h.perimeter_px);
      if (refuted(h.centre_px, n)) {
        flags |= kFlagRefutedSkipped;
        continue;
      }
      double score = -n;  // without a track: the largest
      if (gate.active) {
        const double offset = (h.centre_px - gate.centre_px).norm();
        const double log_ratio = std::log(n / std::max(gate.size_px, 1.0));
        if (offset > gate.radius_px || log_ratio < -down_limit || log_ratio > up_limit) continue;
        score = offset / gate.radius_px + std::abs(log_ratio) / up_limit;
      }
      if (choice.index < 0 || score < best_score) {
        choice.second_n = choice.n;
        choice.index = members[0];
        choice.n = n;
        choice.shape = h;
        best_score = score;
      } else {
        choice.second_n = std::max(choice.second_n, n);
      }
    }
  }
}

bool FarRangeEstimator::hullLacksSharpOutline(const Cluster& c, const OutlineHull& h) const {
  if (!(m_params.min_outline_sharpness > 0.0)) return false;
  Cluster as_hull = c;
  adoptHull(as_hull, h);
  return lacksSharpOutline(as_hull);
}

void FarRangeEstimator::adoptHull(Cluster& c, const OutlineHull& h) const {
  c.sharpness_known = false;
  // The hull stands for the filled silhouette in everything that reads the cluster after selection.
  c.filled_count = static_cast<int>(std::lround(h.area_px));
  c.boundary_count = static_cast<int>(std::lround(h.perimeter_px));
  c.filled_com_px = h.centre_px;
  c.max_radius_px = h.max_radius_px;
  c.x_min = h.x_min;
  c.y_min = h.y_min;
  c.x_max = h.x_max;
  c.y_max = h.y_max;
}

int FarRangeEstimator::preferSilhouette(int selected, std::uint32_t& flags) {
  // eq. 13's largest cluster without a track, or the closed outline when that is extended_enclose_ratio
  // times larger (a speck of noise or the target's fragment against its whole silhouette).
  if (!(m_params.untracked_outline_fill_ratio > 0.0)) return selected;
  const double eq13_n =
      selected >= 0 ? static_cast<double>(usedPixels(m_finder.clusters()[static_cast<std::size_t>(selected)]))
                    : 0.0;
  std::uint32_t outline_flags = 0;
  const int outline = searchSilhouette(outline_flags);
  if (outline >= 0 && usedPixels(m_finder.clusters()[static_cast<std::size_t>(outline)]) >=
                          m_params.extended_enclose_ratio * eq13_n) {
    flags = (flags & ~(kFlagAmbiguous | kFlagFlattened)) | outline_flags;
    return outline;
  }
  flags |= outline_flags & kFlagRefutedSkipped;  // a refuted outline passed over is still reported
  return restoreEq13Clusters(Gate{});
}

}  // namespace visnav::far
