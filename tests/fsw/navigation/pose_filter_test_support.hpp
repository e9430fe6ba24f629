// Shared by the pose-filter tests: a seeded Gaussian sampler, ground truth driven by exactly the filter's
// process model, a tracker-like measurement covariance, the state error against truth.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "visnav/core/rng.hpp"
#include "visnav/navigation/pose_filter.hpp"

namespace visnav::nav::pose_filter_test {

constexpr double kDt = 0.2;  // 5 Hz

inline double gauss(Pcg32& rng) {
  // Box-Muller; uniform() < 1 so 1 - u > 0.
  const double u1 = 1.0 - rng.uniform();
  const double u2 = rng.uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * u2);
}

template <int N>
Eigen::Matrix<double, N, 1> sample(Pcg32& rng, const Eigen::Matrix<double, N, N>& cov) {
  Eigen::Matrix<double, N, 1> z;
  for (int i = 0; i < N; ++i) z[i] = gauss(rng);
  return Eigen::LLT<Eigen::Matrix<double, N, N>>(cov).matrixL() * z;
}

/// Ground truth driven by exactly the filter's process model: white accelerations of density q.
struct Truth {
  Pose pose;
  Vec3 w = Vec3::Zero();
  Vec3 v = Vec3::Zero();

  void step(double dt, double q_lin, double q_ang, Pcg32& rng) {
    Mat2 c;
    c << dt * dt * dt / 3.0, dt * dt / 2.0, dt * dt / 2.0, dt;
    const Mat2 l = Eigen::LLT<Mat2>(c).matrixL();
    Vec3 n_rot, n_w, n_pos, n_v;
    for (int i = 0; i < 3; ++i) {
      const Vec2 a = std::sqrt(q_ang) * l * Vec2(gauss(rng), gauss(rng));
      const Vec2 b = std::sqrt(q_lin) * l * Vec2(gauss(rng), gauss(rng));
      n_rot[i] = a[0];
      n_w[i] = a[1];
      n_pos[i] = b[0];
      n_v[i] = b[1];
    }
    pose.R_c_m = expSo3(n_rot) * expSo3(w * dt) * pose.R_c_m;
    pose.t_c_m += v * dt + n_pos;
    w += n_w;
    v += n_v;
  }
};

inline Mat6 trackerLikeCovariance() {
  Vec6 sigma;
  sigma << 0.3 * kRadPerDeg, 0.3 * kRadPerDeg, 0.1 * kRadPerDeg, 0.01, 0.01, 0.15;
  return sigma.cwiseAbs2().asDiagonal();
}

inline Pose measure(const Pose& truth, const Mat6& cov, Pcg32& rng) {
  return truth.boxPlus(sample<6>(rng, cov));
}

inline Vec12 stateError(const PoseFilter& f, const Truth& truth) {
  Vec12 e;
  e.head<6>() = f.pose().boxMinus(truth.pose);
  e.segment<3>(PoseFilter::kAngularVelocity) = truth.w - f.angularVelocity();
  e.segment<3>(PoseFilter::kVelocity) = truth.v - f.velocity();
  return e;
}

inline PoseFilter makeFilter(const PoseFilterParams& params = {}) {
  PoseFilter f;
  EXPECT_TRUE(f.init(params).ok);
  return f;
}

}  // namespace visnav::nav::pose_filter_test
