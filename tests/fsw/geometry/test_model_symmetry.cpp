// ModelSymmetries: the rotations that map a model onto itself (vertices, and surfaces with their normals),
// the twin/rival test acquisition and reacquisition use, and PoseTolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

int countNear(const PolygonModel& model, double max_rel) {
  ModelSymmetries s;
  s.find(model);
  s.findNear(model, max_rel);
  return s.nearCount();
}

TEST(ModelSymmetries, NearTwinsOfABoxAreItsCubeTurnsOnePerClass) {
  // Campaign box/187: within 7 % of a cube. The cube group's 24 turns fall into 6 classes of the box's 4
  // half turns; the 5 besides the identity's are near twins.
  const PolygonModel near_cube = makeBox(0.615, 0.585, 0.574);
  EXPECT_EQ(countNear(near_cube, 0.15), 5);
  EXPECT_EQ(countNear(near_cube, 0.0), 0) << "0 lists none";
  // Campaign box/39: only the quarter turn about x swaps two faces within 2 % of the radius (0.807 vs 0.786).
  const PolygonModel box39 = makeBox(0.930, 0.807, 0.786);
  EXPECT_EQ(countNear(box39, 0.15), 5);
  EXPECT_EQ(countNear(box39, 0.05), 1);
  EXPECT_EQ(countNear(makeBox(0.5, 0.5, 0.5), 0.15), 0) << "a cube's turns are symmetries, not near ones";
  EXPECT_EQ(countNear(makeRectanglePlate(2.3, 1.8), 0.15), 0) << "its quarter turn is 24 % of the radius off";
  // The one-sided plate turned over matches every vertex but shows its back: never a twin.
  EXPECT_EQ(countNear(makeRectanglePlate(2.0, 2.0), 0.15), 0);
}

/// Campaign box/187's near cube with its symmetries and near twins (within 15 % of the radius) found.
ModelSymmetries nearCubeSymmetries(const PolygonModel& near_cube) {
  ModelSymmetries s;
  s.find(near_cube);
  s.findNear(near_cube, 0.15);
  return s;
}

TEST(ModelSymmetries, ANearTwinsSeparationIsHowFarItMovesTheVertices) {
  // box/187's near cube: the quarter turn about x swaps its two closest half sizes (0.585 and 0.574 m), each
  // vertex lands sqrt(2) x 0.011 m from one of the model's; at 26 m and f 1215 px that is 0.7 px.
  const PolygonModel near_cube = makeBox(0.615, 0.585, 0.574);
  const ModelSymmetries s = nearCubeSymmetries(near_cube);
  ASSERT_EQ(s.nearCount(), 5);
  double smallest = 1e9;
  for (int i = 0; i < s.nearCount(); ++i) {
    const double separation = s.nearSeparationM(i);
    smallest = std::min(smallest, separation);
    EXPECT_LE(separation, 0.15 * near_cube.boundingRadius()) << "twin " << i;
    // Exactly the tolerance at which the turn starts to count as mapping the vertices onto themselves.
    EXPECT_TRUE(ModelSymmetries::isSymmetry(near_cube, s.near(i), separation + 1e-9)) << "twin " << i;
    EXPECT_FALSE(ModelSymmetries::isSymmetry(near_cube, s.near(i), separation - 1e-6)) << "twin " << i;
  }
  EXPECT_NEAR(smallest, std::sqrt(2.0) * 0.011, 1e-9);
}

TEST(ModelSymmetries, IndistinguishableTwinsAreTheSymmetriesAndTheNearTwinsTooCloseToSee) {
  // The near cube's closest twin moves its vertices sqrt(2) x 0.011 m = 15.6 mm: 0.73 px at 26 m with
  // f 1215 px (under 2 px: one more twin), 3.2 px at 6 m (told apart). Its 4 half turns give 3 exact twins.
  const PolygonModel near_cube = makeBox(0.615, 0.585, 0.574);
  const ModelSymmetries s = nearCubeSymmetries(near_cube);
  ASSERT_EQ(s.size(), 4);
  EXPECT_EQ(s.indistinguishableTwins(1215.0 / 6.0, 2.0), 3);
  const int far_twins = s.indistinguishableTwins(1215.0 / 26.0, 2.0);
  EXPECT_GT(far_twins, 3);
  EXPECT_LE(far_twins, 3 + s.nearCount());
  EXPECT_EQ(s.indistinguishableTwins(1215.0 / 26.0, 0.0), 3) << "no separation limit: exact ones only";
  EXPECT_EQ(s.indistinguishableTwins(1e-9, 2.0), 3 + s.nearCount()) << "a point: every near twin";
  // A square plate: three quarter turns about its normal show the same image at any range.
  ModelSymmetries square;
  square.find(makeRectanglePlate(2.0, 2.0));
  EXPECT_EQ(square.indistinguishableTwins(100.0, 2.0), 3);
  // An asymmetric-looking rectangle plate: only its half turn.
  ModelSymmetries rectangle;
  rectangle.find(makeRectanglePlate(2.3, 1.8));
  EXPECT_EQ(rectangle.indistinguishableTwins(100.0, 2.0), 1);
  EXPECT_EQ(ModelSymmetries{}.indistinguishableTwins(100.0, 2.0), 0) << "nothing found: unique";
}

