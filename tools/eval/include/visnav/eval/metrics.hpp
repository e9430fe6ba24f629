// Per-frame pose errors on the six axes of paper fig. 6 and their summary statistics.
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
