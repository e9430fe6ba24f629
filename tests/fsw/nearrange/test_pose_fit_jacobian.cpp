// Analytic Jacobians of the pose-fit residuals (vertex, eq. 7; point-to-line) against central finite
// differences of the residuals under Pose::boxPlus (left perturbation, CONVENTIONS.md), at random poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "visnav/core/rng.hpp"
#include "visnav/nearrange/pose_fit.hpp"

namespace visnav {
namespace {

// Non-square pixels and a skew, so every entry of d px / d p_c matters.
PinholeCamera camera() {
  return PinholeCamera(CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6.3e-6, 0.02, 318.5, 243.0));
}

double symmetric(Pcg32& rng, double half_width) { return (2.0 * rng.uniform() - 1.0) * half_width; }

/// A random pose with the box well in front of the camera (4..15 m), attitude anywhere within +-0.7 rad.
Pose randomPose(Pcg32& rng) {
  const YawPitchRoll ypr{symmetric(rng, 0.7), symmetric(rng, 0.7), symmetric(rng, 0.7)};
  return Pose::fromYpr(ypr, Vec3(symmetric(rng, 0.6), symmetric(rng, 0.5), 4.0 + 11.0 * rng.uniform()));
}

/// Pose offset of a few degrees / centimetres: the linearisation point differs from the pose the
/// observations were made at, so the residuals are not zero.
Vec6 randomOffset(Pcg32& rng) {
  Vec6 d;
  for (int i = 0; i < 3; ++i) d[i] = symmetric(rng, 0.05);
  for (int i = 3; i < 6; ++i) d[i] = symmetric(rng, 0.1);
  return d;
}

/// Max |a - b| relative to max(1, max |b|).
template <typename A, typename B>
double relativeError(const A& a, const B& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1.0, b.cwiseAbs().maxCoeff());
}

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2e", value);
  return text;
}

constexpr double kStep = 1e-6;       // rad and m
constexpr double kTolerance = 1e-6;  // relative, per the issue
constexpr int kPoses = 8;

TEST(PoseFitJacobian, VertexResidualMatchesCentralDifferences) {
  const PinholeCamera cam = camera();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  Pcg32 rng(1401U, 1U);
  double worst = 0.0;
  for (int p = 0; p < kPoses; ++p) {
    const Pose truth = randomPose(rng);
    const Pose at = truth.boxPlus(randomOffset(rng));
    for (int v = 0; v < static_cast<int>(box.vertices().size()); ++v) {
      VertexObservation obs;
      obs.vertex = v;
      ASSERT_TRUE(cam.projectIdeal(truth.transform(box.vertices()[v]), obs.px_ideal));
      obs.px_ideal += Vec2(symmetric(rng, 1.5), symmetric(rng, 1.5));  // measurement noise
      Vec2 r;
      Mat26 j;
      ASSERT_TRUE(vertexResidual(cam, box, obs, at, r, j));
      Mat26 numeric;
      for (int k = 0; k < 6; ++k) {
        Vec6 h = Vec6::Zero();
        h[k] = kStep;
        Vec2 rp, rm;
        Mat26 unused;
        ASSERT_TRUE(vertexResidual(cam, box, obs, at.boxPlus(h), rp, unused));
        ASSERT_TRUE(vertexResidual(cam, box, obs, at.boxPlus(-h), rm, unused));
        numeric.col(k) = (rp - rm) / (2.0 * kStep);
      }
      const double error = relativeError(j, numeric);
      worst = std::max(worst, error);
      EXPECT_LT(error, kTolerance) << "pose " << p << " vertex " << v << "\nanalytic\n"
                                   << j << "\nnumeric\n"
                                   << numeric;
    }
  }
  RecordProperty("worst_relative_error", scientific(worst));
}

TEST(PoseFitJacobian, PointToLineResidualMatchesCentralDifferences) {
  const PinholeCamera cam = camera();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  Pcg32 rng(1402U, 1U);
  double worst = 0.0;
  for (int p = 0; p < kPoses; ++p) {
    const Pose truth = randomPose(rng);
    const Pose at = truth.boxPlus(randomOffset(rng));
    for (int e = 0; e < static_cast<int>(box.edges().size()); ++e) {
      const ModelEdge& edge = box.edges()[e];
      for (int k = 1; k <= 3; ++k) {
        const double t = k / 4.0;
        EdgePointObservation obs;
        obs.edge = e;
        const Vec3 point = (1.0 - t) * box.vertices()[edge.v0] + t * box.vertices()[edge.v1];
        ASSERT_TRUE(cam.projectIdeal(truth.transform(point), obs.px_ideal));
        obs.px_ideal += Vec2(symmetric(rng, 1.5), symmetric(rng, 1.5));
        double r = 0.0;
        Mat16 j;
        if (!pointToLineResidual(cam, box, obs, at, r, j)) continue;  // edge seen end-on: not evaluable
        Mat16 numeric;
        for (int c = 0; c < 6; ++c) {
          Vec6 h = Vec6::Zero();
          h[c] = kStep;
          double rp = 0.0;
          double rm = 0.0;
          Mat16 unused;
          ASSERT_TRUE(pointToLineResidual(cam, box, obs, at.boxPlus(h), rp, unused));
          ASSERT_TRUE(pointToLineResidual(cam, box, obs, at.boxPlus(-h), rm, unused));
          numeric[c] = (rp - rm) / (2.0 * kStep);
        }
        const double error = relativeError(j, numeric);
        worst = std::max(worst, error);
        EXPECT_LT(error, kTolerance) << "pose " << p << " edge " << e << "\nanalytic " << j << "\nnumeric  "
                                     << numeric;
      }
    }
  }
  RecordProperty("worst_relative_error", scientific(worst));
}

