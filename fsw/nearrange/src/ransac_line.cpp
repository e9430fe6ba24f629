#include "visnav/nearrange/ransac_line.hpp"

#include <cmath>

#include "visnav/core/types.hpp"

namespace visnav {
namespace {

/// Variance of a zero-mean normal of sigma `sigma` cut to +-threshold: sigma^2 (1 - 2 c phi(c) /
/// erf(c/sqrt2)), c = threshold / sigma.
double cutNormalVariance(double sigma, double threshold) {
  const double c = threshold / sigma;
  const double phi = std::exp(-0.5 * c * c) / std::sqrt(2.0 * kPi);
  return sigma * sigma * (1.0 - 2.0 * c * phi / std::erf(c / std::sqrt(2.0)));
}

int countInliers(const Vec2* points, int count, const Line2d& line, double threshold) {
  const Vec2 n = line.normal();
  int inliers = 0;
  for (int i = 0; i < count; ++i) inliers += std::fabs(n.dot(points[i]) - line.rho_px) <= threshold ? 1 : 0;
  return inliers;
}

/// Marks the consensus set of `line` and refits on it, in place; bounded by a fixed number of rounds.
bool refit(const Vec2* points, int count, double threshold, Line2d& line, std::uint8_t* inlier, Vec2* scratch,
           int& inliers) {
  constexpr int kRefitRounds = 2;
  for (int round = 0; round < kRefitRounds; ++round) {
    const Vec2 n = line.normal();
    int m = 0;
    for (int i = 0; i < count; ++i) {
      inlier[i] = std::fabs(n.dot(points[i]) - line.rho_px) <= threshold ? 1U : 0U;
      if (inlier[i] != 0U) scratch[m++] = points[i];
    }
    inliers = m;
    if (m < 2 || !Line2d::fit(scratch, m, line)) return false;
  }
  const Vec2 n = line.normal();
  int m = 0;
  for (int i = 0; i < count; ++i) {
    inlier[i] = std::fabs(n.dot(points[i]) - line.rho_px) <= threshold ? 1U : 0U;
    m += inlier[i];
  }
  inliers = m;
  return m >= 2;
}

}  // namespace

RansacResult fitLineRansac(const Vec2* points, int count, const RansacParams& params, Pcg32& rng,
                           std::uint8_t* inlier, Vec2* scratch) {
  RansacResult result;
  if (count < 2) return result;
  Line2d best_line;
  int best_inliers = -1;
  for (int it = 0; it < params.iterations; ++it) {
    const auto a = static_cast<int>(rng.below(static_cast<std::uint32_t>(count)));
    auto b = static_cast<int>(rng.below(static_cast<std::uint32_t>(count - 1)));
    if (b >= a) ++b;  // two distinct indices without rejection
    if ((points[a] - points[b]).squaredNorm() < 1e-12) continue;
    const Line2d hypothesis = Line2d::throughPoints(points[a], points[b]);
    const int inliers = countInliers(points, count, hypothesis, params.threshold_px);
    if (inliers > best_inliers) {
      best_inliers = inliers;
      best_line = hypothesis;
      if (inliers == count) break;  // cannot be beaten
    }
  }
  if (best_inliers < 2) return result;
  const int n = count;
  int inliers = 0;
  Line2d line = best_line;
  if (!refit(points, n, params.threshold_px, line, inlier, scratch, inliers)) return result;
  double sq = 0.0;
  const Vec2 normal = line.normal();
  for (int i = 0; i < n; ++i)
    if (inlier[i] != 0U) sq += std::pow(normal.dot(points[i]) - line.rho_px, 2);
  result.ok = true;
  result.line = line;
  result.inliers = inliers;
  result.rms_px = std::sqrt(sq / inliers);
  return result;
}

double uncutScatterVariance(double inlier_variance_px2, double threshold_px) {
  if (!(inlier_variance_px2 > 0.0) || !(threshold_px > 0.0)) return 0.0;
  // Below a quarter of the threshold the cut removes under 0.2 % of the variance: kept as it is.
  if (inlier_variance_px2 < 0.0625 * threshold_px * threshold_px) return inlier_variance_px2;
  double high = 2.0 * threshold_px;
  if (cutNormalVariance(high, threshold_px) <= inlier_variance_px2) return high * high;
  double low = std::sqrt(inlier_variance_px2);  // the cut only ever shrinks the variance
  constexpr int kBisections = 40;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (low + high);
    (cutNormalVariance(mid, threshold_px) < inlier_variance_px2 ? low : high) = mid;
  }
  const double sigma = 0.5 * (low + high);
  return sigma * sigma;
}

}  // namespace visnav
