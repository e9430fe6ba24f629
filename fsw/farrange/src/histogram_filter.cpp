#include "visnav/farrange/histogram_filter.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::far {

void HistogramFilter::init(double beta) {
  m_beta = beta;
  m_bin16.reserve(65536);
  m_bin16_max_code = 0;
}

int HistogramFilter::binOf(std::uint32_t value, std::uint32_t max_code) {
  // Eq. 11: floor(J * (N - 1)) with J = value / max_code; samples above max_code land in the top bin.
  const std::uint32_t v = std::min(value, max_code);
  return static_cast<int>((v * 255U) / max_code);
}

void HistogramFilter::buildBins16(std::uint16_t max_code) {
  if (m_bin16_max_code == max_code) return;
  for (std::uint32_t v = 0; v < 65536U; ++v) m_bin16[v] = static_cast<std::uint8_t>(binOf(v, max_code));
  m_bin16_max_code = max_code;
}

void HistogramFilter::countBins8(const ImageView8& view, const Roi& roi) {
  // Four interleaved partial histograms: neighbouring background samples often share a grey level, and
  // incrementing the same counter again before its last store has retired stalls.
  std::uint32_t part[4][256] = {};
  const int width = roi.width;
  for (int y = roi.y0; y < roi.y0 + roi.height; ++y) {
    const std::uint8_t* row = view.row(y) + roi.x0;
    int x = 0;
    for (; x + 4 <= width; x += 4) {
      ++part[0][row[x]];
      ++part[1][row[x + 1]];
      ++part[2][row[x + 2]];
      ++part[3][row[x + 3]];
    }
    for (; x < width; ++x) ++part[0][row[x]];
  }
  for (int b = 0; b < 256; ++b) m_histogram[b] = part[0][b] + part[1][b] + part[2][b] + part[3][b];
}

void HistogramFilter::countBins16(const ImageView16& view, const Roi& roi) {
  m_histogram.fill(0U);
  for (int y = roi.y0; y < roi.y0 + roi.height; ++y) {
    const std::uint16_t* row = view.row(y) + roi.x0;
    for (int x = 0; x < roi.width; ++x) ++m_histogram[m_bin16[row[x]]];
  }
}

void HistogramFilter::countOutside(const MonoImage& image, const Roi& roi) {
  constexpr int kRowStep = 4;
  constexpr int kColumnStep = 4;
  constexpr std::uint32_t kWeight = kRowStep * kColumnStep;
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  const int w = image.width();
  const int x1 = roi.x0 + roi.width;
  for (int y = 0; y < image.height(); y += kRowStep) {
    const bool beside = y >= roi.y0 && y < roi.y0 + roi.height;  // this row crosses the region
    for (int x = 0; x < w; x += kColumnStep) {
      if (beside && x >= roi.x0 && x < x1) {
        x = x1 - 1 - (x1 - 1) % kColumnStep;  // jump to the last grid column inside the region
        continue;
      }
      const int bin = eight_bit ? image.u8.row(y)[x] : m_bin16[image.u16.row(y)[x]];
      m_histogram[static_cast<std::size_t>(bin)] += kWeight;
    }
  }
}

void HistogramFilter::apply(const MonoImage& image, const Roi& roi, ResponseImage& out) {
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  if (eight_bit) {
    countBins8(image.u8, roi);
  } else {
    buildBins16(image.max_code);
    countBins16(image.u16, roi);
  }
  if (m_count_outside) countOutside(image, roi);
  // Eq. 12 once per bin: 256 exps per frame.
  const double peak = std::max(1U, *std::max_element(m_histogram.begin(), m_histogram.end()));
  for (int b = 0; b < 256; ++b) {
    const double g = std::exp(-static_cast<double>(m_histogram[b]) / peak * m_beta);
    m_table[b] = static_cast<std::uint8_t>(std::lround(255.0 * g));
  }
  const std::uint8_t* table = m_table.data();
  const int width = roi.width;
  for (int y = 0; y < roi.height; ++y) {
    std::uint8_t* __restrict g_row = out.row(y);
    if (eight_bit) {
      // 8-bit samples are their own bin (max code 255).
      const std::uint8_t* __restrict row = image.u8.row(roi.y0 + y) + roi.x0;
      int x = 0;
      for (; x + 4 <= width; x += 4) {  // a gather: no SIMD on SSE2/NEON, so at least no loop overhead
        g_row[x] = table[row[x]];
        g_row[x + 1] = table[row[x + 1]];
        g_row[x + 2] = table[row[x + 2]];
        g_row[x + 3] = table[row[x + 3]];
      }
      for (; x < width; ++x) g_row[x] = table[row[x]];
    } else {
      const std::uint16_t* __restrict row = image.u16.row(roi.y0 + y) + roi.x0;
      const std::uint8_t* bins = m_bin16.data();
      for (int x = 0; x < width; ++x) g_row[x] = table[bins[row[x]]];
    }
  }
}

}  // namespace visnav::far
