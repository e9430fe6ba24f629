#include "visnav/eval/metrics.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::eval {

const char* axisName(int axis) {
  static const char* const kNames[kAxisCount] = {"x", "y", "z", "yaw", "pitch", "roll"};
  return axis >= 0 && axis < kAxisCount ? kNames[axis] : "?";
}

const char* axisUnit(int axis) { return axis < 3 ? "m" : "deg"; }

double wrapDeg180(double angle_deg) {
  double r = std::fmod(angle_deg, 360.0);
  if (r <= -180.0) r += 360.0;
  if (r > 180.0) r -= 360.0;
  return r;
}

AxisValues poseError(const Pose& estimate, const Pose& truth) {
  AxisValues e{};
  const Vec3 dt = estimate.t_c_m - truth.t_c_m;
  const YawPitchRoll a = estimate.ypr();
  const YawPitchRoll b = truth.ypr();
  e[0] = dt.x();
  e[1] = dt.y();
  e[2] = dt.z();
  e[3] = wrapDeg180((a.yaw_rad - b.yaw_rad) * kDegPerRad);
  e[4] = wrapDeg180((a.pitch_rad - b.pitch_rad) * kDegPerRad);
  e[5] = wrapDeg180((a.roll_rad - b.roll_rad) * kDegPerRad);
  return e;
}

double attitudeErrorDeg(const Pose& estimate, const Pose& truth) {
  return logSo3(estimate.R_c_m * truth.R_c_m.transpose()).norm() * kDegPerRad;
}

Vec3 directionFromAzimuthElevation(double azimuth_rad, double elevation_rad) {
  const double c = std::cos(elevation_rad);
  return Vec3(c * std::sin(azimuth_rad), -std::sin(elevation_rad), c * std::cos(azimuth_rad));
}

bool farRangeError(const Vec3& direction_c, double distance_m, const Vec3& t_c_m_truth, FarRangeError& out) {
  const double z = t_c_m_truth.z();
  if (!direction_c.allFinite() || !t_c_m_truth.allFinite() || !std::isfinite(distance_m) || !(z > 0.0) ||
      !(direction_c.squaredNorm() > 0.0))
    return false;
  // atan2(|a x b|, a . b): accurate for the hundredths of a degree that matter here (acos is not).
  out.direction_deg =
      std::atan2(direction_c.cross(t_c_m_truth).norm(), direction_c.dot(t_c_m_truth)) * kDegPerRad;
  out.distance_pct = 100.0 * (distance_m - z) / z;
  return true;
}

double percentileSorted(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const double rank = std::clamp(p, 0.0, 1.0) * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double frac = rank - static_cast<double>(lo);
  return sorted[lo] + frac * (sorted[hi] - sorted[lo]);
}

ErrorStats absStats(const std::vector<double>& values) {
  std::vector<double> a(values.size());
  std::transform(values.begin(), values.end(), a.begin(), [](double v) { return std::fabs(v); });
  std::sort(a.begin(), a.end());
  ErrorStats s;
  s.count = static_cast<int>(a.size());
  if (a.empty()) return s;
  s.median = percentileSorted(a, 0.5);
  s.p95 = percentileSorted(a, 0.95);
  s.max = a.back();
  return s;
}

}  // namespace visnav::eval
