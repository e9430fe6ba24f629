#include "visnav/farrange/outline_sharpness.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace visnav::far {

namespace {

using S = OutlineSharpnessSettings;
using Profile = std::array<double, S::kMaxRayPx + 1>;

/// Pixel (x, y) on a [0, 1] scale; the caller keeps it inside the image.
double brightness(const MonoImage& image, int x, int y) {
  return image.depth == MonoImage::Depth::kU8 ? image.u8.at(x, y) / 255.0
                                              : image.u16.at(x, y) / static_cast<double>(image.max_code);
}

/// The ray's profile p[0 .. count): each sample the mean of three pixels across the ray (raw pixel
/// coordinates, centres at +0.5). Stops at the first sample whose three pixels are not all in the image.
int sampleRay(const MonoImage& image, const Vec2& centre_px, const Vec2& along, int length, Profile& p) {
  const Vec2 across(-along.y(), along.x());
  const int w = image.width();
  const int h = image.height();
  int count = 0;
  for (int r = 0; r < length; ++r) {
    double sum = 0.0;
    bool inside = true;
    for (int j = -1; j <= 1 && inside; ++j) {
      const Vec2 q = centre_px + static_cast<double>(r) * along + static_cast<double>(j) * across;
      const int x = static_cast<int>(std::floor(q.x()));
      const int y = static_cast<int>(std::floor(q.y()));
      inside = x >= 0 && y >= 0 && x < w && y < h;
      if (inside) sum += brightness(image, x, y);
    }
    if (!inside) break;
    p[static_cast<std::size_t>(r)] = sum / 3.0;
    count = r + 1;
  }
  return count;
}

/// 1-sigma of one profile sample, from the median absolute difference of neighbours: a ramp or an edge
/// moves few of them, the noise all. `work` is scratch.
double profileNoise(const Profile& p, int count, Profile& work) {
  const int n = count - 1;
  for (std::size_t r = 0; r < static_cast<std::size_t>(n); ++r) work[r] = std::fabs(p[r + 1] - p[r]);
  auto* middle = work.begin() + n / 2;
  std::nth_element(work.begin(), middle, work.begin() + n);
  return *middle / (0.6745 * std::sqrt(2.0));
}

}  // namespace

OutlineSharpness measureOutlineSharpness(const MonoImage& image, const Vec2& centre_px, double radius_px) {
  OutlineSharpness out;
  if (image.empty() || !(radius_px >= S::kMinRadiusPx) || !centre_px.allFinite()) return out;
  // The fine scale follows the cluster's size: a body's outline is a step at any size, a blob's ramp is
  // as wide as the blob, so the fine step stays a quarter of the coarse one there.
  const int h = std::max(S::kMinScalePx, static_cast<int>(radius_px / S::kRadiusPerScale));
  const int coarse_half = S::kCoarseScales * h;
  // Out to half a radius beyond the cluster (a blob's cluster stops inside its ramp) and a coarse baseline.
  const int length = std::min(S::kMaxRayPx, static_cast<int>(1.5 * radius_px) + coarse_half + h + 1);
  // The outline is looked for beyond a third of the radius: the body's inner edges (faces, panels) lie
  // inside, and a ramp's steepest part lies near the cluster's edge.
  const int first = std::max(coarse_half + h, static_cast<int>(radius_px / 3.0));
  Profile p{};
  Profile sum{};  // prefix sums of p: sum[r] = p[0] + ... + p[r - 1]
  Profile work{};
  double fine_sum = 0.0;
  double coarse_sum = 0.0;
  constexpr double kTwoPi = 6.283185307179586;
  for (int k = 0; k < S::kRays; ++k) {
    const double angle = kTwoPi * (k + 0.5) / S::kRays;
    const Vec2 along(std::cos(angle), std::sin(angle));
    const int count = sampleRay(image, centre_px, along, length, p);
    // The outline must be inside the sampled part, with the coarse baseline on both sides of it.
    const int last = count - coarse_half - h - 1;
    if (last <= first || count < static_cast<int>(radius_px) + coarse_half + h + 1) continue;
    sum[0] = 0.0;
    for (std::size_t r = 0; r < static_cast<std::size_t>(count); ++r) sum[r + 1] = sum[r] + p[r];
    // q(r): the mean of p over [r - h, r + h].
    const auto q = [&](int r) {
      const int end = r + h + 1;
      const int begin = r - h;
      return (sum[static_cast<std::size_t>(end)] - sum[static_cast<std::size_t>(begin)]) / (2 * h + 1);
    };
    // Located by the step between the fine and the coarse scale, so that the fine step is not the one
    // the location was picked on (on noise, that pick alone makes a step).
    int best = -1;
    double best_step = 0.0;
    for (int r = first; r <= last; ++r) {
      const double step = std::fabs(q(r + 2 * h) - q(r - 2 * h));
      if (step > best_step) {
        best_step = step;
        best = r;
      }
    }
    if (best < 0) continue;
    const double coarse = q(best + coarse_half) - q(best - coarse_half);
    // A ray without a step well above its noise has no outline to measure.
    const double q_noise = profileNoise(p, count, work) / std::sqrt(2.0 * h + 1.0);
    if (std::fabs(coarse) < S::kMinStepNoise * q_noise) continue;
    const double fine = q(best + h) - q(best - h);
    fine_sum += (coarse >= 0.0 ? 1.0 : -1.0) * fine;
    coarse_sum += std::fabs(coarse);
    ++out.rays;
  }
  // Half the rays: a cluster cut by the image border is measured on the side that is in the image.
  if (out.rays < S::kRays / 2 || !(coarse_sum > 0.0)) return out;
  out.measured = true;
  out.ratio = fine_sum / coarse_sum;
  return out;
}

}  // namespace visnav::far
