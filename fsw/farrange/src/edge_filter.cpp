#include "visnav/farrange/edge_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <type_traits>

namespace visnav::far {

void EdgeFilter::init(int max_width, int max_height, const EdgeFilterSettings& settings) {
  m_settings = settings;
  m_stride = max_width;
  m_magnitude.reserve(static_cast<std::size_t>(max_width) * static_cast<std::size_t>(max_height));
  m_x_histogram.reserve(kPercentileBins);
}

namespace {

// One row of X = |Jx| + |Jy| for 3x3 kernels with centre weight kCentre (Sobel 2, Prewitt 1) over image
// columns [x_begin, x_end), all with both horizontal neighbours inside the image. Straight loop, no branch:
// the compiler vectorises it. Returns the row maximum.
template <int kCentre, typename PixelT, typename AccT>
AccT gradientRow(const PixelT* up, const PixelT* mid, const PixelT* down, int x_begin, int x_end, int shift,
                 std::uint16_t* out) {
  AccT row_max = 0;
  for (int x = x_begin; x < x_end; ++x) {
    const AccT left = static_cast<AccT>(up[x - 1] + kCentre * mid[x - 1] + down[x - 1]);
    const AccT right = static_cast<AccT>(up[x + 1] + kCentre * mid[x + 1] + down[x + 1]);
    const AccT top = static_cast<AccT>(up[x - 1] + kCentre * up[x] + up[x + 1]);
    const AccT bottom = static_cast<AccT>(down[x - 1] + kCentre * down[x] + down[x + 1]);
    const AccT gx = static_cast<AccT>(right - left);
    const AccT gy = static_cast<AccT>(bottom - top);
    const AccT ax = gx < 0 ? static_cast<AccT>(-gx) : gx;
    const AccT ay = gy < 0 ? static_cast<AccT>(-gy) : gy;
    const AccT magnitude = static_cast<AccT>((ax + ay) >> shift);
    out[x - x_begin] = static_cast<std::uint16_t>(magnitude);
    row_max = magnitude > row_max ? magnitude : row_max;
  }
  return row_max;
}

template <int kCentre, typename PixelT>
int magnitudeRows(const ImageView<PixelT>& view, const Roi& roi, int shift, std::uint16_t* x_out,
                  int stride) {
  // 8-bit input: |Jx| + |Jy| <= 2 * 4 * 255 fits 16-bit lanes; 16-bit input needs 32-bit lanes.
  using AccT = std::conditional_t<sizeof(PixelT) == 1, std::int16_t, std::int32_t>;
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
    const AccT row_max = gradientRow<kCentre, PixelT, AccT>(view.row(y - 1), view.row(y), view.row(y + 1),
                                                            x_begin, x_end, shift, out + (x_begin - roi.x0));
    frame_max = std::max(frame_max, static_cast<int>(row_max));
  }
  return frame_max;
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

template <typename PixelT>
int EdgeFilter::magnitudes(const ImageView<PixelT>& view, const Roi& roi, int shift) {
  return m_settings.kernel == EdgeKernel::kSobel
             ? magnitudeRows<2>(view, roi, shift, m_magnitude.data(), m_stride)
             : magnitudeRows<1>(view, roi, shift, m_magnitude.data(), m_stride);
}

int EdgeFilter::percentileReference(const Roi& roi, int max_x, int max_possible) {
  // Percentile from every second pixel of every second row: 1/4 of the cost, the same statistics.
  int bin_shift = 0;
  while ((max_possible >> bin_shift) >= kPercentileBins) ++bin_shift;
  std::uint32_t* hist = m_x_histogram.data();
  std::fill(hist, hist + kPercentileBins, 0U);
  std::uint32_t samples = 0;
  for (int y = 0; y < roi.height; y += 2) {
    const std::uint16_t* row = m_magnitude.data() + static_cast<std::ptrdiff_t>(y) * m_stride;
    for (int x = 0; x < roi.width; x += 2) ++hist[row[x] >> bin_shift];
    samples += static_cast<std::uint32_t>((roi.width + 1) / 2);
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
  const int max_x = eight_bit ? magnitudes(image.u8, roi, 0) : magnitudes(image.u16, roi, shift);
  const int max_possible = 2 * gain() * (static_cast<int>(image.max_code) >> shift);
  int reference = std::max(1, max_x);
  if (m_settings.percentile < 100.0) reference = percentileReference(roi, max_x, max_possible);
  const int floor_x = static_cast<int>(
      std::lround(m_settings.ref_floor * gain() * static_cast<double>(image.max_code >> shift)));
  reference = std::max({reference, floor_x, 1});
  m_last_reference = reference;
  m_last_maximum = max_x;

  // F = min(X, ref) / ref in 8-bit fixed point: min(X, ref) * k <= 255 * 2^16, no overflow in 32 bits.
  const auto ref = static_cast<std::uint32_t>(reference);
  const auto k = static_cast<std::uint32_t>(std::lround(255.0 * 65536.0 / reference));
  for (int y = 0; y < roi.height; ++y) {
    const std::uint16_t* x_row = m_magnitude.data() + static_cast<std::ptrdiff_t>(y) * m_stride;
    std::uint8_t* f_row = out.row(y);
    for (int x = 0; x < roi.width; ++x) {
      const std::uint32_t v = x_row[x] < ref ? x_row[x] : ref;
      f_row[x] = static_cast<std::uint8_t>((v * k + 32768U) >> 16U);
    }
  }
}

}  // namespace visnav::far
