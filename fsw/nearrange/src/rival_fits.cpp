// The near-range tracker's rivals of a fit (fsw/nearrange/README.md, "Depth-mirrored rival" and "Near-twin
// rival"): the model's mirror and near-twin relabellings, found once at init, and the refits of the measured
// lines through them that flag a fit as ambiguous. The fit itself: near_range_pose.cpp.
#include <algorithm>
#include <cmath>

#include "visnav/nearrange/near_range_tracker.hpp"

namespace visnav {

bool NearRangeTracker::addRelabel(const Mat3& map, const Vec3& offset, double tolerance_m, int near_index) {
  if (m_relabel_count >= kMaxRelabels) return false;
  const auto& vertices = m_model.vertices();
  const auto& edges = m_model.edges();
  Relabel& slot = m_relabels[static_cast<std::size_t>(m_relabel_count)];
  // Which vertex each one becomes (init only: found by position, the nearest one); a map that loses one is
  // none.
  slot.to_vertex.reserve(vertices.size());  // init only: allocates, and empties a slot a failed map used
  slot.to_edge.reserve(edges.size());
  for (const Vec3& v : vertices) {
    const Vec3 w = map * v + offset;
    int image = -1;
    double nearest = tolerance_m;
    for (std::size_t u = 0; u < vertices.size(); ++u) {
      const double d = (w - vertices[u]).norm();
      if (d <= nearest) {
        nearest = d;
        image = static_cast<int>(u);
      }
    }
    if (image < 0) return false;
    slot.to_vertex.push(image);
  }
  // And each edge, by its vertex pair.
  for (const ModelEdge& e : edges) {
    const int a = slot.to_vertex[static_cast<std::size_t>(e.v0)];
    const int b = slot.to_vertex[static_cast<std::size_t>(e.v1)];
    int image = -1;
    for (std::size_t f = 0; f < edges.size() && image < 0; ++f)
      if ((edges[f].v0 == a && edges[f].v1 == b) || (edges[f].v0 == b && edges[f].v1 == a))
        image = static_cast<int>(f);
    slot.to_edge.push(image);
  }
  // And each chamfer corner (findChamferCorners, run before), by its pair of edges: the twin's own corner,
  // not the turned point (a near twin is not exact).
  slot.to_corner.reserve(m_chamfer_corners.size());
  for (const ChamferCorner& c : m_chamfer_corners) {
    const int a = slot.to_edge[static_cast<std::size_t>(c.edge_a)];
    const int b = slot.to_edge[static_cast<std::size_t>(c.edge_b)];
    int image = -1;
    for (std::size_t d = 0; d < m_chamfer_corners.size() && image < 0; ++d) {
      const ChamferCorner& other = m_chamfer_corners[d];
      if ((other.edge_a == a && other.edge_b == b) || (other.edge_a == b && other.edge_b == a))
        image = static_cast<int>(d);
    }
    slot.to_corner.push(image);
  }
  slot.map = map;
  slot.offset = offset;
  slot.near_index = near_index;
  ++m_relabel_count;
  return true;
}

void NearRangeTracker::findModelMirrors() {
  m_symmetries.find(m_model);
  m_relabel_count = 0;
  const double tol_m = ModelSymmetries::kIndistinguishableRel * std::max(1.0, m_model.boundingRadius());
  for (int axis = 0; axis < kMaxMirrors; ++axis) {
    Mat3 mirror = Mat3::Identity();
    mirror(axis, axis) = -1.0;
    addRelabel(mirror, Vec3::Zero(), tol_m, -1);
  }
  m_mirror_count = m_relabel_count;
}

void NearRangeTracker::findNearTwins() {
  // After findModelMirrors. The near twins with the smallest separations first (the hardest to tell apart),
  // at most kMaxNearTwins; a twin S about the vertex centroid c puts the model point S^T (x - c) + c where
  // the kept pose puts x.
  if (!(m_params.near_twin_rival_max_rel > 0.0)) return;
  m_symmetries.findNear(m_model, m_params.near_twin_rival_max_rel);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : m_model.vertices()) centre += v;
  centre /= static_cast<double>(std::max<std::size_t>(1, m_model.vertices().size()));
  std::array<int, ModelSymmetries::kCapacity> order{};
  const int count = m_symmetries.nearCount();
  for (int i = 0; i < count; ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.begin() + count, [&](int a, int b) {
    return m_symmetries.nearSeparationM(a) < m_symmetries.nearSeparationM(b);
  });
  const double tol_m = m_params.near_twin_rival_max_rel * m_model.boundingRadius() + 1e-9;
  for (int k = 0; k < count && m_relabel_count - m_mirror_count < kMaxNearTwins; ++k) {
    const int i = order[static_cast<std::size_t>(k)];
    const Mat3 back = m_symmetries.near(i).transpose();
    addRelabel(back, centre - back * centre, tol_m, i);
  }
}

