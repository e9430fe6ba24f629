#include "visnav/acquisition/attitude_grid.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace visnav::acq {

Mat3 rotationZTo(const Vec3& u) {
  const Vec3 z = Vec3::UnitZ();
  const double c = z.dot(u);
  if (c < -1.0 + 1e-12) return Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();
  return Eigen::Quaterniond::FromTwoVectors(z, u).toRotationMatrix();
}

LoadError AttitudeGrid::init(const PolygonModel& model, int view_directions, int roll_steps,
                             double max_obliquity_rad) {
  if (view_directions < 1 || roll_steps < 1) return LoadError::failure("acquisition: empty attitude grid");
  m_roll_steps = roll_steps;
  m_views.reserve(static_cast<std::size_t>(view_directions));
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  const double cos_limit = std::cos(max_obliquity_rad);
  for (int i = 0; i < view_directions; ++i) {
    // Fibonacci lattice: equal-area bands in z, golden-angle steps in azimuth.
    const double z = 1.0 - (2.0 * i + 1.0) / view_directions;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 towards_camera_m(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
    bool usable = false;
    for (const ModelSurface& s : model.surfaces())
      usable = usable || s.normal_m.dot(towards_camera_m) > cos_limit;
    if (!usable) continue;
    // R_lm maps the camera direction (model frame) onto -z_L: the inverse of "z_L -> -direction".
    m_views.push(rotationZTo(-towards_camera_m).transpose());
  }
  if (m_views.empty())
    return LoadError::failure("acquisition: no view direction shows a surface head-on enough");
  m_spacing_rad = std::max(std::sqrt(4.0 * kPi / view_directions), 2.0 * kPi / roll_steps);
  return LoadError::success();
}

Mat3 AttitudeGrid::rotation(int index) const {
  const int view = index / m_roll_steps;
  const int roll = index % m_roll_steps;
  const double angle = 2.0 * kPi * roll / m_roll_steps;
  Mat3 rz;
  rz << std::cos(angle), -std::sin(angle), 0.0, std::sin(angle), std::cos(angle), 0.0, 0.0, 0.0, 1.0;
  return rz * m_views[static_cast<std::size_t>(view)];
}

}  // namespace visnav::acq
