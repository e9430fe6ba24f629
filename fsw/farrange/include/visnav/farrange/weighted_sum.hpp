// Eq. 13: S = sum_i lambda_i * F_i with sum_i lambda_i = 1 (eq. 14), in fixed point: integer weights in
// 1/256 that add up to exactly 256, so S stays in [0, 255] without a clamp.
#pragma once

#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/status.hpp"
#include "visnav/farrange/response_filter.hpp"

namespace visnav::far {

class WeightedSum {
 public:
  static constexpr int kMaxInputs = 8;

  /// Init-time: row accumulator for images up to max_width wide.
  void init(int max_width);
  /// Rejects weights outside [0, 1] or not summing to 1 within 1e-9 (eq. 14), with a message.
  LoadError setWeights(const double* lambdas, int count);
  const int* weightsQ8() const { return m_weights_q8; }

  /// S over the ROI of `out` (all inputs cover the same ROI); row_max[y] receives each row's maximum.
  void apply(const ResponseImage* const* inputs, ResponseImage& out, std::uint8_t* row_max);

 private:
  BoundedBuffer<std::uint16_t> m_accumulator;
  int m_weights_q8[kMaxInputs] = {};
  int m_count = 0;
};

}  // namespace visnav::far