bool NearRangeTracker::mirroredRivalFits(const Pose& pose, const PoseFitResult& fit, int lines_used,
                                         Pose& rival_out) {
  // Under weak perspective the depth-mirrored shape projects onto the same image: F R M with F the mirror
  // along the line of sight and M a mirror symmetry of the model (so det = +1) is a pose the outline alone
  // cannot tell from R (a box's Necker reversal, a plate's second tilt). LM from there finds its exact
  // optimum under perspective; if that fits about as well and is a distinct pose, the frame is ambiguous.
  // F R M puts model vertex M v where R puts v: the rival explains the corner measured for v as M v's (and
  // the line of edge e as M e's). Fitted to the labels as measured, a box's Necker twin is pulled back
  // towards R (campaign box/93, box/191: wrong twins held without the flag). mirrored_rival_relabel (on
  // by default; off: the labels as measured) relabels them.
  const double range = pose.t_c_m.norm();
  if (!(range > 0.0)) return false;
  const Vec3 los = pose.t_c_m / range;
  const Mat3 depth_mirror = Mat3::Identity() - 2.0 * los * los.transpose();
  PoseTolerance distinct;
  distinct.position_m = kRivalDistinctRel * range;
  distinct.attitude_rad = kRivalDistinctDeg * kRadPerDeg;
  const double as_good = std::max(kRivalRmsFactor * fit.rms_px, fit.rms_px + m_params.pixel_sigma_px);
  bool ambiguous = false;
  for (int k = 0; k < m_mirror_count && !ambiguous; ++k) {
    Pose start;
    start.R_c_m = depth_mirror * pose.R_c_m * m_relabels[static_cast<std::size_t>(k)].map;
    start.t_c_m = pose.t_c_m;
    Pose rival;
    PoseFitResult rival_fit;
    int vertices = 0;
    std::uint32_t flags = 0;
    if (m_params.mirrored_rival_relabel) m_relabel = k;
    const bool solved = solvePose(start, -1, lines_used, rival, rival_fit, vertices, flags);
    m_relabel = -1;
    if (!solved) continue;
    ambiguous = rival_fit.rms_px <= as_good && rival.t_c_m.z() > 0.0 &&
                !m_symmetries.equivalent(rival, pose, distinct) &&
                (!m_params.mirrored_rival_relabel || rivalShowsMeasuredEdges(pose, rival, k));
    if (ambiguous) rival_out = rival;
  }
  collectVertices(-1);  // leave the buffers as the kept solution saw them
  return ambiguous;
}

