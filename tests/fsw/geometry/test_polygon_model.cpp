#include <gtest/gtest.h>

#include <cmath>

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

// Issue 13 item 11: a star passes "every turn the same way"; its turns add up to two full turns.
TEST(PolygonModel, RejectsSelfIntersectingStar) {
  std::vector<Vec3> v;
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * kPi * k / 5.0;
    v.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  PolygonModel m;
  EXPECT_TRUE(PolygonModel::build(v, {surface({0, 1, 2, 3, 4})}, m).ok);
  const LoadError e = PolygonModel::build(v, {surface({0, 2, 4, 1, 3})}, m);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("not a simple polygon"), std::string::npos) << e.message;
}

TEST(PolygonModel, RejectsCoordinatesBeyondThePhysicalRange) {
  PolygonModel m;
  const std::vector<Vec3> huge = {{0, 0, 0}, {1e300, 0, 0}, {0, 1e300, 0}};  // gave a NaN normal
  LoadError e = PolygonModel::build(huge, {surface({0, 1, 2})}, m);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("coordinate beyond"), std::string::npos) << e.message;
  const double edge = PolygonModel::kMaxCoordinateM;
  e = PolygonModel::build({{-edge, -edge, 0}, {edge, -edge, 0}, {edge, edge, 0}}, {surface({0, 1, 2})}, m);
  EXPECT_TRUE(e.ok) << e.message;
}

TEST(PolygonModel, RejectsSurfacesWithTooManyVertices) {
  const std::size_t n = PolygonModel::kMaxSurfaceVertices + 1;
  std::vector<Vec3> v;
  std::vector<int> idx;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2.0 * kPi * static_cast<double>(k) / static_cast<double>(n);
    v.emplace_back(std::cos(a), std::sin(a), 0.0);
    idx.push_back(static_cast<int>(k));
  }
  PolygonModel m;
  const LoadError e = PolygonModel::build(v, {surface(idx)}, m);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("more than the limit 1000"), std::string::npos) << e.message;
}

}  // namespace
}  // namespace visnav
