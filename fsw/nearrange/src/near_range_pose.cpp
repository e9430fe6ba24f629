// The near-range tracker's pose from its fitted lines (paper sec. II-F/G): vertices where measured lines of
// adjacent edges meet (eq. 6), the LM fit over them (eq. 7) or over every inlier edge point, and the
// leave-one-line-out refit that drops one wrong line. Measuring the lines: near_range_tracker.cpp.
#include <algorithm>
#include <cmath>

#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav {

bool NearRangeTracker::fitPose(const Pose& predicted, Pose& pose, PoseFitResult& fit, NearRangeResult& out) {
  // Sec. II-G, then wrong lines are dropped one at a time (rejectWorstLine) while the fit fails or stays
  // high, at most max_rejected_lines of them (bounded: each pass is one LM per used line).
  bool solved = solvePose(predicted, -1, out.lines_used, pose, fit, out.vertices, out.flags);
  for (int pass = 0; pass < m_params.max_rejected_lines; ++pass) {
    const bool solver_failed = !solved && (out.flags & kFlagTooFewLines) == 0U;
    if (!solver_failed && !(solved && fit.rms_px > m_params.reject_line_trigger_rms_px)) break;
    const int lines_before = out.lines_used;
    solved = rejectWorstLine(predicted, solved, pose, fit, out);
    if (out.lines_used == lines_before) break;  // no line explained enough of the residual
  }
  out.rms_px = fit.rms_px;
  out.lm_iterations = fit.lm.iterations;
  if ((out.flags & kFlagTooFewLines) == 0U && !solved) out.flags |= kFlagSolverFailed;
  if (solved && fit.rms_px > m_params.max_rms_px) out.flags |= kFlagResidualTooHigh;
  if (solved && fit.rms_px > m_params.degraded_rms_px) out.flags |= kFlagResidualHigh;
  if (solved && !(pose.t_c_m.z() > 0.0)) out.flags |= kFlagOutOfImage;
  if (solved && (out.flags & kFlagResidualTooHigh) == 0U &&
      mirroredRivalFits(pose, fit, out.lines_used, out.mirrored_rival))
    out.flags |= kFlagAmbiguous;
  if (solved && m_near_twin_checks && (out.flags & kFlagResidualTooHigh) == 0U &&
      nearTwinRivalFits(pose, fit, out.lines_used, out.near_twin_rival))
    out.flags |= kFlagNearTwinRival;
  return solved;
}

void NearRangeTracker::findChamferCorners() {
  // For every face of five or more vertices and every run of three edges a -> bridge -> b along its ring,
  // the point where the lines of a and b meet, if they do near the bridge (no further from its midpoint than
  // twice its length: a regular octagon's is half its length away; near-parallel lines meet far off and are
  // no corner). Init only: edges are found by their vertex pair.
  m_chamfer_corners.clear();
  const auto& vertices = m_model.vertices();
  const auto edgeOf = [&](int u, int v) {
    const auto& edges = m_model.edges();
    for (std::size_t e = 0; e < edges.size(); ++e)
      if ((edges[e].v0 == u && edges[e].v1 == v) || (edges[e].v0 == v && edges[e].v1 == u))
        return static_cast<int>(e);
    return -1;
  };
  for (const ModelSurface& surface : m_model.surfaces()) {
    const std::vector<int>& ring = surface.vertex_indices;
    const std::size_t n = ring.size();
    if (n < 5) continue;
    for (std::size_t i = 0; i < n; ++i) {
      const int p0 = ring[i], p1 = ring[(i + 1) % n], p2 = ring[(i + 2) % n], p3 = ring[(i + 3) % n];
      ChamferCorner c;
      c.edge_a = edgeOf(p0, p1);
      c.bridge = edgeOf(p1, p2);
      c.edge_b = edgeOf(p2, p3);
      if (c.edge_a < 0 || c.bridge < 0 || c.edge_b < 0) continue;
      // Closest points of the two lines p1 + s (p1 - p0) and p2 + t (p2 - p3).
      const Vec3 da = vertices[p1] - vertices[p0];
      const Vec3 db = vertices[p2] - vertices[p3];
      const Vec3 w = vertices[p1] - vertices[p2];
      const double aa = da.dot(da), bb = db.dot(db), ab = da.dot(db);
      const double det = aa * bb - ab * ab;
      if (!(det > kMinVertexSinAngle * kMinVertexSinAngle * aa * bb)) continue;  // parallel: no corner
      const double sa = (ab * db.dot(w) - bb * da.dot(w)) / det;
      const double tb = (aa * db.dot(w) - ab * da.dot(w)) / det;
      const Vec3 on_a = vertices[p1] + sa * da;
      const Vec3 on_b = vertices[p2] + tb * db;
      const double bridge_m = (vertices[p2] - vertices[p1]).norm();
      if ((on_a - on_b).norm() > 1e-6 * std::max(1.0, m_model.boundingRadius())) continue;  // not coplanar
      c.point_m = 0.5 * (on_a + on_b);
      if ((c.point_m - 0.5 * (vertices[p1] + vertices[p2])).norm() > 2.0 * bridge_m) continue;
      if (!m_chamfer_corners.push(c)) return;
    }
  }
}

