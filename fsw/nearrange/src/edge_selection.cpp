// Which model edges the tracker measures this frame (sec. II-H and the outline), and which of them sit so
// close to a parallel outline edge that the 1-D step search could take the outline's step for theirs.
#include <algorithm>
#include <cmath>

#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav {

void NearRangeTracker::selectEdges(NearRangeResult& out) {
  // Every edge of a tracked surface (sec. II-H), plus the outline when enabled: exactly one side
  // front-facing (an open boundary counts as a back side).
  const auto& edges = m_model.edges();
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const ModelEdge& edge = edges[e];
    const bool left = edge.surface_left >= 0 && m_surface_tracked[edge.surface_left] != 0U;
    const bool right = edge.surface_right >= 0 && m_surface_tracked[edge.surface_right] != 0U;
    m_edge_selected[e] = (left || right) ? 1U : 0U;
    if (m_edge_selected[e] != 0U || !m_params.silhouette_edges) continue;
    const bool front_left = edge.surface_left >= 0 && m_surface_front[edge.surface_left] != 0U;
    const bool front_right = edge.surface_right >= 0 && m_surface_front[edge.surface_right] != 0U;
    if (front_left != front_right) {
      m_edge_selected[e] = 1U;
      ++out.silhouette_lines;
    }
  }
  for (std::size_t s = 0; s < m_surface_tracked.size(); ++s) {
    if (m_surface_tracked[s] == 0U) continue;
    ++out.tracked_surfaces;
    if (s < 64) out.tracked_surface_mask |= 1ULL << s;
  }
  if (out.tracked_surfaces == 0 && out.silhouette_lines > 0) out.flags |= kFlagSilhouetteOnly;
  if (out.tracked_surfaces == 0 && out.silhouette_lines == 0) out.flags |= kFlagNoSurface;
}

bool NearRangeTracker::interiorEdge(const ModelEdge& edge) const {
  return edge.surface_left >= 0 && edge.surface_right >= 0 && m_surface_front[edge.surface_left] != 0U &&
         m_surface_front[edge.surface_right] != 0U;
}

bool NearRangeTracker::findConfusableEdges() {
  // An interior edge (both neighbouring surfaces front-facing) next to a face seen at a grazing angle lies a
  // few pixels from the outline edge on that face's far side. Closer than the step test can resolve (its two
  // w-sample windows plus the blur: confusable_edge_separation_px), the interior edge's scanlines may find
  // the outline's step instead of its own, and under flat lighting the interior edge has no step at all.
  // Such pairs are noted here; measureEdge then keeps only the interior edge's steps that lie nearer its own
  // predicted line than the neighbour's (campaign box/17: strips of 2.5-3.8 px, the interior lines had been
  // fitted 2.6 and 3.5 px off, on the outline, and the pose 5.7 deg off from the true start at 0.2 px rms).
  constexpr double kParallelSin = 0.26;  // within 15 deg: the other edge runs along the scanline window
  constexpr double kMinOverlap = 0.3;    // of the interior edge's length: side by side, not end to end
  // A strip narrower than a pixel (a face just turning into view) makes both edges one image line whose step
  // lies between the two predicted lines: the nearer-line test would split it at random. Taking it for the
  // interior edge biases that edge by under a pixel and keeps its corners for eq. 7 (slew_box frame 87:
  // without them, 3 corners and a point-to-line fit 6 px off).
  constexpr double kNegligibleGapPx = 1.0;
  const auto& edges = m_model.edges();
  const auto interior = [this, &edges](std::size_t e) {
    return m_edge_selected[e] != 0U && interiorEdge(edges[e]);
  };
  bool any_interior = false;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    m_confusable_partner[e] = -1;
    m_edge_bounds_narrow_face[e] = 0U;
    any_interior = any_interior || interior(e);
  }
  // A plate, or a body seen face-on with one tracked face, has no interior edge: nothing to project.
  if (!any_interior || !(m_params.confusable_edge_separation_px > 0.0)) return false;
  for (std::size_t v = 0; v < m_vertex_c.size(); ++v) {
    const Vec3& p_c = m_vertex_c[v];  // at the prediction (transformVertices)
    m_vertex_in_front[v] = p_c.z() > 0.0 && m_camera.project(p_c, m_vertex_px[v]) ? 1U : 0U;
  }
  const double separation = m_params.confusable_edge_separation_px;
  bool narrow_strip = false;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!interior(e)) continue;
    const ModelEdge& edge = edges[e];
    if (m_vertex_in_front[edge.v0] == 0U || m_vertex_in_front[edge.v1] == 0U) continue;
    const Vec2 a = m_vertex_px[edge.v0];
    const Vec2 ab = m_vertex_px[edge.v1] - a;
    const double length = ab.norm();
    if (!(length > 1.0)) continue;
    const Vec2 d = ab / length;
    const Vec2 n(-d.y(), d.x());
    double best_gap = separation;
    for (std::size_t f = 0; f < edges.size(); ++f) {
      const ModelEdge& other = edges[f];
      if (f == e || m_edge_selected[f] == 0U) continue;
      // Edges sharing a vertex meet at a corner: neighbours, not parallel strips.
      if (other.v0 == edge.v0 || other.v0 == edge.v1 || other.v1 == edge.v0 || other.v1 == edge.v1) continue;
      if (m_vertex_in_front[other.v0] == 0U || m_vertex_in_front[other.v1] == 0U) continue;
      const Vec2 c = m_vertex_px[other.v0] - a;
      const Vec2 cd = m_vertex_px[other.v1] - m_vertex_px[other.v0];
      const double other_length = cd.norm();
      if (!(other_length > 1.0) || std::fabs(n.dot(cd)) > kParallelSin * other_length) continue;
      const double s0 = std::max(0.0, std::min(d.dot(c), d.dot(c + cd)));
      const double s1 = std::min(length, std::max(d.dot(c), d.dot(c + cd)));
      if (s1 - s0 < kMinOverlap * length) continue;
      const double gap = std::max(std::fabs(n.dot(c)), std::fabs(n.dot(c + cd)));
      // Opposite edges of one face this close: that face is seen nearly edge-on (kFlagNarrowFace). Another
      // part's edge nearby (a panel beside a body) is no narrow face.
      const auto bordersEdge = [&edge](int surface) {
        return surface >= 0 && (surface == edge.surface_left || surface == edge.surface_right);
      };
      if (gap < separation && (bordersEdge(other.surface_left) || bordersEdge(other.surface_right))) {
        narrow_strip = true;
        m_edge_bounds_narrow_face[e] = 1U;  // both edges of the strip (narrow_face_edge_bias_px)
        m_edge_bounds_narrow_face[f] = 1U;
      }
      if (gap >= kNegligibleGapPx && gap < best_gap) {
        best_gap = gap;
        m_confusable_partner[e] = static_cast<int>(f);
      }
    }
  }
  return narrow_strip;
}

}  // namespace visnav
