// Renderer pieces for the far-range scenarios: per-frame clutter (bars, glints) and models made of several
// convex parts (a satellite body with solar panels), composited far to near.
#include <algorithm>
#include <cmath>

#include "visnav/synthetic/renderer.hpp"

namespace visnav::synthetic {

bool clutterAt(std::int64_t first_frame, std::int64_t last_frame, std::int64_t frame, double& fraction) {
  if (frame < first_frame || frame > last_frame) return false;
  fraction = last_frame == first_frame
                 ? 0.0
                 : static_cast<double>(frame - first_frame) / static_cast<double>(last_frame - first_frame);
  return true;
}

void Renderer::findParts() {
  // Surfaces sharing an edge belong to one part (union-find over the model's edges).
  const std::size_t n = m_model.surfaces().size();
  m_surface_part.assign(n, 0);
  std::vector<int> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<int>(i);
  const auto root = [&parent](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  for (const ModelEdge& e : m_model.edges()) {
    if (e.surface_left >= 0 && e.surface_right >= 0) {
      parent[static_cast<std::size_t>(root(e.surface_left))] = root(e.surface_right);
    }
  }
  std::vector<int> part_of_root(n, -1);
  std::vector<int> vertex_count;
  m_part_centroid.clear();
  for (std::size_t s = 0; s < n; ++s) {
    const auto r = static_cast<std::size_t>(root(static_cast<int>(s)));
    if (part_of_root[r] < 0) {
      part_of_root[r] = static_cast<int>(m_part_centroid.size());
      m_part_centroid.push_back(Vec3::Zero());
      vertex_count.push_back(0);
    }
    const int part = part_of_root[r];
    m_surface_part[s] = part;
    for (const int v : m_model.surfaces()[s].vertex_indices) {
      m_part_centroid[static_cast<std::size_t>(part)] += m_model.vertices()[static_cast<std::size_t>(v)];
      ++vertex_count[static_cast<std::size_t>(part)];
    }
  }
  for (std::size_t p = 0; p < m_part_centroid.size(); ++p) m_part_centroid[p] /= vertex_count[p];
  m_part_order.assign(m_part_centroid.size(), 0);
}

int Renderer::rasterizeParts(const Pose& T_c_m, const double* background) {
  // Painter's order by the distance of each part's centroid, far first; within a part the front faces of a
  // convex body do not overlap and add up exactly as in the one-part path.
  const std::size_t parts = m_part_centroid.size();
  for (std::size_t p = 0; p < parts; ++p) m_part_order[p] = static_cast<int>(p);
  std::sort(m_part_order.begin(), m_part_order.end(), [&](int a, int b) {
    return T_c_m.transform(m_part_centroid[static_cast<std::size_t>(a)]).norm() >
           T_c_m.transform(m_part_centroid[static_cast<std::size_t>(b)]).norm();
  });
  std::copy(background, background + m_radiance.size(), m_radiance.begin());
  std::fill(m_union_coverage.begin(), m_union_coverage.end(), 0.0);
  const auto& surfaces = m_model.surfaces();
  int drawn = 0;
  for (const int part : m_part_order) {
    int drawn_here = 0;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
      if (m_surface_part[s] != part) continue;
      const Vec3 normal_c = T_c_m.R_c_m * surfaces[s].normal_m;
      if (normal_c.dot(T_c_m.transform(surfaces[s].centroid_m)) >= 0.0) continue;  // back face
      rasterizeSurface(surfaces[s], T_c_m, surfaceBrightness(static_cast<int>(s), normal_c));
      ++drawn_here;
    }
    if (drawn_here == 0) continue;
    drawn += drawn_here;
    m_raster.resolve(m_coverage.data(), m_weighted.data());
    for (std::size_t i = 0; i < m_radiance.size(); ++i) {
      m_radiance[i] = m_radiance[i] * (1.0 - m_coverage[i]) + m_weighted[i];
      m_union_coverage[i] += (1.0 - m_union_coverage[i]) * m_coverage[i];
    }
  }
  std::copy(m_union_coverage.begin(), m_union_coverage.end(), m_coverage.begin());
  return drawn;
}

const double* Renderer::frameBackground() {
  const int w = width();
  const int h = height();
  std::copy(m_background.begin(), m_background.end(), m_frame_background.begin());
  bool any_bar = false;
  for (const MovingBar& bar : m_options.bars) {
    double t = 0.0;
    if (!clutterAt(bar.first_frame, bar.last_frame, m_frame, t)) continue;
    const Vec2 centre = bar.start_px + t * (bar.end_px - bar.start_px);
    const double brightness = bar.brightness_start + t * (bar.brightness_end - bar.brightness_start);
    const double a = bar.angle_deg * kRadPerDeg;
    const Vec2 along = 0.5 * bar.length_px * Vec2(std::cos(a), std::sin(a));
    const Vec2 across = 0.5 * bar.width_px * Vec2(-std::sin(a), std::cos(a));
    const Vec2 corners[4] = {centre - along - across, centre + along - across, centre + along + across,
                             centre - along + across};
    double area2 = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Vec2& p = corners[k];
      const Vec2& q = corners[(k + 1) % 4];
      area2 += p.x() * q.y() - q.x() * p.y();
    }
    const double sign = area2 < 0.0 ? 1.0 : -1.0;  // as rasterizeSurface: enclosed area accumulates > 0
    for (int k = 0; k < 4; ++k) m_raster.addSegment(corners[k], corners[(k + 1) % 4], sign, brightness);
    any_bar = true;
  }
  if (any_bar) {
    m_raster.resolve(m_coverage.data(), m_weighted.data());
    for (std::size_t i = 0; i < m_frame_background.size(); ++i) {
      m_frame_background[i] = m_frame_background[i] * (1.0 - m_coverage[i]) + m_weighted[i];
    }
  }
  for (const Glint& g : m_options.glints) {
    double t = 0.0;
    if (!clutterAt(g.first_frame, g.last_frame, m_frame, t)) continue;
    const Vec2 c = g.start_px + t * (g.end_px - g.start_px);
    const double reach = 4.0 * g.sigma_px;
    const int u0 = std::max(0, static_cast<int>(std::floor(c.x() - reach)));
    const int u1 = std::min(w - 1, static_cast<int>(std::ceil(c.x() + reach)));
    const int v0 = std::max(0, static_cast<int>(std::floor(c.y() - reach)));
    const int v1 = std::min(h - 1, static_cast<int>(std::ceil(c.y() + reach)));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const double dx = u + 0.5 - c.x();
        const double dy = v + 0.5 - c.y();
        m_frame_background[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) +
                           static_cast<std::size_t>(u)] +=
            g.peak * std::exp(-0.5 * (dx * dx + dy * dy) / (g.sigma_px * g.sigma_px));
      }
    }
  }
  return m_frame_background.data();
}

}  // namespace visnav::synthetic