TEST(PoseFitJacobian, PointToLineResidualIsTheSignedDistanceToTheProjectedEdge) {
  const PinholeCamera cam = camera();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  Pcg32 rng(1403U, 1U);
  const Pose pose = randomPose(rng);
  const ModelEdge& edge = box.edges()[0];
  Vec2 a, b;
  ASSERT_TRUE(cam.projectIdeal(pose.transform(box.vertices()[edge.v0]), a));
  ASSERT_TRUE(cam.projectIdeal(pose.transform(box.vertices()[edge.v1]), b));
  const Vec2 along = (b - a).normalized();
  const Vec2 normal(-along.y(), along.x());
  for (const double distance : {-2.0, 0.0, 0.75}) {
    EdgePointObservation obs;
    obs.edge = 0;
    obs.px_ideal = a + 0.3 * (b - a) + distance * normal;
    double r = 0.0;
    Mat16 j;
    ASSERT_TRUE(pointToLineResidual(cam, box, obs, pose, r, j));
    EXPECT_NEAR(std::fabs(r), std::fabs(distance), 1e-9);
  }
}

/// The fits linearise exactly these residuals: the information J^T J the LM reports at the solution is the
/// sum of the per-observation j^T j at the returned pose.
TEST(PoseFitJacobian, FitInformationIsTheSumOfTheObservationJacobians) {
  const PinholeCamera cam = camera();
  const PolygonModel box = makeBox(0.8, 0.6, 0.5);
  Pcg32 rng(1404U, 1U);
  const Pose truth = randomPose(rng);

  std::vector<VertexObservation> vertices(box.vertices().size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    vertices[v].vertex = static_cast<int>(v);
    ASSERT_TRUE(cam.projectIdeal(truth.transform(box.vertices()[v]), vertices[v].px_ideal));
    vertices[v].px_ideal += Vec2(symmetric(rng, 0.5), symmetric(rng, 0.5));
  }
  Pose pose = truth.boxPlus(randomOffset(rng));
  PoseFitResult fit;
  ASSERT_TRUE(fitPoseToVertices(cam, box, vertices.data(), static_cast<int>(vertices.size()), LmOptions{},
                                0.1, pose, fit));
  Mat6 jtj = Mat6::Zero();
  Vec6 jtr = Vec6::Zero();
  double cost = 0.0;
  for (const VertexObservation& obs : vertices) {
    Vec2 r;
    Mat26 j;
    ASSERT_TRUE(vertexResidual(cam, box, obs, pose, r, j));
    jtj += j.transpose() * j;
    jtr += j.transpose() * r;
    cost += r.squaredNorm();
  }
  EXPECT_LT(relativeError(fit.lm.information, jtj), 1e-12);
  EXPECT_NEAR(fit.lm.final_cost, cost, 1e-12 * std::max(1.0, cost));
  // At the minimum the gradient vanishes relative to its scale.
  EXPECT_LT(jtr.cwiseAbs().maxCoeff(), 1e-6 * jtj.cwiseAbs().maxCoeff());

  std::vector<EdgePointObservation> points;
  for (int e = 0; e < static_cast<int>(box.edges().size()); ++e) {
    const ModelEdge& edge = box.edges()[e];
    for (int k = 1; k <= 4; ++k) {
      const double t = k / 5.0;
      EdgePointObservation obs;
      obs.edge = e;
      ASSERT_TRUE(cam.projectIdeal(
          truth.transform((1.0 - t) * box.vertices()[edge.v0] + t * box.vertices()[edge.v1]), obs.px_ideal));
      obs.px_ideal += Vec2(symmetric(rng, 0.5), symmetric(rng, 0.5));
      points.push_back(obs);
    }
  }
  pose = truth.boxPlus(randomOffset(rng));
  ASSERT_TRUE(fitPoseToEdgePoints(cam, box, points.data(), static_cast<int>(points.size()), LmOptions{}, 0.1,
                                  pose, fit));
  jtj.setZero();
  cost = 0.0;
  for (const EdgePointObservation& obs : points) {
    double r = 0.0;
    Mat16 j;
    ASSERT_TRUE(pointToLineResidual(cam, box, obs, pose, r, j));
    jtj += j.transpose() * j;
    cost += r * r;
  }
  EXPECT_LT(relativeError(fit.lm.information, jtj), 1e-12);
  EXPECT_NEAR(fit.lm.final_cost, cost, 1e-12 * std::max(1.0, cost));
}

}  // namespace
}  // namespace visnav
