// Rotational symmetries of a polygon model: rotations S (model frame) that map the vertex set onto itself,
// so poses R and R S show the same outline. Acquisition and reacquisition use them to tell a symmetric twin
// of a hypothesis (the same image, ambiguity to flag) from a real rival (a different pose as good as it).
// Found at init by testing a fixed candidate set (the 24 rotations of the cube group and the rotations
// about z by multiples of 45 and 60 deg: plates, boxes, octagons, hexagons); bounded, no allocation after.
#pragma once

#include <array>

#include "visnav/core/types.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav {

class ModelSymmetries {
 public:
  static constexpr int kCapacity = 48;

  /// Tests every candidate against the model's vertices (tolerance relative to the bounding radius). The
  /// identity is always the first entry.
  void find(const PolygonModel& model, double tolerance_rel = 1e-6);
  int size() const { return m_count; }
  const Mat3& operator[](int i) const { return m_rotations[static_cast<std::size_t>(i)]; }

  /// Smallest attitude difference [rad] between `a` and any symmetric twin of `b` (R_b S).
  double attitudeDistanceRad(const Mat3& a_R_c_m, const Mat3& b_R_c_m) const;
  /// True when the two poses show the same target pose up to a symmetry: positions within
  /// `position_tol_m` and attitudes within `attitude_tol_rad` modulo the symmetries.
  bool equivalent(const Pose& a, const Pose& b, double position_tol_m, double attitude_tol_rad) const;

 private:
  std::array<Mat3, kCapacity> m_rotations{};
  int m_count = 0;
};

/// Angle [rad] of the rotation a^T b.
double rotationAngleRad(const Mat3& a, const Mat3& b);

}  // namespace visnav