TEST(ModelSymmetries, ANearTwinKeepsTheCentroidInPlaceAndItsVerticesClose) {
  // A model whose origin is off its centroid: the twin turns about the centroid, not the origin.
  PolygonModel box = makeBox(0.615, 0.585, 0.574);
  std::vector<Vec3> shifted = box.vertices();
  for (Vec3& v : shifted) v += Vec3(0.3, -0.2, 0.1);
  PolygonModel offset;
  ASSERT_TRUE(PolygonModel::build(shifted, box.surfaces(), offset).ok);
  ModelSymmetries s;
  s.find(offset);
  s.findNear(offset, 0.15);
  ASSERT_EQ(s.nearCount(), 5);
  Pose pose;
  pose.R_c_m = expSo3(Vec3(0.3, -0.5, 0.2));
  pose.t_c_m = Vec3(0.2, -0.1, 12.0);
  const Vec3 centroid = Vec3(0.3, -0.2, 0.1);
  for (int i = 0; i < s.nearCount(); ++i) {
    const Pose twin = s.nearTwin(pose, i);
    EXPECT_NEAR((twin.transform(centroid) - pose.transform(centroid)).norm(), 0.0, 1e-12);
    EXPECT_GT(rotationAngleRad(twin.R_c_m, pose.R_c_m), 60.0 * kRadPerDeg) << "a different attitude";
    for (const Vec3& v : offset.vertices()) {  // each twin vertex lies within 7 % of the radius of one
      double nearest = 1e9;
      for (const Vec3& u : offset.vertices())
        nearest = std::min(nearest, (twin.transform(v) - pose.transform(u)).norm());
      EXPECT_LT(nearest, 0.07 * offset.boundingRadius());
    }
  }
}

