// Worst-case error envelope of paper sec. IV-A: every vertex measured +-delta px off in x and y, the pose
// re-solved from the truth pose; the envelope is the largest |error| per axis over the offset combinations.
#pragma once

#include <cstdint>
#include <vector>

#include "visnav/eval/metrics.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/solver/levenberg_marquardt.hpp"

namespace visnav::eval {

struct EnvelopeOptions {
  double max_obliquity_deg = 50.0;     ///< surfaces beyond this obliquity are not tracked (CONVENTIONS.md)
  int max_exhaustive_offsets = 10;     ///< exhaustive when 2 * V <= this (2^(2V) combinations)
  int sampled_combinations = 256;      ///< random sign patterns otherwise, plus 8 structured ones
  std::uint64_t seed = 0x76697365ULL;  ///< Pcg32 seed; reseeded per frame so results ignore stride/order
  /// Near-frontal planar targets have a flat, two-fold pitch/roll minimum (the worst case itself): allow
  /// more iterations than the tracker so the solves converge instead of stopping half way (measured on the
  /// approach: 200 leaves ~20x fewer unconverged solves than 50 at no measurable cost).
  LmOptions lm = [] {
    LmOptions o;
    o.max_iterations = 200;
    return o;
  }();
};

struct FrameEnvelope {
  bool valid = false;  ///< false: fewer than 3 usable vertices (nothing tracked at this pose)
  bool exhaustive = false;
  int vertex_count = 0;
  int combinations = 0;
  int failed_solves = 0;  ///< LM runs not converged: max_iterations or kGaveUp (their pose is still used)
  AxisValues max_abs{};   ///< per-axis envelope: max |error| [m | deg]
  double max_angle_deg = 0.0;
};

/// Indices (ascending, unique) of the vertices of every surface facing the camera with obliquity below
/// `max_obliquity_deg`: n_c . d < -cos(max), d the unit line of sight to the surface centroid.
std::vector<int> envelopeVertices(const PolygonModel& model, const Pose& truth, double max_obliquity_deg);

class EnvelopeSolver {
 public:
  EnvelopeSolver(const PinholeCamera& camera, const PolygonModel& model, const EnvelopeOptions& options)
      : m_camera(camera), m_model(model), m_options(options) {}

  /// One envelope per entry of `deltas_px` at the truth pose; the same sign patterns serve every delta.
  void compute(const Pose& truth, const std::vector<double>& deltas_px, std::vector<FrameEnvelope>& out);

 private:
  void buildPatterns(const std::vector<Vec2>& px);

  const PinholeCamera& m_camera;
  const PolygonModel& m_model;
  EnvelopeOptions m_options;
  std::vector<std::int8_t> m_signs;  ///< combinations x (2V): +-1 for (x0, y0, x1, y1, ...)
  int m_combinations = 0;
  bool m_exhaustive = false;
};

}  // namespace visnav::eval
