// Which scanlines a model of several parts hides from itself ([nearrange] occluded_scanlines,
// fsw/nearrange/README.md "Occluded scanlines"): sec. II-H culls back faces, enough for one convex body,
// not for a panel in front of a body edge.
#include <cmath>

#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav {

void NearRangeTracker::prepareOccluders(const Pose& predicted) {
  m_occluders.clear();
  const auto& surfaces = m_model.surfaces();
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    if (m_surface_front[s] == 0U) continue;
    const ModelSurface& surface = surfaces[s];
    Occluder o;
    o.surface = static_cast<int>(s);
    o.n_c = predicted.R_c_m * surface.normal_m;
    o.d = o.n_c.dot(m_vertex_c[static_cast<std::size_t>(surface.vertex_indices[0])]);
    constexpr double kUnbounded = 1e300;
    o.min_px = Vec2::Constant(kUnbounded);
    o.max_px = Vec2::Constant(-kUnbounded);
    for (const int index : surface.vertex_indices) {
      Vec2 px;
      if (!m_camera.project(m_vertex_c[static_cast<std::size_t>(index)], px)) {
        o.min_px = Vec2::Constant(-kUnbounded);  // behind the camera: no image bound
        o.max_px = Vec2::Constant(kUnbounded);
        break;
      }
      o.min_px = o.min_px.cwiseMin(px);
      o.max_px = o.max_px.cwiseMax(px);
    }
    (void)m_occluders.push(o);  // capacity: one per surface
  }
}

bool NearRangeTracker::occluded(const Vec3& p_c, const ModelEdge& edge) const {
  // Ray from the camera centre through p_c: an occluder whose plane it crosses before p_c (by more than a
  // relative margin: the edge's own corners lie on their neighbours' planes) at a point inside that
  // surface's polygon hides p_c. The projection's bounding box (one pixel of slack for the lens model)
  // screens the occluders first. Bounded: occluders x their vertices.
  constexpr double kMargin = 1e-6;
  constexpr double kSlackPx = 1.0;
  Vec2 p_px;
  if (!m_camera.project(p_c, p_px)) return false;
  const auto& surfaces = m_model.surfaces();
  for (const Occluder& o : m_occluders) {
    if (o.surface == edge.surface_left || o.surface == edge.surface_right) continue;
    if (p_px.x() < o.min_px.x() - kSlackPx || p_px.x() > o.max_px.x() + kSlackPx ||
        p_px.y() < o.min_px.y() - kSlackPx || p_px.y() > o.max_px.y() + kSlackPx)
      continue;
    const double along_ray = o.n_c.dot(p_c);
    if (!(std::fabs(along_ray) > 0.0)) continue;
    const double scale = o.d / along_ray;
    if (!(scale > 0.0 && scale < 1.0 - kMargin)) continue;
    const Vec3 q = scale * p_c;
    // Point in polygon (crossing number) in the plane's two coordinates with the larger normal components.
    int drop = 0;
    o.n_c.cwiseAbs().maxCoeff(&drop);
    const int u = drop == 0 ? 1 : 0;
    const int v = drop == 2 ? 1 : 2;
    const ModelSurface& surface = surfaces[static_cast<std::size_t>(o.surface)];
    bool inside = false;
    const std::size_t n = surface.vertex_indices.size();
    for (std::size_t k = 0, j = n - 1; k < n; j = k++) {
      const Vec3& a = m_vertex_c[static_cast<std::size_t>(surface.vertex_indices[k])];
      const Vec3& b = m_vertex_c[static_cast<std::size_t>(surface.vertex_indices[j])];
      if ((a[v] > q[v]) != (b[v] > q[v]) && q[u] < (b[u] - a[u]) * (q[v] - a[v]) / (b[v] - a[v]) + a[u])
        inside = !inside;
    }
    if (inside) return true;
  }
  return false;
}

}  // namespace visnav
