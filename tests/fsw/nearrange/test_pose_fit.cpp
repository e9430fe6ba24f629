#include <gtest/gtest.h>

#include "visnav/nearrange/pose_fit.hpp"

namespace visnav {
namespace {

PinholeCamera vga() {
  return PinholeCamera(CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320, 240));
}

TEST(PoseFit, VertexResidualRecoversTruthFromPerturbedStart) {
  const PinholeCamera cam = vga();
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  const Pose truth = Pose::fromYpr({0.05, -0.1, 0.08}, Vec3(0.3, -0.2, 12.0));
  VertexObservation obs[4];
  for (int i = 0; i < 4; ++i) {
    obs[i].vertex = i;
    ASSERT_TRUE(cam.projectIdeal(truth.transform(plate.vertices()[i]), obs[i].px_ideal));
  }
  Vec6 offset;
  offset << 0.05, -0.04, 0.06, 0.3, -0.2, 1.5;
  Pose pose = truth.boxPlus(offset);
  PoseFitResult result;
  ASSERT_TRUE(fitPoseToVertices(cam, plate, obs, 4, LmOptions{}, 0.1, pose, result));
  EXPECT_LT(truth.boxMinus(pose).norm(), 1e-6);
  EXPECT_LT(result.rms_px, 1e-6);
  EXPECT_EQ(result.lm.residual_count, 8);
  // Covariance is symmetric positive definite.
  EXPECT_LT((result.covariance - result.covariance.transpose()).norm(), 1e-9 * result.covariance.norm());
  EXPECT_GT(result.covariance.ldlt().vectorD().minCoeff(), 0.0);
}

TEST(PoseFit, PointToLineRecoversTruth) {
  const PinholeCamera cam = vga();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  const Pose truth = Pose::fromYpr({0.5, 0.4, 0.3}, Vec3(-0.2, 0.1, 8.0));
  EdgePointObservation obs[12 * 5];
  int n = 0;
  for (int e = 0; e < 12; ++e) {
    const ModelEdge& edge = box.edges()[e];
    for (int k = 1; k <= 5; ++k) {
      const double t = k / 6.0;
      const Vec3 p = (1 - t) * box.vertices()[edge.v0] + t * box.vertices()[edge.v1];
      obs[n].edge = e;
      ASSERT_TRUE(cam.projectIdeal(truth.transform(p), obs[n].px_ideal));
      ++n;
    }
  }
  Vec6 offset;
  offset << -0.03, 0.04, 0.02, 0.1, 0.1, 0.5;
  Pose pose = truth.boxPlus(offset);
  PoseFitResult result;
  ASSERT_TRUE(fitPoseToEdgePoints(cam, box, obs, n, LmOptions{}, 0.1, pose, result));
  EXPECT_LT(truth.boxMinus(pose).norm(), 1e-6);
}

TEST(PoseFit, TooFewVerticesIsReportedNotSolved) {
  const PinholeCamera cam = vga();
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  VertexObservation obs[2] = {{0, Vec2(300, 200)}, {1, Vec2(340, 200)}};
  Pose pose = Pose::fromYpr({}, Vec3(0, 0, 10));
  PoseFitResult result;
  EXPECT_FALSE(fitPoseToVertices(cam, plate, obs, 2, LmOptions{}, 0.1, pose, result));
  EXPECT_EQ(result.lm.status, Status::kNotEnoughData);
}

}  // namespace
}  // namespace visnav
