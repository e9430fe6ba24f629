// 6-DOF pose update (paper sec. II-G): Levenberg-Marquardt over the vertex residual of eq. 7, or over the
// point-to-line residual of every edge point. Works in ideal (undistorted) pixels: CONVENTIONS.md.
#pragma once

#include "visnav/core/types.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/solver/levenberg_marquardt.hpp"

namespace visnav {

/// A measured image position (ideal pixels) of model vertex `vertex` (eq. 6 output).
struct VertexObservation {
  int vertex = -1;  ///< model vertex index; -1: the model point `point_m`
  Vec2 px_ideal = Vec2::Zero();
  /// Per-axis variance of px_ideal [px^2] propagated from the two fitted lines that made it (0: unknown).
  double variance_px2 = 0.0;
  /// 1 / sin^2 of the angle between the two lines that made it: a line-end error b moves it by
  /// b^2 * inv_sin2 in variance per axis (NearRangeTracker::covarianceScale).
  double inv_sin2 = 0.0;
  /// inv_sin2 x the share (0, 1/2 or 1) of its two lines that are of interior edges: an interior line-end
  /// error b_i adds b_i^2 x this (NearRangeTracker::covarianceScale, interior_edge_bias_px).
  double interior_inv_sin2 = 0.0;
  /// The same for the share of its lines that bound a narrow face (narrow_face_edge_bias_px).
  double narrow_inv_sin2 = 0.0;
  /// With vertex -1: the model-frame point observed, e.g. where the lines of two edges of one face meet
  /// across a short edge between them (a chamfered corner, NearRangeTracker).
  Vec3 point_m = Vec3::Zero();
};

/// The model-frame point a vertex observation measures.
inline const Vec3& observedPoint(const PolygonModel& model, const VertexObservation& obs) {
  return obs.vertex >= 0 ? model.vertices()[static_cast<std::size_t>(obs.vertex)] : obs.point_m;
}

/// A measured edge point (ideal pixels) lying on model edge `edge`.
struct EdgePointObservation {
  int edge = -1;
  Vec2 px_ideal = Vec2::Zero();
};

enum class PoseResidual : std::uint8_t { kVertex, kPointToLine };

struct PoseFitResult {
  LmSummary<6> lm;
  Mat6 covariance = Mat6::Zero();  ///< over (omega, dt), CONVENTIONS.md; sigma^2 (J^T J)^-1
  double rms_px = 0.0;             ///< root-mean-square residual at the solution
};

/// Eq. 7: minimise sum_i |c_i(p) - r_i|^2. `pose` is the start and receives the solution.
/// `pixel_sigma_px` scales the covariance (a posteriori when <= 0: from the residual).
/// Both fits return true only for a converged LM (result.lm.status kOk); kGaveUp, kNotConverged and
/// kNotEnoughData are failed fits (`pose` is then the last iterate).
bool fitPoseToVertices(const PinholeCamera& camera, const PolygonModel& model, const VertexObservation* obs,
                       int count, const LmOptions& options, double pixel_sigma_px, Pose& pose,
                       PoseFitResult& result);

/// Point-to-line: minimise sum_j d(e_j, projected model edge)^2 over every edge inlier point.
bool fitPoseToEdgePoints(const PinholeCamera& camera, const PolygonModel& model,
                         const EdgePointObservation* obs, int count, const LmOptions& options,
                         double pixel_sigma_px, Pose& pose, PoseFitResult& result);

/// One observation's residual, exactly as both fits linearise it, and its Jacobian over the pose delta
/// (omega, dt) of Pose::boxPlus (CONVENTIONS.md). Vertex: projected minus measured position [ideal px].
/// False when the vertex is not in front of the camera.
bool vertexResidual(const PinholeCamera& camera, const PolygonModel& model, const VertexObservation& obs,
                    const Pose& pose, Vec2& residual, Mat26& jacobian);
/// Point-to-line: signed distance [ideal px] of the edge point from its projected model edge. False when an
/// edge end is not in front of the camera or the edge projects to (almost) a point.
bool pointToLineResidual(const PinholeCamera& camera, const PolygonModel& model,
                         const EdgePointObservation& obs, const Pose& pose, double& residual,
                         Mat16& jacobian);

}  // namespace visnav
