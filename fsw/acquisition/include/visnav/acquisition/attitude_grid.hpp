// The fixed set of attitude hypotheses searched by acquisition: viewing directions spread evenly over the
// sphere (Fibonacci lattice) times in-plane roll steps. Attitudes are built in the line-of-sight frame L
// (z towards the target); the hypothesis for a target seen along unit direction u is R_c_m = R_cl(u) * R_lm.
// Views from which no surface of the model is seen within max_obliquity of head-on are dropped at init: the
// tracker could not start on them anyway (sec. II-H, 45 deg gate). Built once; read-only afterwards.
#pragma once

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"
#include "visnav/geometry/polygon_model.hpp"

namespace visnav::acq {

class AttitudeGrid {
 public:
  LoadError init(const PolygonModel& model, int view_directions, int roll_steps, double max_obliquity_rad);

  int size() const { return static_cast<int>(m_views.size()) * m_roll_steps; }
  int views() const { return static_cast<int>(m_views.size()); }
  int rollSteps() const { return m_roll_steps; }
  /// Mean angular spacing of the grid [rad] (the larger of view spacing and roll step).
  double spacingRad() const { return m_spacing_rad; }

  /// Hypothesis index in [0, size()) -> R_lm (model to line-of-sight frame).
  Mat3 rotation(int index) const;

 private:
  BoundedBuffer<Mat3> m_views;  ///< R_lm for roll 0: the view direction maps to -z_L (towards the camera)
  int m_roll_steps = 1;
  double m_spacing_rad = 0.0;
};

/// Rotation taking +z to the unit vector u (the shortest one; defined for every u).
Mat3 rotationZTo(const Vec3& u);

}  // namespace visnav::acq
