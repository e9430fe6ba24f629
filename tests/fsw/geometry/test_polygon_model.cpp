#include <gtest/gtest.h>

#include "visnav/geometry/polygon_model.hpp"

namespace visnav {
namespace {

std::vector<Vec3> square() { return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}; }

ModelSurface surface(std::vector<int> idx, Vec3 normal = Vec3::Zero()) {
  ModelSurface s;
  s.vertex_indices = std::move(idx);
  s.normal_m = normal;
  return s;
}

TEST(PolygonModel, BoxHasTwelveSharedEdges) {
  const PolygonModel box = makeBox(1, 2, 3);
  ASSERT_EQ(box.surfaces().size(), 6U);
  ASSERT_EQ(box.edges().size(), 12U);
  for (const ModelEdge& e : box.edges()) EXPECT_GE(e.surface_right, 0);
  for (const ModelSurface& s : box.surfaces())
    EXPECT_NEAR(s.normal_m.dot(s.centroid_m.normalized()), 1.0, 1e-12);
}

TEST(PolygonModel, ComputesNormalFromCounterClockwiseOrder) {
  PolygonModel m;
  ASSERT_TRUE(PolygonModel::build(square(), {surface({0, 1, 2, 3})}, m).ok);
  EXPECT_NEAR((m.surfaces()[0].normal_m - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_EQ(m.edges().size(), 4U);
  EXPECT_EQ(m.edges()[0].surface_right, -1);
}

TEST(PolygonModel, RejectsStoredNormalThatContradictsVertexOrder) {
  PolygonModel m;
  const LoadError e = PolygonModel::build(square(), {surface({0, 1, 2, 3}, -Vec3::UnitZ())}, m);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("counter-clockwise"), std::string::npos) << e.message;
}

TEST(PolygonModel, RejectsBadIndexNonPlanarNonConvexAndDegenerate) {
  PolygonModel m;
  EXPECT_FALSE(PolygonModel::build(square(), {surface({0, 1, 7})}, m).ok);
  EXPECT_FALSE(PolygonModel::build(square(), {surface({0, 1})}, m).ok);
  EXPECT_FALSE(PolygonModel::build(square(), {surface({0, 1, 1})}, m).ok);
  auto bent = square();
  bent[2].z() = 0.2;
  EXPECT_FALSE(PolygonModel::build(bent, {surface({0, 1, 2, 3})}, m).ok);
  std::vector<Vec3> dart = {{0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {1, 2, 0}};
  const LoadError e = PolygonModel::build(dart, {surface({0, 1, 2, 3})}, m);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("convex"), std::string::npos) << e.message;
  EXPECT_FALSE(PolygonModel::build({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {surface({0, 1, 2})}, m).ok);
}

TEST(PolygonModel, RejectsInconsistentlyOrientedNeighbours) {
  PolygonModel m;
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  // Both surfaces traverse 1 -> 2 in the same direction.
  const LoadError e = PolygonModel::build(v, {surface({0, 1, 2, 3}), surface({1, 2, 5, 4})}, m);
  EXPECT_FALSE(e.ok);
}

TEST(PolygonModel, FailedBuildLeavesOutputUntouched) {
  PolygonModel m = makeRectanglePlate(2.3, 1.8);
  EXPECT_FALSE(PolygonModel::build(square(), {surface({0, 1, 9})}, m).ok);
  EXPECT_EQ(m.vertices().size(), 4U);
  EXPECT_NEAR(m.vertices()[1].x(), 1.15, 1e-12);
}

}  // namespace
}  // namespace visnav
