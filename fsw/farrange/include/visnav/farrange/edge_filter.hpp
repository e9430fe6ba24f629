// Edge filter of paper sec. III-B: 3x3 integer gradient kernels, X = |J * Kx| + |J * Ky|, normalised to
// [0, 1] (eq. 10). Sobel is the default (fsw/farrange/README.md); eq. 9's kernels as printed are Prewitt-type
// and offered as a setting. Eq. 10 divides by max X; the robust method divides by a multiple of a percentile
// of X (the median by default: the noise level, the same in any region of interest; never below a floor)
// and clips at 1, so one bright non-target edge cannot push the target below t_in.
// Row loops are straight and branch-free inside, so -O2 vectorises them (SSE2 here, NEON on ARM).
#pragma once

#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/farrange/far_range_params.hpp"
#include "visnav/farrange/response_filter.hpp"

namespace visnav::far {

struct EdgeFilterSettings {
  EdgeKernel kernel = EdgeKernel::kSobel;
  double percentile = 100.0;       ///< 100: eq. 10 as published (single maximum)
  double percentile_factor = 1.0;  ///< divisor = factor * percentile (when percentile < 100)
  double ref_floor = 0.0;          ///< smallest divisor, as the response to a step of this contrast (0..1)
};

class EdgeFilter final : public ResponseFilter {
 public:
  /// Init-time: buffers for a max_width x max_height ROI.
  void init(int max_width, int max_height, const EdgeFilterSettings& settings);
  const char* name() const override { return "edge"; }
  void apply(const MonoImage& image, const Roi& roi, ResponseImage& out) override;

  /// Divisor of eq. 10 used on the last frame and the largest X seen (in X units of that frame).
  int lastReference() const { return m_last_reference; }
  int lastMaximum() const { return m_last_maximum; }
  /// Kernel gain: X across a step of contrast C codes is gain * C (Sobel 4, Prewitt 3).
  int gain() const { return m_settings.kernel == EdgeKernel::kSobel ? 4 : 3; }

 private:
  int magnitudes8(const ImageView8& view, const Roi& roi);
  int magnitudes16(const ImageView16& view, const Roi& roi, int shift);
  int percentileReference(const Roi& roi, int max_x, int max_possible);

  static constexpr int kPercentileBins = 1024;
  EdgeFilterSettings m_settings;
  BoundedBuffer<std::uint16_t> m_magnitude;  ///< X per ROI pixel, row stride = max width
  BoundedBuffer<std::uint32_t> m_x_histogram;
  BoundedBuffer<std::int16_t> m_rows16;  ///< column smoothing and difference of one row (8-bit input)
  BoundedBuffer<std::int32_t> m_rows32;  ///< the same for 16-bit input
  int m_stride = 0;
  int m_last_reference = 1;
  int m_last_maximum = 0;
};

}  // namespace visnav::far
