#include "visnav/farrange/edge_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace visnav::far {

void EdgeFilter::init(int max_width, int max_height, const EdgeFilterSettings& settings) {
  m_settings = settings;
  m_stride = max_width;
  m_magnitude.reserve(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height));
  m_x_histogram.reserve(kPercentileBins);
  m_rows16.reserve(2U * static_cast<std::size_t>(max_width));
  m_rows32.reserve(2U * static_cast<std::size_t>(max_width));
}

namespace {

// One row of X = |Jx| + |Jy| for 3x3 kernels with centre weight kCentre (Sobel 2, Prewitt 1), separably:
// first the vertical smoothing and difference of the three rows over image columns [x_begin - 1, x_end + 1),
// then the horizontal difference / smoothing of those over [x_begin, x_end). Straight loops, no branch:
// the compiler vectorises them. Returns the row maximum.
template <int kCentre, typename PixelT, typename AccT>
AccT gradientRow(const PixelT* __restrict up, const PixelT* __restrict mid, const PixelT* __restrict down,
                 int x_begin, int x_end, int shift, AccT* __restrict smooth, AccT* __restrict diff,
                 std::uint16_t* __restrict out) {
  const int n = x_end - x_begin + 2;
  const PixelT* u = up + x_begin - 1;
  const PixelT* m = mid + x_begin - 1;
  const PixelT* d = down + x_begin - 1;
  for (int i = 0; i < n; ++i) {
    smooth[i] = static_cast<AccT>(u[i] + kCentre * m[i] + d[i]);  // column smoothing, for Jx
    diff[i] = static_cast<AccT>(d[i] - u[i]);                     // column difference, for Jy
  }
  AccT row_max = 0;
  const int width = x_end - x_begin;
  for (int i = 0; i < width; ++i) {
    const AccT gx = static_cast<AccT>(smooth[i + 2] - smooth[i]);
    const AccT gy = static_cast<AccT>(diff[i] + kCentre * diff[i + 1] + diff[i + 2]);
    const AccT ax = gx < 0 ? static_cast<AccT>(-gx) : gx;
    const AccT ay = gy < 0 ? static_cast<AccT>(-gy) : gy;
    const AccT magnitude = static_cast<AccT>((ax + ay) >> shift);
    out[i] = static_cast<std::uint16_t>(magnitude);
    row_max = magnitude > row_max ? magnitude : row_max;
  }
  return row_max;
}

template <int kCentre, typename PixelT, typename AccT>
int magnitudeRows(const ImageView<PixelT>& view, const Roi& roi, int shift, AccT* scratch, int scratch_stride,
                  std::uint16_t* x_out, int stride) {
  const int w = view.width();
  const int h = view.height();
  // The outermost image rows and columns have no full 3x3 neighbourhood: X = 0 there.
  const int x_begin = std::max(roi.x0, 1);
  const int x_end = std::min(roi.x0 + roi.width, w - 1);
  int frame_max = 0;
  for (int y = roi.y0; y < roi.y0 + roi.height; ++y) {
    std::uint16_t* out = x_out + static_cast<std::ptrdiff_t>(y - roi.y0) * stride;
    if (y == 0 || y == h - 1 || x_begin >= x_end) {
      std::memset(out, 0, static_cast<std::size_t>(roi.width) * sizeof(std::uint16_t));
      continue;
    }
    if (x_begin > roi.x0) out[0] = 0;
    if (x_end < roi.x0 + roi.width) out[roi.width - 1] = 0;
    const AccT row_max = gradientRow<kCentre, PixelT, AccT>(
        view.row(y - 1), view.row(y), view.row(y + 1), x_begin, x_end, shift, scratch,
        scratch + scratch_stride, out + (x_begin - roi.x0));
    frame_max = std::max(frame_max, static_cast<int>(row_max));
  }
  return frame_max;
}

// F = min(X, ref) / ref in 8-bit fixed point as the high half of a 16 x 16 bit product (pmulhuw on SSE2,
// umull on NEON): min(X, ref) << kShift fills 16 bits (X <= 2040 for 8-bit input, kShift 5; X <= 32760 for
// 16-bit input, kShift 1) and k = ceil(255 * 2^16 / (ref << kShift)), so F(ref) is exactly 255, never 256.
template <int kShift>
void normaliseRow(const std::uint16_t* __restrict x_row, int width, std::uint16_t ref, std::uint16_t k,
                  std::uint8_t* __restrict f_row) {
  for (int x = 0; x < width; ++x) {
    const std::uint16_t m = x_row[x] < ref ? x_row[x] : ref;
    const auto v = static_cast<std::uint16_t>(m << kShift);
    const auto high = static_cast<std::uint16_t>((static_cast<std::uint32_t>(v) * k) >> 16U);
    f_row[x] = static_cast<std::uint8_t>(high);
  }
}

int bitLength(std::uint32_t v) {
  int bits = 0;
  while (v != 0U && bits < 32) {
    v >>= 1U;
    ++bits;
  }
  return bits;
}

}  // namespace

