#include "visnav/geometry/line2d.hpp"

#include <cmath>

namespace visnav {

Vec2 Line2d::normal() const { return {std::cos(theta_rad), std::sin(theta_rad)}; }

Line2d Line2d::throughPoints(const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  Line2d line;
  line.theta_rad = std::atan2(d.x(), -d.y());  // normal = (-dy, dx) rotated: (cos, sin) ~ (-d.y, d.x)
  line.rho_px = line.normal().dot(a);
  return line;
}

bool Line2d::fit(const Vec2* points, int count, Line2d& out) {
  if (count < 2) return false;
  Vec2 mean = Vec2::Zero();
  for (int i = 0; i < count; ++i) mean += points[i];
  mean /= static_cast<double>(count);
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (int i = 0; i < count; ++i) {
    const Vec2 d = points[i] - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  if (sxx + syy < 1e-18) return false;
  // The normal is the eigenvector of the smaller eigenvalue; its angle in closed form.
  const double direction = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // angle of the principal axis
  out.theta_rad = direction + 0.5 * kPi;
  out.rho_px = out.normal().dot(mean);
  return true;
}

bool intersect(const Line2d& a, const Line2d& b, Vec2& out, double min_sin_angle) {
  const double c1 = std::cos(a.theta_rad), s1 = std::sin(a.theta_rad);
  const double c2 = std::cos(b.theta_rad), s2 = std::sin(b.theta_rad);
  const double det = c1 * s2 - c2 * s1;  // = sin(theta2 - theta1)
  if (std::fabs(det) < min_sin_angle) return false;
  out.x() = (s2 * a.rho_px - s1 * b.rho_px) / det;
  out.y() = (c1 * b.rho_px - c2 * a.rho_px) / det;
  return true;
}

}  // namespace visnav