namespace {
// Share of a vertex's two lines that are of interior edges: each line's end error moves the vertex alike.
double interiorShare(const EdgeMeasurement& a, const EdgeMeasurement& b) {
  return 0.5 * ((a.interior ? 1.0 : 0.0) + (b.interior ? 1.0 : 0.0));
}
double narrowShare(const EdgeMeasurement& a, const EdgeMeasurement& b) {
  return 0.5 * ((a.bounds_narrow_face ? 1.0 : 0.0) + (b.bounds_narrow_face ? 1.0 : 0.0));
}
}  // namespace

int NearRangeTracker::collectVertices(int excluded_slot) {
  // A vertex is observed where two measured lines of edges meeting at it intersect (eq. 6, Cramer form).
  // With outline edges a vertex may join three measured edges: the best-conditioned pair (largest |sin| of
  // the angle between the lines) gives its one observation, so no corner is counted twice.
  m_vertex_obs.clear();
  for (double& best : m_vertex_best_sin) best = 0.0;
  const auto& edges = m_model.edges();
  const int slots = static_cast<int>(m_edges.size());
  for (int i = 0; i < slots; ++i) {
    if (!m_edges[i].line_ok || i == excluded_slot) continue;
    const ModelEdge& ei = edges[m_edges[i].model_edge];
    for (int j = i + 1; j < slots; ++j) {
      if (!m_edges[j].line_ok || j == excluded_slot) continue;
      const ModelEdge& ej = edges[m_edges[j].model_edge];
      const int shared =
          (ei.v0 == ej.v0 || ei.v0 == ej.v1) ? ei.v0 : ((ei.v1 == ej.v0 || ei.v1 == ej.v1) ? ei.v1 : -1);
      if (shared < 0) continue;
      const Line2d& a = m_edges[i].line;
      const Line2d& b = m_edges[j].line;
      const double sin_angle = std::fabs(std::sin(a.theta_rad - b.theta_rad));
      Vec2 px;
      // Nearly parallel neighbours give no vertex.
      if (sin_angle <= m_vertex_best_sin[shared] || !intersect(a, b, px, kMinVertexSinAngle)) continue;
      m_vertex_best_sin[shared] = sin_angle;
      m_vertex_best_px[shared] = px;
      // Each line's offset error moves the intersection along the other line by 1/sin: the trace of the
      // vertex covariance is (Va + Vb) / sin^2, half of it per axis.
      m_vertex_best_var[shared] =
          0.5 * (m_edges[i].end_variance_px2 + m_edges[j].end_variance_px2) / (sin_angle * sin_angle);
      m_vertex_best_interior[shared] = interiorShare(m_edges[i], m_edges[j]);
      m_vertex_best_narrow[shared] = narrowShare(m_edges[i], m_edges[j]);
    }
  }
  for (std::size_t v = 0; v < m_vertex_best_sin.size(); ++v) {
    if (m_vertex_best_sin[v] <= 0.0) continue;
    VertexObservation obs;
    obs.vertex =
        m_relabel < 0 ? static_cast<int>(v) : m_relabels[static_cast<std::size_t>(m_relabel)].to_vertex[v];
    if (obs.vertex < 0) continue;
    obs.px_ideal = m_vertex_best_px[v];
    obs.variance_px2 = m_vertex_best_var[v];
    obs.inv_sin2 = 1.0 / (m_vertex_best_sin[v] * m_vertex_best_sin[v]);
    obs.interior_inv_sin2 = m_vertex_best_interior[v] * obs.inv_sin2;
    obs.narrow_inv_sin2 = m_vertex_best_narrow[v] * obs.inv_sin2;
    m_vertex_obs.push(obs);
  }
  // Chamfer corners (findChamferCorners), where the bridge edge is too short this frame to give a line
  // (fitLines: fewer scanlines than min_points_per_line). A bridge long enough to measure gives its own two
  // vertices above when its line was found, and when it was not, that is a missed line, not a chamfer: on
  // a regular octagon close up, corners across missed lines changed which lines the leave-one-out search
  // dropped, and case low_contrast_octagon lost 3 of 150 frames.
  if (m_chamfer_corners.empty()) return static_cast<int>(m_vertex_obs.size());
  const auto hasLine = [&](int slot) { return slot >= 0 && slot != excluded_slot && m_edges[slot].line_ok; };
  for (std::size_t index = 0; index < m_chamfer_corners.size(); ++index) {
    const ChamferCorner& c = m_chamfer_corners[index];
    const int i = m_slot_of_edge[c.edge_a];
    const int j = m_slot_of_edge[c.edge_b];
    const int k = m_slot_of_edge[c.bridge];
    if (!hasLine(i) || !hasLine(j)) continue;
    if (k >= 0 && m_edges[k].scanlines >= m_params.min_points_per_line) continue;
    const Line2d& a = m_edges[i].line;
    const Line2d& b = m_edges[j].line;
    const double sin_angle = std::fabs(std::sin(a.theta_rad - b.theta_rad));
    VertexObservation obs;
    if (!intersect(a, b, obs.px_ideal, kMinVertexSinAngle)) continue;
    const int corner = m_relabel < 0 ? static_cast<int>(index)
                                     : m_relabels[static_cast<std::size_t>(m_relabel)].to_corner[index];
    if (corner < 0) continue;
    obs.point_m = m_chamfer_corners[static_cast<std::size_t>(corner)].point_m;
    obs.variance_px2 =
        0.5 * (m_edges[i].end_variance_px2 + m_edges[j].end_variance_px2) / (sin_angle * sin_angle);
    obs.inv_sin2 = 1.0 / (sin_angle * sin_angle);
    obs.interior_inv_sin2 = interiorShare(m_edges[i], m_edges[j]) * obs.inv_sin2;
    obs.narrow_inv_sin2 = narrowShare(m_edges[i], m_edges[j]) * obs.inv_sin2;
    if (!m_vertex_obs.push(obs)) break;
  }
  return static_cast<int>(m_vertex_obs.size());
}