bool NearRangeTracker::nearTwinRivalFits(const Pose& pose, const PoseFitResult& fit, int lines_used,
                                         Pose& rival_out) {
  // A near-square plate's quarter turn, tilted and moved a few per cent in range, draws nearly the same
  // outline (campaign octagon/172, 2.66 x 2.51 m at 30 m: acquired 90 deg off, its fits mostly 0.5-0.9 px rms
  // where the true pose's were 0.06-0.3, and delivered for 11 frames). Relabelled onto the twin's features
  // the measured lines say which of the two they belong to, as mirroredRivalFits does for the depth mirror.
  const double range = pose.t_c_m.norm();
  if (nearTwinCount() == 0 || !(range > 0.0)) return false;  // nothing refitted, the buffers untouched
  PoseTolerance distinct;
  distinct.position_m = kRivalDistinctRel * range;
  distinct.attitude_rad = kRivalDistinctDeg * kRadPerDeg;
  const double as_good = std::max(kRivalRmsFactor * fit.rms_px, fit.rms_px + m_params.pixel_sigma_px);
  // The twin of a fit that bent its tilt and range to the wrong labels starts on the wrong side of a flat
  // target's two-tilt ambiguity (test NearTwinRivalTest, octagon/172's plate rendered at 20 m: LM from there
  // stopped 20 deg away at 4x the true pose's rms), so its depth-mirrored starts (mirroredRivalFits) are
  // tried too.
  const Vec3 los = pose.t_c_m / range;
  const Mat3 depth_mirror = Mat3::Identity() - 2.0 * los * los.transpose();
  bool rival_fits = false;
  for (int k = m_mirror_count; k < m_relabel_count && !rival_fits; ++k) {
    const Pose twin = m_symmetries.nearTwin(pose, m_relabels[static_cast<std::size_t>(k)].near_index);
    for (int m = -1; m < m_mirror_count && !rival_fits; ++m) {
      Pose start = twin;
      if (m >= 0) start.R_c_m = depth_mirror * twin.R_c_m * m_relabels[static_cast<std::size_t>(m)].map;
      Pose rival;
      PoseFitResult rival_fit;
      int vertices = 0;
      std::uint32_t flags = 0;
      m_relabel = k;
      const bool solved = solvePose(start, -1, lines_used, rival, rival_fit, vertices, flags);
      m_relabel = -1;
      rival_fits = solved && rival_fit.rms_px <= as_good && rival.t_c_m.z() > 0.0 &&
                   !m_symmetries.equivalent(rival, pose, distinct) && rivalShowsMeasuredEdges(pose, rival, k);
      if (rival_fits) rival_out = rival;
    }
  }
  collectVertices(-1);  // leave the buffers as the kept solution saw them
  return rival_fits;
}

bool NearRangeTracker::rivalShowsMeasuredEdges(const Pose& pose, const Pose& rival, int k) const {
  // Relabelled through an in-plane mirror (x or y of a flat plate) the rival is the plate turned over: the
  // same outline with its back towards the camera, never a pose to hold (campaign plate/40: 103 of 120
  // frames flagged without this test). Only the kept pose's outline lines are asked: the depth-mirrored
  // twin shows every one of them (a box's Necker reversal keeps its silhouette) but hides the interior
  // edges, and those carry no contrast on the boxes where the twin is a real danger (box/191).
  const auto& edges = m_model.edges();
  const auto& surfaces = m_model.surfaces();
  const BoundedBuffer<int>& to_edge = m_relabels[static_cast<std::size_t>(k)].to_edge;
  // Facing or within kRivalGrazingCos of grazing: under perspective the twin of a face seen edge-on may
  // turn its back by a few degrees (box/93: cosines down to -0.21) and still give the same outline.
  const auto shown_by_rival = [&](int s) {
    if (s < 0) return false;
    const ModelSurface& surface = surfaces[static_cast<std::size_t>(s)];
    const Vec3 n = rival.R_c_m * surface.normal_m;
    const Vec3 to_centroid = rival.transform(surface.centroid_m);
    return -n.dot(to_centroid) > -kRivalGrazingCos * to_centroid.norm();
  };
  const auto front = [&](int s) {
    return s >= 0 && viewSurface(surfaces[static_cast<std::size_t>(s)], pose).front_facing;
  };
  for (const EdgeMeasurement& slot : m_edges) {
    if (!slot.line_ok) continue;
    const ModelEdge& kept = edges[static_cast<std::size_t>(slot.model_edge)];
    if (front(kept.surface_left) && front(kept.surface_right)) continue;  // interior
    const int e = to_edge[static_cast<std::size_t>(slot.model_edge)];
    if (e < 0) return false;
    const ModelEdge& edge = edges[static_cast<std::size_t>(e)];
    if (!shown_by_rival(edge.surface_left) && !shown_by_rival(edge.surface_right)) return false;
  }
  return true;
}

}  // namespace visnav