int EdgeFilter::magnitudes8(const ImageView8& view, const Roi& roi) {
  // 8-bit input: |Jx| + |Jy| <= 2 * 4 * 255 fits 16-bit lanes.
  std::int16_t* scratch = m_rows16.data();
  return m_settings.kernel == EdgeKernel::kSobel
             ? magnitudeRows<2>(view, roi, 0, scratch, m_stride, m_magnitude.data(), m_stride)
             : magnitudeRows<1>(view, roi, 0, scratch, m_stride, m_magnitude.data(), m_stride);
}

int EdgeFilter::magnitudes16(const ImageView16& view, const Roi& roi, int shift) {
  std::int32_t* scratch = m_rows32.data();
  return m_settings.kernel == EdgeKernel::kSobel
             ? magnitudeRows<2>(view, roi, shift, scratch, m_stride, m_magnitude.data(), m_stride)
             : magnitudeRows<1>(view, roi, shift, scratch, m_stride, m_magnitude.data(), m_stride);
}

int EdgeFilter::percentileReference(const Roi& roi, int max_x, int max_possible) {
  // Histogram of X over every fourth pixel of every fourth row (1/16 of the cost; a percentile of the
  // background's noise needs no more).
  int bin_shift = 0;
  while ((max_possible >> bin_shift) >= kPercentileBins) ++bin_shift;
  std::uint32_t* hist = m_x_histogram.data();
  std::fill(hist, hist + kPercentileBins, 0U);
  std::uint32_t samples = 0;
  for (int y = 0; y < roi.height; y += 4) {
    const std::uint16_t* row = m_magnitude.data() + static_cast<std::ptrdiff_t>(y) * m_stride;
    for (int x = 0; x < roi.width; x += 4) ++hist[row[x] >> bin_shift];
    samples += static_cast<std::uint32_t>((roi.width + 3) / 4);
  }
  const auto wanted = static_cast<std::uint32_t>(std::ceil(m_settings.percentile / 100.0 * samples));
  std::uint32_t cumulative = 0;
  for (int b = 0; b < kPercentileBins; ++b) {
    cumulative += hist[b];
    if (cumulative >= wanted) return std::min(max_x, ((b + 1) << bin_shift) - 1);
  }
  return max_x;
}

void EdgeFilter::apply(const MonoImage& image, const Roi& roi, ResponseImage& out) {
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  // 16-bit samples are shifted so X stays below 2^15 (12-bit sensors keep every bit).
  const int shift = eight_bit ? 0 : std::max(0, bitLength(image.max_code) - 12);
  const int max_x = eight_bit ? magnitudes8(image.u8, roi) : magnitudes16(image.u16, roi, shift);
  const int max_possible = 2 * gain() * (static_cast<int>(image.max_code) >> shift);
  int reference = std::max(1, max_x);
  if (m_settings.percentile < 100.0) {
    reference = static_cast<int>(
        std::lround(m_settings.percentile_factor * percentileReference(roi, max_x, max_possible)));
  }
  const int floor_x = static_cast<int>(
      std::lround(m_settings.ref_floor * gain() * static_cast<double>(image.max_code >> shift)));
  // k below must fit 16 bits: ref << product_shift >= 256, so the divisor is at least 8 (2 grey levels of a
  // Sobel step); a flatter frame has no edge worth normalising.
  const int product_shift = eight_bit ? 5 : 1;
  reference = std::max({reference, floor_x, 256 >> product_shift});
  m_last_reference = reference;
  m_last_maximum = max_x;
  const auto k = static_cast<std::uint16_t>(std::ceil(255.0 * 65536.0 / (reference << product_shift)));
  const auto ref = static_cast<std::uint16_t>(reference);
  for (int y = 0; y < roi.height; ++y) {
    const std::uint16_t* x_row = m_magnitude.data() + static_cast<std::ptrdiff_t>(y) * m_stride;
    if (eight_bit) {
      normaliseRow<5>(x_row, roi.width, ref, k, out.row(y));
    } else {
      normaliseRow<1>(x_row, roi.width, ref, k, out.row(y));
    }
  }
}

}  // namespace visnav::far
