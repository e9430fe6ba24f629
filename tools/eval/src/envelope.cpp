#include "visnav/eval/envelope.hpp"

#include <algorithm>
#include <cmath>

#include "visnav/core/rng.hpp"
#include "visnav/nearrange/pose_fit.hpp"

namespace visnav::eval {

std::vector<int> envelopeVertices(const PolygonModel& model, const Pose& truth, double max_obliquity_deg) {
  const double limit = -std::cos(max_obliquity_deg * kRadPerDeg);
  std::vector<int> out;
  for (const ModelSurface& s : model.surfaces()) {
    const Vec3 q = truth.transform(s.centroid_m);
    const double range = q.norm();
    if (range <= 0.0) continue;
    const Vec3 n = truth.R_c_m * s.normal_m;
    if (n.dot(q / range) < limit) out.insert(out.end(), s.vertex_indices.begin(), s.vertex_indices.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void EnvelopeSolver::buildPatterns(const std::vector<Vec2>& px) {
  const int v = static_cast<int>(px.size());
  const int bits = 2 * v;
  m_signs.clear();
  m_exhaustive = bits <= std::min(m_options.max_exhaustive_offsets, 20);  // 2^20 solves is the sane limit
  if (m_exhaustive) {
    m_combinations = 1 << bits;
    m_signs.resize(static_cast<std::size_t>(m_combinations) * bits);
    for (int c = 0; c < m_combinations; ++c)
      for (int k = 0; k < bits; ++k) m_signs[c * bits + k] = ((c >> k) & 1) != 0 ? 1 : -1;
    return;
  }
  // Structured patterns first: 4 uniform shifts (all x offsets one sign, all y offsets one sign) and 4
  // centroid-relative ones (expand/contract in x and y), the worst cases for position and for distance/tilt.
  Vec2 centroid = Vec2::Zero();
  for (const Vec2& p : px) centroid += p;
  centroid /= static_cast<double>(v);
  for (int radial = 0; radial < 2; ++radial) {
    for (int sx = -1; sx <= 1; sx += 2) {
      for (int sy = -1; sy <= 1; sy += 2) {
        for (int i = 0; i < v; ++i) {
          const int rx = radial != 0 && px[i].x() < centroid.x() ? -1 : 1;
          const int ry = radial != 0 && px[i].y() < centroid.y() ? -1 : 1;
          m_signs.push_back(static_cast<std::int8_t>(sx * rx));
          m_signs.push_back(static_cast<std::int8_t>(sy * ry));
        }
      }
    }
  }
  // Then a deterministic random sample; reseeding per frame makes each frame's result independent of the
  // envelope stride and of the frame order.
  Pcg32 rng(m_options.seed);
  for (int c = 0; c < m_options.sampled_combinations; ++c)
    for (int k = 0; k < bits; ++k) m_signs.push_back((rng.next() >> 31U) != 0U ? 1 : -1);
  m_combinations = static_cast<int>(m_signs.size()) / bits;
}

void EnvelopeSolver::compute(const Pose& truth, const std::vector<double>& deltas_px,
                             std::vector<FrameEnvelope>& out) {
  out.assign(deltas_px.size(), FrameEnvelope{});
  const std::vector<int> vertices = envelopeVertices(m_model, truth, m_options.max_obliquity_deg);
  std::vector<Vec2> px(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!m_camera.projectIdeal(truth.transform(m_model.vertices()[vertices[i]]), px[i])) return;
  const int v = static_cast<int>(vertices.size());
  if (v < 3) return;  // 2V residuals must cover 6 pose parameters
  buildPatterns(px);
  const int bits = 2 * v;
  std::vector<VertexObservation> obs(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) obs[i].vertex = vertices[i];

  for (std::size_t d = 0; d < deltas_px.size(); ++d) {
    FrameEnvelope& env = out[d];
    env.valid = true;
    env.vertex_count = v;
    env.exhaustive = m_exhaustive;
    // delta = 0: every combination is the same unperturbed problem.
    const int combinations = deltas_px[d] == 0.0 ? 1 : m_combinations;
    env.combinations = combinations;
    for (int c = 0; c < combinations; ++c) {
      const std::int8_t* s = &m_signs[static_cast<std::size_t>(c) * bits];
      for (int i = 0; i < v; ++i) obs[i].px_ideal = px[i] + deltas_px[d] * Vec2(s[2 * i], s[2 * i + 1]);
      Pose pose = truth;
      PoseFitResult fit;
      if (!fitPoseToVertices(m_camera, m_model, obs.data(), v, m_options.lm, 1.0, pose, fit))
        ++env.failed_solves;
      const AxisValues e = poseError(pose, truth);
      for (int a = 0; a < kAxisCount; ++a) env.max_abs[a] = std::max(env.max_abs[a], std::fabs(e[a]));
      env.max_angle_deg = std::max(env.max_angle_deg, attitudeErrorDeg(pose, truth));
    }
  }
}

}  // namespace visnav::eval
