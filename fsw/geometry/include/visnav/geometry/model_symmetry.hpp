// Rotational symmetries of a polygon model: rotations S (model frame) that map the model onto itself (every
// vertex onto a vertex, every surface with its outward normal onto a surface), so poses R and R S show the
// same object. A one-sided plate turned over is not a symmetry: its vertices match but its face looks away.
// Acquisition and reacquisition use them to tell a symmetric twin of a hypothesis (the same image, ambiguity
// to flag) from a real rival (a different pose as good as it). Found at init by testing a fixed candidate set
// (the 24 rotations of the cube group and the rotations about z by multiples of 45 and 60 deg: plates, boxes,
// octagons, hexagons); bounded, no allocation after.
// Near-symmetries are the same candidates turning the model about its vertex centroid onto itself only
// within a few per cent of its size (a box of half sizes 0.615 x 0.585 x 0.574 m and its 120 deg turn about a
// body diagonal): a far or noisy image may not tell the two poses apart, so acquisition tests such a near
// twin of its best hypothesis as a rival instead of assuming it away.
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
  /// True when `rotation` about `centre_m` maps the model onto itself (vertices, and surfaces with their
  /// outward normals) within tolerance_m.
  static bool isSymmetry(const PolygonModel& model, const Mat3& rotation, double tolerance_m,
                         const Vec3& centre_m = Vec3::Zero());
  int size() const { return m_count; }
  const Mat3& operator[](int i) const { return m_rotations[static_cast<std::size_t>(i)]; }

  /// Smallest attitude difference [rad] between `a` and any symmetric twin of `b` (R_b S).
  double attitudeDistanceRad(const Mat3& a_R_c_m, const Mat3& b_R_c_m) const;
  /// True when the two poses show the same target pose up to a symmetry: positions and attitudes (modulo
  /// the symmetries) within the tolerance.
  bool equivalent(const Pose& a, const Pose& b, const PoseTolerance& tolerance) const;
  /// `reference` turned about the camera centre onto `candidate`'s line of sight (what a slew does to it).
  static Pose turnedOntoLineOfSight(const Pose& reference, const Pose& candidate);
  /// The look difference [rad]: attitudeDistanceRad between `candidate` and turnedOntoLineOfSight of
  /// `reference`, which a slew does not change and a lost target cannot change much in a few frames.
  double lookDistanceRad(const Pose& reference, const Pose& candidate) const;

  /// Lists the candidate rotations that are not symmetries about the vertex centroid (nor such a symmetry's
  /// product with one already listed) but turn the model about it onto itself within max_rel of the
  /// bounding radius. max_rel <= 0 lists none. find() does not change the list.
  void findNear(const PolygonModel& model, double max_rel);
  int nearCount() const { return m_near_count; }
  const Mat3& near(int i) const { return m_near[static_cast<std::size_t>(i)]; }
  /// How far near(i) moves the model's vertices [m]: the largest distance of a turned vertex from the
  /// nearest vertex of the model (what an image has to tell the two poses apart by).
  double nearSeparationM(int i) const { return m_near_separation_m[static_cast<std::size_t>(i)]; }
  /// Other attitudes an image at `px_per_m` (focal length over depth) cannot tell from a pose's: the
  /// model's symmetries besides the identity, plus the near twins that move its vertices less than
  /// `min_separation_px` there (none when it is <= 0). 0: the attitude is unique. What telemetry flags as
  /// ambiguity (PoseEstimate.symmetric_twins); the pose reported is the one continuous with the track.
  int indistinguishableTwins(double px_per_m, double min_separation_px) const;
  /// The pose that shows the model turned by near(i) about its centroid in place of `pose`:
  /// R S and t + R c - R S c, so the centroid stays where it was.
  Pose nearTwin(const Pose& pose, int i) const;

  /// Lists the reflections (diagonal, det -1) that map the model's vertex set onto itself about its vertex
  /// centroid, one per class (two whose product is a symmetry give the same twin). Their normals need not
  /// match: a one-sided plate mirrored through its own plane is one. find() and findNear() do not change it.
  void findMirrors(const PolygonModel& model, double tolerance_rel = kIndistinguishableRel);
  int mirrorCount() const { return m_mirror_count; }
  /// The depth-reversed ("Necker") twin of `pose` by mirror(i): the model's vertices mirrored through the
  /// plane through its centroid across the line of sight, R' = D_u R M_i (D_u the reflection along the line
  /// of sight u, M_i the model's reflection), the centroid kept. Seen along the line of sight it has the
  /// same outline, so an image without perspective, shading or internal edges does not tell the two apart:
  /// a rival to test, not a symmetry to assume away.
  Pose mirrorTwin(const Pose& pose, int i) const;

 private:
  /// Calls offer(S) for every candidate rotation, in a fixed order.
  template <typename Offer>
  static void forEachCandidate(Offer&& offer);

  std::array<Mat3, kCapacity> m_rotations{};
  int m_count = 0;
  std::array<Mat3, kCapacity> m_near{};
  std::array<double, kCapacity> m_near_separation_m{};
  int m_near_count = 0;
  Vec3 m_centre_m = Vec3::Zero();
  std::array<Mat3, 4> m_mirrors{};
  int m_mirror_count = 0;
  Vec3 m_mirror_centre_m = Vec3::Zero();
};

/// Angle [rad] of the rotation a^T b.
double rotationAngleRad(const Mat3& a, const Mat3& b);

}  // namespace visnav