TEST(ModelSymmetries, TheLookDistanceIgnoresASlewAndSeesATurnOrANearTwin) {
  // What continuity with a lost track compares: a slew (the camera turning) moves the target across the image
  // without changing its look; the target turning does, and so does its quarter-turn near twin.
  const ModelSymmetries s = nearCubeSymmetries(makeBox(0.615, 0.585, 0.574));
  ASSERT_GT(s.nearCount(), 0);
  Pose reference;
  reference.R_c_m = expSo3(Vec3(0.3, -0.5, 0.2));
  reference.t_c_m = Vec3(0.2, -0.1, 14.0);
  const Mat3 slew = expSo3(Vec3(0.0, 8.0 * kRadPerDeg, 0.0));
  Pose slewed;
  slewed.R_c_m = slew * reference.R_c_m;
  slewed.t_c_m = slew * reference.t_c_m * 0.9;  // and 10 % closer: the look ignores range
  // Off the optical axis (0.9 deg here) the shortest turn onto the new line of sight differs from the slew
  // by a small roll about it.
  EXPECT_LT(s.lookDistanceRad(reference, slewed) * kDegPerRad, 0.1);
  Pose turned = slewed;
  turned.R_c_m = slewed.R_c_m * expSo3(Vec3::UnitZ() * (20.0 * kRadPerDeg));
  EXPECT_NEAR(s.lookDistanceRad(reference, turned) * kDegPerRad, 20.0, 0.1);
  for (int i = 0; i < s.nearCount(); ++i)
    EXPECT_GT(s.lookDistanceRad(reference, s.nearTwin(reference, i)) * kDegPerRad, 60.0) << "twin " << i;
  // The turn onto the line of sight keeps the reference's range and look.
  const Pose onto = ModelSymmetries::turnedOntoLineOfSight(reference, slewed);
  EXPECT_NEAR(onto.t_c_m.norm(), reference.t_c_m.norm(), 1e-12);
  EXPECT_NEAR((onto.t_c_m.normalized() - slewed.t_c_m.normalized()).norm(), 0.0, 1e-12);
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

/// Largest distance [px, f = 1000] of a projected vertex of `a` from the nearest projected vertex of `b`.
double projectedVertexGapPx(const PolygonModel& model, const Pose& a, const Pose& b) {
  double worst = 0.0;
  for (const Vec3& v : model.vertices()) {
    const Vec3 p = a.transform(v);
    double nearest = 1e9;
    for (const Vec3& u : model.vertices()) {
      const Vec3 q = b.transform(u);
      nearest = std::min(nearest, 1000.0 * (p.head<2>() / p.z() - q.head<2>() / q.z()).norm());
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

TEST(ModelSymmetries, ADepthReversedTwinShowsTheSameOutlineUntilPerspectiveTellsThemApart) {
  // Campaign box/120: at 62 m the acquisition verified a box 79 deg off whose depth-reversed twin was the
  // truth within 3.4 deg. A box's three mirrors differ by its half turns: one twin. A one-sided plate has
  // two: mirrored in its own plane (the face still towards the camera: the planar tilt ambiguity) and
  // across it (the face away, which the tracker never fits).
  ModelSymmetries box_mirrors;
  const PolygonModel box = makeBox(0.684, 0.846, 0.406);
  box_mirrors.findMirrors(box);
  ASSERT_EQ(box_mirrors.mirrorCount(), 1);
  ModelSymmetries plate_mirrors;
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  plate_mirrors.findMirrors(plate);
  ASSERT_EQ(plate_mirrors.mirrorCount(), 2);
  // A scalene tetrahedron: no mirror maps its vertices onto themselves.
  const std::vector<Vec3> corners = {Vec3(0.0, 0.0, 0.0), Vec3(1.0, 0.0, 0.0), Vec3(0.2, 0.9, 0.0),
                                     Vec3(0.3, 0.2, 0.7)};
  std::vector<ModelSurface> faces(4);
  faces[0].vertex_indices = {0, 2, 1};
  faces[1].vertex_indices = {0, 1, 3};
  faces[2].vertex_indices = {1, 2, 3};
  faces[3].vertex_indices = {0, 3, 2};
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i].name = "f" + std::to_string(i);
  PolygonModel tetrahedron;
  ASSERT_TRUE(PolygonModel::build(corners, faces, tetrahedron).ok);
  ModelSymmetries none;
  none.findMirrors(tetrahedron);
  EXPECT_EQ(none.mirrorCount(), 0);

  ModelSymmetries box_turns;
  box_turns.find(box);
  Pose pose;
  pose.R_c_m = expSo3(Vec3(0.5, -0.7, 0.3)) * expSo3(Vec3::UnitX() * kPi);
  for (const double range_m : {1000.0, 66.0, 8.0}) {
    pose.t_c_m = Vec3(0.1, -0.05, 1.0).normalized() * range_m;
    const Pose twin = box_mirrors.mirrorTwin(pose, 0);
    EXPECT_NEAR((twin.transform(Vec3::Zero()) - pose.transform(Vec3::Zero())).norm(), 0.0, 1e-9);
    EXPECT_NEAR((twin.R_c_m * twin.R_c_m.transpose() - Mat3::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(twin.R_c_m.determinant(), 1.0, 1e-12) << "a rotation, not a reflection";
    EXPECT_GT(box_turns.attitudeDistanceRad(twin.R_c_m, pose.R_c_m), 30.0 * kRadPerDeg) << "a rival";
    const double gap_px = projectedVertexGapPx(box, twin, pose);
    if (range_m == 1000.0) {
      EXPECT_LT(gap_px, 0.01);
    } else if (range_m == 66.0) {
      EXPECT_LT(gap_px, 2.0) << "within the agreement's tolerance";
    } else {
      EXPECT_GT(gap_px, 2.0) << "perspective tells them apart";
    }
  }
  pose.t_c_m = Vec3(0.0, 0.0, 50.0);
  int facing = 0;
  for (int i = 0; i < plate_mirrors.mirrorCount(); ++i) {
    const Pose twin = plate_mirrors.mirrorTwin(pose, i);
    EXPECT_LT(projectedVertexGapPx(plate, twin, pose), 2.0);
    const Vec3 normal_c = twin.R_c_m * Vec3::UnitZ();
    facing += normal_c.dot(twin.transform(Vec3::Zero())) < 0.0 ? 1 : 0;
  }
  EXPECT_EQ(facing, (pose.R_c_m * Vec3::UnitZ()).dot(pose.t_c_m) < 0.0 ? 1 : 0);
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
