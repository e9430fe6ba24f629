// Fixed-size Eigen aliases shared by every fsw/ component. Double precision throughout: the per-frame
// arithmetic is small and doubles keep x86 and aarch64 results within a tight tolerance.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace visnav {

using Vec2 = Eigen::Matrix<double, 2, 1>;
using Vec3 = Eigen::Matrix<double, 3, 1>;
using Vec4 = Eigen::Matrix<double, 4, 1>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat2 = Eigen::Matrix<double, 2, 2>;
using Mat3 = Eigen::Matrix<double, 3, 3>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Mat26 = Eigen::Matrix<double, 2, 6>;
using Mat16 = Eigen::Matrix<double, 1, 6>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegPerRad = 180.0 / kPi;
constexpr double kRadPerDeg = kPi / 180.0;

}  // namespace visnav