int NearRangeTracker::collectEdgePoints(int excluded_slot) {
  m_edge_obs.clear();
  for (int k = 0; k < static_cast<int>(m_edges.size()); ++k) {
    const EdgeMeasurement& slot = m_edges[k];
    if (!slot.line_ok || k == excluded_slot) continue;
    const int edge = m_relabel < 0 ? slot.model_edge
                                   : m_relabels[static_cast<std::size_t>(m_relabel)]
                                         .to_edge[static_cast<std::size_t>(slot.model_edge)];
    if (edge < 0) continue;
    for (int i = 0; i < slot.point_count; ++i) {
      if (!m_scan_points[slot.first_point + i].inlier) continue;
      m_edge_obs.push({edge, m_points_ideal[slot.first_point + i]});
    }
  }
  return static_cast<int>(m_edge_obs.size());
}

bool NearRangeTracker::solvePose(const Pose& predicted, int excluded_slot, int lines_used, Pose& pose,
                                 PoseFitResult& fit, int& vertices, std::uint32_t& flags) {
  pose = predicted;
  fit = PoseFitResult{};
  const LmOptions lm{m_params.lm_max_iterations};
  vertices = collectVertices(excluded_slot);
  const bool vertex_mode = m_params.pose_residual == static_cast<int>(PoseResidualMode::kVertex);
  if (vertex_mode && lines_used >= kMinLinesForVertexPose && vertices >= kMinLinesForVertexPose)
    return fitPoseToVertices(m_camera, m_model, m_vertex_obs.data(), vertices, lm, m_params.pixel_sigma_px,
                             pose, fit);
  // Point-to-line needs no complete corner: three non-parallel lines with many points still fix 6 DOF.
  // When the vertex residual lacks corners this is the fallback, and the frame is marked degraded.
  const int n = collectEdgePoints(excluded_slot);
  const int min_lines = vertex_mode ? kMinLinesForPointToLine : kMinLinesForVertexPose;
  if (lines_used < min_lines || n < kMinEdgePointsForPose) {
    flags |= kFlagTooFewLines;
    return false;
  }
  if (vertex_mode) flags |= kFlagResidualFallback;
  return fitPoseToEdgePoints(m_camera, m_model, m_edge_obs.data(), n, lm, m_params.pixel_sigma_px, pose, fit);
}

