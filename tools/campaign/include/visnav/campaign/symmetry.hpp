// Geometric symmetries of a target model, named (fsw/geometry model_symmetry.hpp finds them: rotations S of
// the model frame under which the model is the same object). An estimate
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

/// The model's symmetry group as fsw/geometry finds it (ModelSymmetries, the one the flight code uses to
/// tell a twin from a rival), each with its name. Identity first; deterministic.
std::vector<Symmetry> modelSymmetries(const PolygonModel& model);

/// Angle [deg] between R_est and the nearest R_truth S over `symmetries` (plain angle when empty).
double attitudeErrorModuloDeg(const Mat3& R_est, const Mat3& R_truth,
                              const std::vector<Symmetry>& symmetries);

/// R_truth S for the S of `symmetries` nearest to R_est (R_truth when empty): the truth as the estimate
/// labels the model's features, so that a feature of the estimate is compared with the same feature of
/// the truth (a box's edge 0 fitted on its z180 twin lies where the truth's opposite edge projects).
Mat3 nearestTwinOfTruth(const Mat3& R_est, const Mat3& R_truth, const std::vector<Symmetry>& symmetries);

/// "z180", "x90", ...: axis-angle name of a rotation (a model axis when it is one).
std::string rotationName(const Mat3& rotation);

}  // namespace visnav::campaign
