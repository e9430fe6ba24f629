#include "visnav/campaign/symmetry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "visnav/geometry/pose.hpp"

namespace visnav::campaign {
namespace {

constexpr std::size_t kMaxGroup = 48;  // the largest finite rotation group with a cube's axes has 24

bool sameRotation(const Mat3& a, const Mat3& b) { return (a - b).cwiseAbs().maxCoeff() < 1e-9; }

bool contains(const std::vector<Symmetry>& group, const Mat3& r) {
  return std::any_of(group.begin(), group.end(),
                     [&](const Symmetry& s) { return sameRotation(s.rotation, r); });
}

Mat3 snap(const Mat3& r) {
  // Products of exact-looking rotations pick up 1e-16 noise; snap entries near 0 and +-1 so the group
  // (and its names) are reproducible bit for bit.
  Mat3 out = r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double v = out(i, j);
      if (std::fabs(v) < 1e-12) out(i, j) = 0.0;
      if (std::fabs(std::fabs(v) - 1.0) < 1e-12) out(i, j) = v > 0.0 ? 1.0 : -1.0;
    }
  return out;
}

}  // namespace

bool isModelSymmetry(const PolygonModel& model, const Mat3& rotation, double tolerance_m) {
  const double tol = tolerance_m > 0.0 ? tolerance_m : 1e-6 * std::max(1.0, model.boundingRadius());
  const auto& vertices = model.vertices();
  for (const Vec3& v : vertices) {
    const Vec3 w = rotation * v;
    const bool hit =
        std::any_of(vertices.begin(), vertices.end(), [&](const Vec3& u) { return (u - w).norm() <= tol; });
    if (!hit) return false;
  }
  const auto& surfaces = model.surfaces();
  for (const ModelSurface& s : surfaces) {
    const Vec3 c = rotation * s.centroid_m;
    const Vec3 n = rotation * s.normal_m;
    const bool hit = std::any_of(surfaces.begin(), surfaces.end(), [&](const ModelSurface& u) {
      return u.vertex_indices.size() == s.vertex_indices.size() && (u.centroid_m - c).norm() <= tol &&
             (u.normal_m - n).norm() <= 1e-6;
    });
    if (!hit) return false;
  }
  return true;
}

std::string rotationName(const Mat3& rotation) {
  const Vec3 w = logSo3(rotation);
  const double angle = w.norm();
  if (angle < 1e-9) return "identity";
  const Vec3 axis = w / angle;
  const int deg = static_cast<int>(std::lround(angle * kDegPerRad));
  const char* names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (std::fabs(std::fabs(axis[a]) - 1.0) < 1e-9) {
      // A negative axis is the positive one turned the other way: -z90 == z270.
      const int turn = axis[a] > 0.0 ? deg : 360 - deg;
      return std::string(names[a]) + std::to_string(turn);
    }
  }
  char buf[96];
  std::snprintf(buf, sizeof(buf), "rot%d[%.3f,%.3f,%.3f]", deg, axis.x() + 0.0, axis.y() + 0.0,
                axis.z() + 0.0);
  return buf;
}

std::vector<Symmetry> modelSymmetries(const PolygonModel& model, double tolerance_m) {
  std::vector<Symmetry> group{{Mat3::Identity(), "identity"}};
  std::vector<Mat3> candidates;
  for (int axis = 0; axis < 3; ++axis)
    for (int k = 1; k <= 3; ++k) candidates.push_back(snap(expSo3(Vec3::Unit(axis) * (k * 0.5 * kPi))));
  for (int k = 0; k < 4; ++k) candidates.push_back(expSo3(Vec3::UnitZ() * ((45.0 + 90.0 * k) * kRadPerDeg)));
  for (const Mat3& c : candidates)
    if (!contains(group, c) && isModelSymmetry(model, c, tolerance_m)) group.push_back({c, rotationName(c)});
  // Closure: products of found symmetries (bounded: a finite group never exceeds kMaxGroup here).
  for (std::size_t i = 0; i < group.size() && group.size() < kMaxGroup; ++i) {
    for (std::size_t j = 0; j < group.size() && group.size() < kMaxGroup; ++j) {
      const Mat3 p = snap(group[i].rotation * group[j].rotation);
      if (!contains(group, p) && isModelSymmetry(model, p, tolerance_m))
        group.push_back({p, rotationName(p)});
    }
  }
  return group;
}

double attitudeErrorModuloDeg(const Mat3& R_est, const Mat3& R_truth,
                              const std::vector<Symmetry>& symmetries) {
  double best = logSo3(R_est * R_truth.transpose()).norm() * kDegPerRad;
  for (const Symmetry& s : symmetries)
    best = std::min(best, logSo3(R_est * (R_truth * s.rotation).transpose()).norm() * kDegPerRad);
  return best;
}

}  // namespace visnav::campaign
