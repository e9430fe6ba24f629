#include "visnav/geometry/model_symmetry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace visnav {

namespace {

bool alreadyListed(const std::array<Mat3, ModelSymmetries::kCapacity>& list, int count, const Mat3& s) {
  for (int i = 0; i < count; ++i)
    if ((list[static_cast<std::size_t>(i)] - s).cwiseAbs().maxCoeff() < 1e-9) return true;
  return false;
}

/// Largest distance [m] of a vertex turned by `rotation` about `centre_m` from the nearest model vertex.
double vertexSeparationM(const PolygonModel& model, const Mat3& rotation, const Vec3& centre_m) {
  const auto& vertices = model.vertices();
  double worst = 0.0;
  for (const Vec3& v : vertices) {
    const Vec3 w = rotation * (v - centre_m) + centre_m;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3& u : vertices) nearest = std::min(nearest, (u - w).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

bool ModelSymmetries::isSymmetry(const PolygonModel& model, const Mat3& rotation, double tolerance_m,
                                 const Vec3& centre_m) {
  if (vertexSeparationM(model, rotation, centre_m) > tolerance_m) return false;
  const auto& surfaces = model.surfaces();
  for (const ModelSurface& s : surfaces) {
    const Vec3 c = rotation * (s.centroid_m - centre_m) + centre_m;
    const Vec3 n = rotation * s.normal_m;
    if (std::none_of(surfaces.begin(), surfaces.end(), [&](const ModelSurface& u) {
          return u.vertex_indices.size() == s.vertex_indices.size() &&
                 (u.centroid_m - c).norm() <= tolerance_m && (u.normal_m - n).norm() <= 1e-6;
        }))
      return false;
  }
  return true;
}

double rotationAngleRad(const Mat3& a, const Mat3& b) {
  // |log(a^T b)|: exact near 0, where acos((trace - 1) / 2) loses half the digits.
  return logSo3(a.transpose() * b).norm();
}

template <typename Offer>
void ModelSymmetries::forEachCandidate(Offer&& offer) {
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

void ModelSymmetries::find(const PolygonModel& model, double tolerance_rel) {
  m_rotations[0] = Mat3::Identity();
  m_count = 1;
  const double tol_m = tolerance_rel * std::max(1.0, model.boundingRadius());
  forEachCandidate([&](const Mat3& s) {
    if (m_count < kCapacity && !alreadyListed(m_rotations, m_count, s) && isSymmetry(model, s, tol_m))
      m_rotations[static_cast<std::size_t>(m_count++)] = s;
  });
}

void ModelSymmetries::findNear(const PolygonModel& model, double max_rel) {
  m_near_count = 0;
  m_centre_m = Vec3::Zero();
  const auto& vertices = model.vertices();
  if (!(max_rel > 0.0) || vertices.empty()) return;
  for (const Vec3& v : vertices) m_centre_m += v;
  m_centre_m /= static_cast<double>(vertices.size());
  // The symmetries about the centroid (about the origin, find()'s, when the model is centred on it): a turn
  // that shows the same image is not a rival to test.
  std::array<Mat3, kCapacity> exact{};
  int exact_count = 0;
  const double exact_m = kIndistinguishableRel * std::max(1.0, model.boundingRadius());
  forEachCandidate([&](const Mat3& s) {
    if (exact_count < kCapacity && isSymmetry(model, s, exact_m, m_centre_m))
      exact[static_cast<std::size_t>(exact_count++)] = s;
  });
  const double near_m = max_rel * model.boundingRadius();
  forEachCandidate([&](const Mat3& s) {
    if (m_near_count >= kCapacity) return;
    // R S E shows what R S shows for every symmetry E: one entry per class.
    for (int e = 0; e < exact_count; ++e) {
      const Mat3& sym = exact[static_cast<std::size_t>(e)];
      if ((sym - s).cwiseAbs().maxCoeff() < 1e-9) return;
      for (int n = 0; n < m_near_count; ++n)
        if ((m_near[static_cast<std::size_t>(n)] * sym - s).cwiseAbs().maxCoeff() < 1e-9) return;
    }
    if (!isSymmetry(model, s, near_m, m_centre_m)) return;
    m_near_separation_m[static_cast<std::size_t>(m_near_count)] = vertexSeparationM(model, s, m_centre_m);
    m_near[static_cast<std::size_t>(m_near_count++)] = s;
  });
}

void ModelSymmetries::findMirrors(const PolygonModel& model, double tolerance_rel) {
  m_mirror_count = 0;
  m_mirror_centre_m = Vec3::Zero();
  const auto& vertices = model.vertices();
  if (vertices.empty()) return;
  for (const Vec3& v : vertices) m_mirror_centre_m += v;
  m_mirror_centre_m /= static_cast<double>(vertices.size());
  const double tol_m = tolerance_rel * std::max(1.0, model.boundingRadius());
  const std::array<Mat3, 4> reflections = {
      Vec3(-1.0, 1.0, 1.0).asDiagonal(), Vec3(1.0, -1.0, 1.0).asDiagonal(), Vec3(1.0, 1.0, -1.0).asDiagonal(),
      Vec3(-1.0, -1.0, -1.0).asDiagonal()};
  for (const Mat3& m : reflections) {
    if (vertexSeparationM(model, m, m_mirror_centre_m) > tol_m) continue;
    // R' M_a and R' M_b differ by the rotation M_a M_b: when that maps the model onto itself, one twin.
    bool same_class = false;
    for (int k = 0; k < m_mirror_count && !same_class; ++k)
      same_class = isSymmetry(model, m_mirrors[static_cast<std::size_t>(k)] * m, tol_m, m_mirror_centre_m);
    if (!same_class) m_mirrors[static_cast<std::size_t>(m_mirror_count++)] = m;
  }
}

Pose ModelSymmetries::mirrorTwin(const Pose& pose, int i) const {
  const Vec3 centre_c = pose.transform(m_mirror_centre_m);
  const double distance = centre_c.norm();
  if (!(distance > 0.0)) return pose;
  const Vec3 u = centre_c / distance;
  const Mat3 along = Mat3::Identity() - 2.0 * u * u.transpose();
  Pose twin;
  twin.R_c_m = along * pose.R_c_m * m_mirrors[static_cast<std::size_t>(i)];
  twin.t_c_m = centre_c - twin.R_c_m * m_mirror_centre_m;
  return twin;
}

int ModelSymmetries::indistinguishableTwins(double px_per_m, double min_separation_px) const {
  int twins = m_count > 0 ? m_count - 1 : 0;
  if (!(min_separation_px > 0.0) || !(px_per_m > 0.0)) return twins;
  for (int i = 0; i < m_near_count; ++i)
    if (m_near_separation_m[static_cast<std::size_t>(i)] * px_per_m < min_separation_px) ++twins;
  return twins;
}

Pose ModelSymmetries::nearTwin(const Pose& pose, int i) const {
  const Mat3& s = m_near[static_cast<std::size_t>(i)];
  Pose twin;
  twin.R_c_m = pose.R_c_m * s;
  twin.t_c_m = pose.t_c_m + pose.R_c_m * m_centre_m - twin.R_c_m * m_centre_m;
  return twin;
}

double ModelSymmetries::attitudeDistanceRad(const Mat3& a_R_c_m, const Mat3& b_R_c_m) const {
  double best = kPi;
  for (int i = 0; i < m_count; ++i)
    best = std::min(best, rotationAngleRad(a_R_c_m, b_R_c_m * m_rotations[static_cast<std::size_t>(i)]));
  return best;
}

Pose ModelSymmetries::turnedOntoLineOfSight(const Pose& reference, const Pose& candidate) {
  const double range = reference.t_c_m.norm();
  const double candidate_range = candidate.t_c_m.norm();
  if (!(range > 0.0) || !(candidate_range > 0.0)) return reference;
  const Mat3 r = rotationBetween(reference.t_c_m / range, candidate.t_c_m / candidate_range);
  Pose turned;
  turned.R_c_m = r * reference.R_c_m;
  turned.t_c_m = r * reference.t_c_m;
  return turned;
}

double ModelSymmetries::lookDistanceRad(const Pose& reference, const Pose& candidate) const {
  return attitudeDistanceRad(candidate.R_c_m, turnedOntoLineOfSight(reference, candidate).R_c_m);
}

bool ModelSymmetries::equivalent(const Pose& a, const Pose& b, const PoseTolerance& tolerance) const {
  return (a.t_c_m - b.t_c_m).norm() <= tolerance.position_m &&
         attitudeDistanceRad(a.R_c_m, b.R_c_m) <= tolerance.attitude_rad;
}

PoseTolerance PoseTolerance::widened(double position_m, double attitude_rad, const Mat6& covariance) {
  PoseTolerance t;
  t.attitude_rad = attitude_rad + kUnresolvedSigmas * std::sqrt(covariance.topLeftCorner<3, 3>().trace());
  t.position_m = position_m + kUnresolvedSigmas * std::sqrt(covariance.bottomRightCorner<3, 3>().trace());
  return t;
}

bool PoseTolerance::holds(const Pose& a, const Pose& b) const {
  return (a.t_c_m - b.t_c_m).norm() <= position_m && rotationAngleRad(a.R_c_m, b.R_c_m) <= attitude_rad;
}

}  // namespace visnav
