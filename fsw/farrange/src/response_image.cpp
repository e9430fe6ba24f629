#include <algorithm>
#include <cmath>
#include <string>

#include "visnav/farrange/response_filter.hpp"
#include "visnav/farrange/weighted_sum.hpp"

namespace visnav::far {

Roi Roi::clipped(int w, int h) const {
  const int xa = std::max(x0, 0);
  const int ya = std::max(y0, 0);
  const int xb = std::min(x0 + width, w);
  const int yb = std::min(y0 + height, h);
  return {xa, ya, std::max(0, xb - xa), std::max(0, yb - ya)};
}

void ResponseImage::init(int max_width, int max_height) {
  m_stride = max_width;
  m_max_height = max_height;
  m_data.reserve(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height));
  m_roi = Roi::full(max_width, max_height);
}

bool ResponseImage::setRoi(const Roi& roi) {
  if (roi.empty() || roi.width > m_stride || roi.height > m_max_height) return false;
  m_roi = roi;
  return true;
}

void WeightedSum::init(int max_width) { m_accumulator.reserve(static_cast<std::size_t>(max_width)); }

LoadError WeightedSum::setWeights(const double* lambdas, int count) {
  if (count < 1 || count > kMaxInputs) return LoadError::failure("far range: 1 to 8 filters can be combined");
  double sum = 0.0;
  for (int i = 0; i < count; ++i) {
    if (!(lambdas[i] >= 0.0 && lambdas[i] <= 1.0))
      return LoadError::failure("far range: filter weight " + std::to_string(i + 1) + " must be in [0, 1]");
    sum += lambdas[i];
  }
  if (std::abs(sum - 1.0) > 1e-9) {
    return LoadError::failure("far range: filter weights sum to " + std::to_string(sum) +
                              ", paper eq. 14 requires exactly 1");
  }
  // Rounded weights; the largest absorbs the rounding so that they add up to exactly 256.
  int total = 0;
  int largest = 0;
  for (int i = 0; i < count; ++i) {
    m_weights_q8[i] = static_cast<int>(std::lround(lambdas[i] * 256.0));
    total += m_weights_q8[i];
    if (m_weights_q8[i] > m_weights_q8[largest]) largest = i;
  }
  m_weights_q8[largest] += 256 - total;
  m_count = count;
  return LoadError::success();
}

namespace {

void accumulateRow(const std::uint8_t* __restrict in, int width, std::uint16_t weight,
                   std::uint16_t* __restrict acc) {
  for (int x = 0; x < width; ++x) acc[x] = static_cast<std::uint16_t>(acc[x] + weight * in[x]);
}

// S = acc / 256 (truncated: never lifts a response onto a threshold it does not exceed, e.g. 0.5 * 1 + 0.5 *
// 0 must not pass t_out = 0.5); returns the row maximum.
std::uint8_t finishRow(const std::uint16_t* __restrict acc, int width, std::uint8_t* __restrict s) {
  std::uint8_t peak = 0;
  for (int x = 0; x < width; ++x) {
    const auto v = static_cast<std::uint8_t>(acc[x] >> 8U);
    s[x] = v;
    peak = v > peak ? v : peak;
  }
  return peak;
}

// The usual two filters in one pass: S = (w0 F0 + w1 F1) / 256, 16-bit lanes.
std::uint8_t combineTwoRow(const std::uint8_t* __restrict f0, const std::uint8_t* __restrict f1, int width,
                           std::uint16_t w0, std::uint16_t w1, std::uint8_t* __restrict s) {
  std::uint8_t peak = 0;
  for (int x = 0; x < width; ++x) {
    const auto v = static_cast<std::uint8_t>(static_cast<std::uint16_t>(w0 * f0[x] + w1 * f1[x]) >> 8U);
    s[x] = v;
    peak = v > peak ? v : peak;
  }
  return peak;
}

}  // namespace

void WeightedSum::apply(const ResponseImage* const* inputs, ResponseImage& out, std::uint8_t* row_max) {
  const int width = out.roi().width;
  const int height = out.roi().height;
  if (m_count == 2) {
    const auto w0 = static_cast<std::uint16_t>(m_weights_q8[0]);
    const auto w1 = static_cast<std::uint16_t>(m_weights_q8[1]);
    for (int y = 0; y < height; ++y) {
      row_max[y] = combineTwoRow(inputs[0]->row(y), inputs[1]->row(y), width, w0, w1, out.row(y));
    }
    return;
  }
  std::uint16_t* acc = m_accumulator.data();
  for (int y = 0; y < height; ++y) {
    std::fill(acc, acc + width, static_cast<std::uint16_t>(0));
    for (int i = 0; i < m_count; ++i) {
      accumulateRow(inputs[i]->row(y), width, static_cast<std::uint16_t>(m_weights_q8[i]), acc);
    }
    row_max[y] = finishRow(acc, width, out.row(y));
  }
}

}  // namespace visnav::far
