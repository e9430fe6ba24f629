#include "visnav/nearrange/pose_fit.hpp"

#include <Eigen/LU>
#include <cmath>

namespace visnav {
namespace {

/// d p_c / d delta for the left perturbation of CONVENTIONS.md: [-skew(R p_m), I].
Eigen::Matrix<double, 3, 6> pointJacobian(const Vec3& rotated_m) {
  Eigen::Matrix<double, 3, 6> j;
  j.leftCols<3>() = -skew(rotated_m);
  j.rightCols<3>() = Mat3::Identity();
  return j;
}

inline double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

class VertexProblem {
 public:
  VertexProblem(const PinholeCamera& camera, const PolygonModel& model, const VertexObservation* obs,
                int count)
      : m_camera(camera), m_model(model), m_obs(obs), m_count(count) {}

  int linearize(const Pose& pose, Mat6& jtj, Vec6& jtr, double& cost) const {
    jtj.setZero();
    jtr.setZero();
    cost = 0.0;
    int residuals = 0;
    for (int i = 0; i < m_count; ++i) {
      Vec2 r;
      Mat26 j;
      if (!vertexResidual(m_camera, m_model, m_obs[i], pose, r, j)) return 0;
      jtj.noalias() += j.transpose() * j;
      jtr.noalias() += j.transpose() * r;
      cost += r.squaredNorm();
      residuals += 2;
    }
    return residuals;
  }

  bool evaluate(const Pose& pose, double& cost) const {
    cost = 0.0;
    for (int i = 0; i < m_count; ++i) {
      Vec2 px;
      if (!m_camera.projectIdeal(pose.transform(observedPoint(m_model, m_obs[i])), px)) return false;
      cost += (px - m_obs[i].px_ideal).squaredNorm();
    }
    return true;
  }

 private:
  const PinholeCamera& m_camera;
  const PolygonModel& m_model;
  const VertexObservation* m_obs;
  int m_count;
};

class PointToLineProblem {
 public:
  PointToLineProblem(const PinholeCamera& camera, const PolygonModel& model, const EdgePointObservation* obs,
                     int count)
      : m_camera(camera), m_model(model), m_obs(obs), m_count(count) {}

  int linearize(const Pose& pose, Mat6& jtj, Vec6& jtr, double& cost) const {
    jtj.setZero();
    jtr.setZero();
    cost = 0.0;
    int residuals = 0;
    for (int i = 0; i < m_count; ++i) {
      double r = 0.0;
      Mat16 j;
      if (!pointToLineResidual(m_camera, m_model, m_obs[i], pose, r, j)) return 0;
      jtj.noalias() += j.transpose() * j;
      jtr.noalias() += j.transpose() * r;
      cost += r * r;
      residuals += 1;
    }
    return residuals;
  }

  bool evaluate(const Pose& pose, double& cost) const {
    cost = 0.0;
    for (int i = 0; i < m_count; ++i) {
      const ModelEdge& edge = m_model.edges()[m_obs[i].edge];
      Vec2 a, b;
      if (!m_camera.projectIdeal(pose.transform(m_model.vertices()[edge.v0]), a) ||
          !m_camera.projectIdeal(pose.transform(m_model.vertices()[edge.v1]), b))
        return false;
      const Vec2 d = b - a;
      const double len = d.norm();
      if (len < 1e-9) return false;
      const double r = cross2(d, m_obs[i].px_ideal - a) / len;
      cost += r * r;
    }
    return true;
  }

 private:
  const PinholeCamera& m_camera;
  const PolygonModel& m_model;
  const EdgePointObservation* m_obs;
  int m_count;
};

bool finish(const LmSummary<6>& lm, double pixel_sigma_px, PoseFitResult& result) {
  result.lm = lm;
  if (lm.residual_count < 6) return false;
  result.rms_px = std::sqrt(lm.final_cost / lm.residual_count);
  const int dof = lm.residual_count - 6;
  const double sigma2 =
      pixel_sigma_px > 0.0 ? pixel_sigma_px * pixel_sigma_px : (dof > 0 ? lm.final_cost / dof : 1.0);
  Eigen::FullPivLU<Mat6> lu(lm.information);
  if (!lu.isInvertible()) {
    result.covariance = Mat6::Identity() * 1e6;
    return false;
  }
  result.covariance = sigma2 * lu.inverse();
  return lm.status == Status::kOk;
}

}  // namespace

bool vertexResidual(const PinholeCamera& camera, const PolygonModel& model, const VertexObservation& obs,
                    const Pose& pose, Vec2& residual, Mat26& jacobian) {
  const Vec3 rotated = pose.R_c_m * observedPoint(model, obs);
  Vec2 px;
  Mat23 d_px_d_p;
  if (!camera.projectIdeal(rotated + pose.t_c_m, px, &d_px_d_p)) return false;
  residual = px - obs.px_ideal;
  jacobian = d_px_d_p * pointJacobian(rotated);
  return true;
}

bool pointToLineResidual(const PinholeCamera& camera, const PolygonModel& model,
                         const EdgePointObservation& obs, const Pose& pose, double& residual,
                         Mat16& jacobian) {
  const ModelEdge& edge = model.edges()[obs.edge];
  const Vec3 ra = pose.R_c_m * model.vertices()[edge.v0];
  const Vec3 rb = pose.R_c_m * model.vertices()[edge.v1];
  Vec2 a, b;
  Mat23 da, db;
  if (!camera.projectIdeal(ra + pose.t_c_m, a, &da) || !camera.projectIdeal(rb + pose.t_c_m, b, &db))
    return false;
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len < 1e-9) return false;
  const Vec2 w = obs.px_ideal - a;
  // r = cross(d, w) / |d|: signed distance of the edge point from the projected model edge.
  const double r = cross2(d, w) / len;
  const Vec2 dc_db(w.y(), -w.x());
  const Vec2 dc_da(d.y() - w.y(), w.x() - d.x());
  const Vec2 dr_db = dc_db / len - r * d / (len * len);
  const Vec2 dr_da = dc_da / len + r * d / (len * len);
  residual = r;
  jacobian = dr_da.transpose() * da * pointJacobian(ra) + dr_db.transpose() * db * pointJacobian(rb);
  return true;
}

bool fitPoseToVertices(const PinholeCamera& camera, const PolygonModel& model, const VertexObservation* obs,
                       int count, const LmOptions& options, double pixel_sigma_px, Pose& pose,
                       PoseFitResult& result) {
  VertexProblem problem(camera, model, obs, count);
  const LmSummary<6> lm = solveLevenbergMarquardt<6>(problem, pose, options);
  return finish(lm, pixel_sigma_px, result);
}

bool fitPoseToEdgePoints(const PinholeCamera& camera, const PolygonModel& model,
                         const EdgePointObservation* obs, int count, const LmOptions& options,
                         double pixel_sigma_px, Pose& pose, PoseFitResult& result) {
  PointToLineProblem problem(camera, model, obs, count);
  const LmSummary<6> lm = solveLevenbergMarquardt<6>(problem, pose, options);
  return finish(lm, pixel_sigma_px, result);
}

}  // namespace visnav
