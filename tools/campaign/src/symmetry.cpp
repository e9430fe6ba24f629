#include "visnav/campaign/symmetry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "visnav/geometry/model_symmetry.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::campaign {
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

std::vector<Symmetry> modelSymmetries(const PolygonModel& model) {
  ModelSymmetries found;
  found.find(model);
  std::vector<Symmetry> group;
  group.reserve(static_cast<std::size_t>(found.size()));
  for (int i = 0; i < found.size(); ++i) group.push_back({found[i], rotationName(found[i])});
  return group;
}

double attitudeErrorModuloDeg(const Mat3& R_est, const Mat3& R_truth,
                              const std::vector<Symmetry>& symmetries) {
  double best = logSo3(R_est * R_truth.transpose()).norm() * kDegPerRad;
  for (const Symmetry& s : symmetries)
    best = std::min(best, logSo3(R_est * (R_truth * s.rotation).transpose()).norm() * kDegPerRad);
  return best;
}

Mat3 nearestTwinOfTruth(const Mat3& R_est, const Mat3& R_truth, const std::vector<Symmetry>& symmetries) {
  Mat3 nearest = R_truth;
  double best = logSo3(R_est * R_truth.transpose()).norm();
  for (const Symmetry& s : symmetries) {
    const Mat3 twin = R_truth * s.rotation;
    const double angle = logSo3(R_est * twin.transpose()).norm();
    if (angle < best) {
      best = angle;
      nearest = twin;
    }
  }
  return nearest;
}

}  // namespace visnav::campaign
