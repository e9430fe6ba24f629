#include "visnav/farrange/gamma_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::far {
namespace {

double medianOf(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

}  // namespace

double gammaOf(const GammaSample& sample) {
  if (!(sample.distance_m > 0.0) || !(sample.cluster_pixels > 0.0)) return 0.0;
  return sample.distance_m * std::sqrt(sample.cluster_pixels);  // eq. 16 solved for gamma
}

GammaEstimate calibrateGamma(const std::vector<GammaSample>& samples) {
  GammaEstimate e;
  std::vector<double> values;
  for (const GammaSample& s : samples) {
    const double g = gammaOf(s);
    if (g > 0.0 && std::isfinite(g)) values.push_back(g);
  }
  e.samples = static_cast<int>(values.size());
  if (values.empty()) return e;
  e.median = medianOf(values);
  std::vector<double> deviations;
  deviations.reserve(values.size());
  for (const double g : values) deviations.push_back(std::abs(g - e.median));
  const double mad = 1.4826 * medianOf(deviations);
  e.spread = mad / e.median;
  double sum = 0.0;
  for (const double g : values) {
    if (std::abs(g - e.median) <= 3.0 * mad) {
      sum += g;
      ++e.inliers;
    }
  }
  e.gamma = e.inliers > 0 ? sum / e.inliers : e.median;
  e.ok = true;
  return e;
}

}  // namespace visnav::far
