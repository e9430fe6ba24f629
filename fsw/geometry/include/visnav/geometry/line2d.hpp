// Image lines in the (theta, rho) form of paper fig. 4: x cos(theta) + y sin(theta) = rho, theta the angle of
// the line normal from the x axis, rho the distance from the pixel-grid origin. No singular direction.
#pragma once

#include "visnav/core/types.hpp"

namespace visnav {

struct Line2d {
  double theta_rad = 0.0;
  double rho_px = 0.0;

  Vec2 normal() const;
  /// Signed distance of p from the line (positive on the normal's side).
  double signedDistance(const Vec2& p) const { return normal().dot(p) - rho_px; }

  static Line2d throughPoints(const Vec2& a, const Vec2& b);
  /// Total-least-squares fit (principal axis of the scatter). False when fewer than 2 distinct points.
  static bool fit(const Vec2* points, int count, Line2d& out);
};

/// Eq. 6 rewritten by Cramer's rule, without the paper's division by sin(theta1), so a vertical first line
/// works. Returns false when the lines are parallel within `min_sin_angle` (|sin(theta1 - theta2)|).
bool intersect(const Line2d& a, const Line2d& b, Vec2& out, double min_sin_angle = 1e-3);

}  // namespace visnav
