// Geometric symmetries of a target model: rotations S of the model frame under which the model is the same
// object (vertex set, and every surface with its outward normal, mapped onto the model itself). An estimate
// R_est is then as right as R_truth S for any S, so attitude errors are taken modulo them (as visnav-eval
// does with --symmetry: min over S of the angle between R_est and R_truth S).
#pragma once

#include <string>
#include <vector>

#include "visnav/geometry/polygon_model.hpp"

namespace visnav::campaign {

struct Symmetry {
  Mat3 rotation = Mat3::Identity();  ///< S, model frame
  std::string name;                  ///< "identity", "z180", "x90", or "rot120[0.577,0.577,0.577]"
};

/// True when S maps the model onto itself: every vertex lands on a vertex, every surface (centroid and
/// outward normal) on a surface with as many vertices. `tolerance_m` is absolute; <= 0 picks
/// 1e-6 * max(1, bounding radius).
bool isModelSymmetry(const PolygonModel& model, const Mat3& rotation, double tolerance_m = 0.0);

/// The symmetry group found from the candidates (90/180/270 deg about x, y and z, 45 + k 90 deg about z),
/// closed under composition (products of symmetries are symmetries, e.g. the 120 deg turns of a cube).
/// Identity first, then in order of discovery; deterministic.
std::vector<Symmetry> modelSymmetries(const PolygonModel& model, double tolerance_m = 0.0);

/// Angle [deg] between R_est and the nearest R_truth S over `symmetries` (plain angle when empty).
double attitudeErrorModuloDeg(const Mat3& R_est, const Mat3& R_truth,
                              const std::vector<Symmetry>& symmetries);

/// "z180", "x90", ...: axis-angle name of a rotation (a model axis when it is one).
std::string rotationName(const Mat3& rotation);

}  // namespace visnav::campaign
