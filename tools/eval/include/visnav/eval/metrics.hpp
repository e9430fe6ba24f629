// Per-frame pose errors on the six axes of paper fig. 6, the far-range direction/distance errors, and their
// summary statistics.
#pragma once

#include <array>
#include <vector>

#include "visnav/geometry/pose.hpp"

namespace visnav::eval {

/// Axis order everywhere (CSV, JSON, plot): x, y, z [m] of t_c_m, then yaw, pitch, roll [deg] (DIN 9300).
constexpr int kAxisCount = 6;
using AxisValues = std::array<double, kAxisCount>;

/// "x", "y", "z", "yaw", "pitch", "roll".
const char* axisName(int axis);
/// "m" or "deg".
const char* axisUnit(int axis);

/// Wraps an angle in degrees to (-180, 180].
double wrapDeg180(double angle_deg);

/// estimate - truth per axis: position difference of t_c_m [m] and wrapped YPR differences [deg].
AxisValues poseError(const Pose& estimate, const Pose& truth);
/// Total attitude error |log(R_est * R_truth^T)| [deg].
double attitudeErrorDeg(const Pose& estimate, const Pose& truth);

/// Unit line of sight in the camera frame from azimuth = atan2(x, z) and elevation = atan2(-y, hypot(x, z))
/// (CONVENTIONS.md, NavSolution): (cos el sin az, -sin el, cos el cos az).
Vec3 directionFromAzimuthElevation(double azimuth_rad, double elevation_rad);

/// Errors of one far-range estimate (paper sec. III). Shared by visnav-eval and visnav-far-eval so both
/// report the same numbers.
struct FarRangeError {
  double direction_deg =
      0.0;  ///< angle between the estimated line of sight and the truth's t_c_m (model origin)
  double distance_pct = 0.0;  ///< 100 (d_est - t_c_m.z) / t_c_m.z, signed; distance is along the boresight
};
/// `direction_c` need not be unit length. False (and `out` untouched) when the truth is not in front of the
/// camera (t_c_m.z <= 0) or an input is not finite or zero.
bool farRangeError(const Vec3& direction_c, double distance_m, const Vec3& t_c_m_truth, FarRangeError& out);

struct ErrorStats {
  int count = 0;
  double median = 0.0;
  double p95 = 0.0;
  double max = 0.0;
};

/// Percentile p in [0, 1] of sorted values by linear interpolation between order statistics (rank
/// p * (n - 1), the numpy default). 0 for an empty input.
double percentileSorted(const std::vector<double>& sorted, double p);
/// Median, p95 and max of |values|.
ErrorStats absStats(const std::vector<double>& values);

}  // namespace visnav::eval
