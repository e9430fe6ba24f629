#include "visnav/geometry/model_symmetry.hpp"

#include <algorithm>
#include <cmath>

namespace visnav {

namespace {

bool mapsOntoItself(const PolygonModel& model, const Mat3& s, double tol_m) {
  const auto& vertices = model.vertices();
  for (const Vec3& v : vertices) {
    const Vec3 w = s * v;
    const bool found = std::any_of(vertices.begin(), vertices.end(),
                                   [&](const Vec3& u) { return (u - w).squaredNorm() <= tol_m * tol_m; });
    if (!found) return false;
  }
  return true;
}

bool alreadyListed(const std::array<Mat3, ModelSymmetries::kCapacity>& list, int count, const Mat3& s) {
  for (int i = 0; i < count; ++i)
    if ((list[static_cast<std::size_t>(i)] - s).cwiseAbs().maxCoeff() < 1e-9) return true;
  return false;
}

}  // namespace

double rotationAngleRad(const Mat3& a, const Mat3& b) {
  const double c = 0.5 * ((a.transpose() * b).trace() - 1.0);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

void ModelSymmetries::find(const PolygonModel& model, double tolerance_rel) {
  m_count = 0;
  m_rotations[0] = Mat3::Identity();
  m_count = 1;
  const double tol_m = std::max(1e-12, tolerance_rel * model.boundingRadius());
  auto offer = [&](const Mat3& s) {
    if (m_count < kCapacity && !alreadyListed(m_rotations, m_count, s) && mapsOntoItself(model, s, tol_m))
      m_rotations[static_cast<std::size_t>(m_count++)] = s;
  };
  // The cube group: products of quarter turns about x, y and z (4 x 4 x 4 products cover all 24).
  const Mat3 qx = expSo3(Vec3(0.5 * kPi, 0.0, 0.0));
  const Mat3 qy = expSo3(Vec3(0.0, 0.5 * kPi, 0.0));
  const Mat3 qz = expSo3(Vec3(0.0, 0.0, 0.5 * kPi));
  Mat3 rx = Mat3::Identity();
  for (int i = 0; i < 4; ++i, rx = qx * rx) {
    Mat3 ry = Mat3::Identity();
    for (int j = 0; j < 4; ++j, ry = qy * ry) {
      Mat3 rz = Mat3::Identity();
      for (int k = 0; k < 4; ++k, rz = qz * rz) {
        Mat3 s = rx * ry * rz;
        s = s.array().round().matrix();  // exact signed permutation matrices
        offer(s);
      }
    }
  }
  // Regular polygons in the x-y plane (octagon, hexagon), each also flipped about x.
  const Mat3 flip = expSo3(Vec3(kPi, 0.0, 0.0));
  for (const int n : {8, 6}) {
    for (int k = 1; k < n; ++k) {
      const Mat3 rz = expSo3(Vec3(0.0, 0.0, 2.0 * kPi * k / n));
      offer(rz);
      offer(rz * flip);
    }
  }
}

double ModelSymmetries::attitudeDistanceRad(const Mat3& a_R_c_m, const Mat3& b_R_c_m) const {
  double best = kPi;
  for (int i = 0; i < m_count; ++i)
    best = std::min(best, rotationAngleRad(a_R_c_m, b_R_c_m * m_rotations[static_cast<std::size_t>(i)]));
  return best;
}

bool ModelSymmetries::equivalent(const Pose& a, const Pose& b, double position_tol_m,
                                 double attitude_tol_rad) const {
  return (a.t_c_m - b.t_c_m).norm() <= position_tol_m &&
         attitudeDistanceRad(a.R_c_m, b.R_c_m) <= attitude_tol_rad;
}

}  // namespace visnav