bool NearRangeTracker::rejectWorstLine(const Pose& predicted, bool solved, Pose& pose, PoseFitResult& fit,
                                       NearRangeResult& out) {
  // One wrong line (e.g. locked onto the parallel neighbour edge of a face seen at a grazing angle) spoils
  // every vertex it touches. Refit without each used line in turn (bounded: one LM per line) and keep the
  // best, if it explains the rest clearly better; the frame is then degraded (kFlagLineRejected).
  if (out.lines_used < kMinLinesForLineRejection) return solved;
  // A fit above max_rms_px is lost whatever happens next: it is nothing to keep, so a fallback trial may
  // replace it (eclipse_box frame 102: one short line 10 px off blew the vertex fit to 30 px rms, and the
  // only trial without it had too few corners left).
  const bool usable = solved && fit.rms_px <= m_params.max_rms_px;
  int best_slot = -1;
  Pose best_pose = pose;
  PoseFitResult best_fit = fit;
  std::uint32_t best_flags = 0;
  for (int k = 0; k < static_cast<int>(m_edges.size()); ++k) {
    if (!m_edges[k].line_ok) continue;
    Pose trial_pose;
    PoseFitResult trial_fit;
    int trial_vertices = 0;  // unused: recounted for the kept solution
    std::uint32_t trial_flags = 0;
    if (!solvePose(predicted, k, out.lines_used - 1, trial_pose, trial_fit, trial_vertices, trial_flags))
      continue;
    // A vertex fit (eq. 7) and the point-to-line fallback have residuals of different kinds: their rms are
    // not compared. A trial that has to fall back wins only over nothing or another fallback (slew_box:
    // dropping the one line that left 3 corners gave a point-to-line fit 8 deg off at 0.04 px rms).
    const bool trial_fallback = (trial_flags & kFlagResidualFallback) != 0U;
    const bool best_fallback = best_slot >= 0 ? (best_flags & kFlagResidualFallback) != 0U
                                              : (out.flags & kFlagResidualFallback) != 0U;
    if (trial_fallback && !best_fallback && (usable || best_slot >= 0)) continue;
    const bool better = (best_slot < 0 && !usable) || (best_fallback && !trial_fallback) ||
                        trial_fit.rms_px < m_params.reject_line_rms_gain * best_fit.rms_px;
    if (better) {
      best_slot = k;
      best_pose = trial_pose;
      best_fit = trial_fit;
      best_flags = trial_flags;
    }
  }
  if (best_slot < 0) {
    out.vertices = collectVertices(-1);  // leave the buffers as the kept solution saw them
    return solved;
  }
  EdgeMeasurement& rejected = m_edges[best_slot];
  rejected.line_ok = false;
  for (int b = 0; b < kPolarityBins; ++b) m_polarity_next[rejected.model_edge * kPolarityBins + b] = 0;
  --out.lines_used;
  out.flags |= kFlagLineRejected | best_flags;
  out.vertices = collectVertices(-1);
  pose = best_pose;
  fit = best_fit;
  return true;
}

}  // namespace visnav
