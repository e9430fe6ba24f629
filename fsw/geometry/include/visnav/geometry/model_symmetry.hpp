// Rotational symmetries of a polygon model: rotations S (model frame) that map the model onto itself (every
// vertex onto a vertex, every surface with its outward normal onto a surface), so poses R and R S show the
// same object. A one-sided plate turned over is not a symmetry: its vertices match but its face looks away.
// Acquisition and reacquisition use them to tell a symmetric twin of a hypothesis (the same image, ambiguity
// to flag) from a real rival (a different pose as good as it). Found at init by testing a fixed candidate set
// (the 24 rotations of the cube group and the rotations about z by multiples of 45 and 60 deg: plates, boxes,
// octagons, hexagons); bounded, no allocation after.
#pragma once

#include <array>

#include "visnav/core/types.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav {

/// How far two poses may differ and still be one hypothesis.
struct PoseTolerance {
  double position_m = 0.0;
  double attitude_rad = 0.0;
  /// Two poses within three sigmas of the tracker's covariance are not told apart by it.
  static constexpr double kUnresolvedSigmas = 3.0;
  /// A base allowance (e.g. what a target can move in one frame) widened by kUnresolvedSigmas of a pose
  /// covariance over (omega, dt) (CONVENTIONS.md): far out a plate's tilt is weakly observed, and two tilts
  /// within its noise are one hypothesis, not two.
  static PoseTolerance widened(double position_m, double attitude_rad, const Mat6& covariance);
  /// Positions and attitudes (plain rotation angle, no symmetry) within the tolerance.
  bool holds(const Pose& a, const Pose& b) const;
};

class ModelSymmetries {
 public:
  static constexpr int kCapacity = 48;
  /// Shapes that differ by less than 1 % of the bounding radius differ by less than 0.2 px at the smallest
  /// size tracked (20 px across): no image tells a box of 0.848 x 0.478 x 0.847 m from its quarter-turned
  /// twin, so such near-symmetries count as symmetries.
  static constexpr double kIndistinguishableRel = 0.01;

  /// Tests every candidate (tolerance relative to the bounding radius, at least 1e-6 m). The identity is
  /// always the first entry; the order is deterministic.
  void find(const PolygonModel& model, double tolerance_rel = kIndistinguishableRel);
  /// True when `rotation` maps the model onto itself (vertices, and surfaces with their outward normals).
  static bool isSymmetry(const PolygonModel& model, const Mat3& rotation, double tolerance_m);
  int size() const { return m_count; }
  const Mat3& operator[](int i) const { return m_rotations[static_cast<std::size_t>(i)]; }

  /// Smallest attitude difference [rad] between `a` and any symmetric twin of `b` (R_b S).
  double attitudeDistanceRad(const Mat3& a_R_c_m, const Mat3& b_R_c_m) const;
  /// True when the two poses show the same target pose up to a symmetry: positions and attitudes (modulo
  /// the symmetries) within the tolerance.
  bool equivalent(const Pose& a, const Pose& b, const PoseTolerance& tolerance) const;

 private:
  std::array<Mat3, kCapacity> m_rotations{};
  int m_count = 0;
};

/// Angle [rad] of the rotation a^T b.
double rotationAngleRad(const Mat3& a, const Mat3& b);

}  // namespace visnav
