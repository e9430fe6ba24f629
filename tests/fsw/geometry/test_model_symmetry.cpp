// ModelSymmetries: the rotations that map a model onto itself (vertices, and surfaces with their normals),
// the twin/rival test acquisition and reacquisition use, and PoseTolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "visnav/geometry/model_symmetry.hpp"

namespace visnav {
namespace {

int countFound(const PolygonModel& model) {
  ModelSymmetries s;
  s.find(model);
  return s.size();
}

TEST(ModelSymmetries, PlateBoxAndCube) {
  EXPECT_EQ(countFound(makeRectanglePlate(2.3, 1.8)), 2);  // identity, z180
  EXPECT_EQ(countFound(makeRectanglePlate(2.0, 2.0)), 4);  // quarter turns about the normal
  EXPECT_EQ(countFound(makeBox(0.8, 0.6, 0.5)), 4);        // half turns about x, y, z
  EXPECT_EQ(countFound(makeBox(0.5, 0.5, 0.8)), 8);        // square prism
  EXPECT_EQ(countFound(makeBox(0.5, 0.5, 0.5)), 24);       // the cube's rotation group
  ModelSymmetries s;
  s.find(makeBox(0.5, 0.5, 0.5));
  EXPECT_TRUE((s[0] - Mat3::Identity()).norm() == 0.0) << "identity first";
  for (int i = 0; i < s.size(); ++i)
    EXPECT_NEAR((s[i] * s[i].transpose() - Mat3::Identity()).norm(), 0.0, 1e-12);
}

TEST(ModelSymmetries, NearSymmetriesWithinOnePercentCount) {
  // Campaign box/2: x and z half sizes 1 mm apart; at 20 px across that is 0.02 px.
  EXPECT_EQ(countFound(makeBox(0.848, 0.478, 0.847)), 8);
  EXPECT_EQ(countFound(makeBox(0.848, 0.478, 0.80)), 4);  // 5 % apart: told apart
  ModelSymmetries exact;
  exact.find(makeBox(0.848, 0.478, 0.847), 1e-6);
  EXPECT_EQ(exact.size(), 4);
}

TEST(ModelSymmetries, AOneSidedPlateTurnedOverIsNotASymmetry) {
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  const Mat3 flip = expSo3(Vec3::UnitX() * kPi);  // the vertices match, the face looks away
  EXPECT_FALSE(ModelSymmetries::isSymmetry(plate, flip, 1e-6));
  EXPECT_TRUE(ModelSymmetries::isSymmetry(plate, expSo3(Vec3::UnitZ() * kPi), 1e-6));
  EXPECT_TRUE(ModelSymmetries::isSymmetry(makeBox(0.8, 0.6, 0.5), flip, 1e-6));  // closed: a face is there
}

TEST(ModelSymmetries, TwinIsEquivalentRivalIsNot) {
  ModelSymmetries s;
  s.find(makeRectanglePlate(2.3, 1.8));
  Pose a;
  a.R_c_m = expSo3(Vec3(0.2, -0.1, 0.4)) * expSo3(Vec3::UnitX() * kPi);
  a.t_c_m = Vec3(0.1, 0.0, 10.0);
  Pose twin = a;
  twin.R_c_m = a.R_c_m * expSo3(Vec3::UnitZ() * kPi);
  Pose rival = a;
  rival.R_c_m = expSo3(Vec3::UnitY() * (20.0 * kRadPerDeg)) * a.R_c_m;  // a tilt 20 deg off
  const PoseTolerance tol{0.5, 5.0 * kRadPerDeg};
  EXPECT_NEAR(s.attitudeDistanceRad(twin.R_c_m, a.R_c_m), 0.0, 1e-9);
  EXPECT_TRUE(s.equivalent(twin, a, tol));
  EXPECT_FALSE(s.equivalent(rival, a, tol));
  EXPECT_FALSE(tol.holds(twin, a)) << "holds() compares plain angles: no symmetry";
  Pose moved = a;
  moved.t_c_m.x() += 1.0;
  EXPECT_FALSE(s.equivalent(moved, a, tol));
}

TEST(PoseTolerance, WidenedByThreeSigmasOfTheCovariance) {
  Mat6 cov = Mat6::Zero();
  cov.topLeftCorner<3, 3>() = Mat3::Identity() * std::pow(1.0 * kRadPerDeg, 2) / 3.0;  // 1 deg in all
  cov.bottomRightCorner<3, 3>() = Mat3::Identity() * 0.01 / 3.0;                       // 0.1 m in all
  const PoseTolerance t = PoseTolerance::widened(0.5, 5.0 * kRadPerDeg, cov);
  EXPECT_NEAR(t.attitude_rad, 8.0 * kRadPerDeg, 1e-12);
  EXPECT_NEAR(t.position_m, 0.8, 1e-12);
  const PoseTolerance none = PoseTolerance::widened(0.5, 0.1, Mat6::Zero());
  EXPECT_DOUBLE_EQ(none.position_m, 0.5);
  EXPECT_DOUBLE_EQ(none.attitude_rad, 0.1);
}

}  // namespace
}  // namespace visnav
