#include "visnav/farrange/histogram_filter.hpp"

#include <algorithm>
#include <array>
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

void HistogramFilter::setBackgroundBlock(int block_px, int width, int height) {
  m_block_px = block_px > 0 && width > 0 && height > 0 ? block_px : 0;
  if (m_block_px == 0) return;
  m_blocks_x = (width + m_block_px - 1) / m_block_px;
  m_blocks_y = (height + m_block_px - 1) / m_block_px;
  m_block_median.reserve(static_cast<std::size_t>(m_blocks_x) * static_cast<std::size_t>(m_blocks_y));
  m_block_row.reserve(static_cast<std::size_t>(m_blocks_x));
  m_background_row.reserve(static_cast<std::size_t>(width));
}

void HistogramFilter::measureBackground(const MonoImage& image) {
  // The median of each block's samples on every 4th row and column (a sixteenth of the frame). A target or
  // a glint covering less than half a block leaves the median at the background's level; a mean would
  // rise by the target's share and ring it with a halo of rare deviations, which grew a bright bar into a
  // round cluster and added a ring to a target's n (eq. 16).
  constexpr int kStep = 4;
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  const int w = image.width();
  const int h = image.height();
  std::array<std::uint32_t, 256> counts{};
  for (int by = 0; by < m_blocks_y; ++by) {
    const int y1 = std::min(h, (by + 1) * m_block_px);
    for (int bx = 0; bx < m_blocks_x; ++bx) {
      const int x1 = std::min(w, (bx + 1) * m_block_px);
      counts.fill(0U);
      std::uint32_t n = 0;
      for (int y = by * m_block_px; y < y1; y += kStep) {
        if (eight_bit) {
          const std::uint8_t* row = image.u8.row(y);
          for (int x = bx * m_block_px; x < x1; x += kStep) ++counts[row[x]];
        } else {
          const std::uint16_t* row = image.u16.row(y);
          for (int x = bx * m_block_px; x < x1; x += kStep) ++counts[m_bin16[row[x]]];
        }
        n += static_cast<std::uint32_t>((x1 - 1 - bx * m_block_px) / kStep + 1);
      }
      int median = 0;
      for (std::uint32_t below = 0; median < 255; ++median) {
        below += counts[static_cast<std::size_t>(median)];
        if (2U * below >= n) break;
      }
      const std::size_t block =
          static_cast<std::size_t>(by) * static_cast<std::size_t>(m_blocks_x) + static_cast<std::size_t>(bx);
      m_block_median[block] = median * 256;
    }
  }
}

void HistogramFilter::backgroundRow(int y, int x0, int width) {
  // Bilinear between block centres (block index + 1/2), held flat beyond the outer centres. Integer: the
  // block row in 8 fractional bits, the columns in 16, stepped along each span between two centres.
  const int half = m_block_px / 2;
  int j0 = 0;
  int wy = 0;  // weight of block row j0 + 1, of 256
  if (y > half) {
    j0 = (y - half) / m_block_px;
    wy = ((y - half - j0 * m_block_px) * 256) / m_block_px;
  }
  if (j0 >= m_blocks_y - 1) {
    j0 = m_blocks_y - 1;
    wy = 0;
  }
  const int j1 = std::min(j0 + 1, m_blocks_y - 1);
  const std::int32_t* upper = m_block_median.data() + static_cast<std::ptrdiff_t>(j0) * m_blocks_x;
  const std::int32_t* lower = m_block_median.data() + static_cast<std::ptrdiff_t>(j1) * m_blocks_x;
  std::int32_t* row = m_block_row.data();
  for (int i = 0; i < m_blocks_x; ++i) row[i] = (upper[i] * (256 - wy) + lower[i] * wy) >> 8;
  std::int32_t* out = m_background_row.data();
  const int last = m_blocks_x - 1;
  const int x_end = x0 + width;
  int x = x0;
  for (; x < std::min(x_end, half + 1); ++x) out[x - x0] = row[0] << 8;  // left of the first centre
  while (x < x_end) {
    const int i = (x - half) / m_block_px;
    if (i >= last) {
      for (; x < x_end; ++x) out[x - x0] = row[last] << 8;  // right of the last centre
      break;
    }
    const int span_start = half + i * m_block_px;
    const int span_end = std::min(x_end, span_start + m_block_px);
    const std::int32_t step = ((row[i + 1] - row[i]) * 256) / m_block_px;
    std::int32_t value = (row[i] << 8) + step * (x - span_start);
    for (; x < span_end; ++x, value += step) out[x - x0] = value;
  }
}

void HistogramFilter::flattenRow(const MonoImage& image, int y, int x0, int width, std::uint8_t* out) const {
  const std::int32_t* background = m_background_row.data();
  constexpr std::int32_t kRound = 1 << 15;
  if (image.depth == MonoImage::Depth::kU8) {
    const std::uint8_t* row = image.u8.row(y) + x0;
    for (int k = 0; k < width; ++k) {
      const int deviation = static_cast<int>(row[k]) - ((background[k] + kRound) >> 16);
      out[k] = static_cast<std::uint8_t>(std::clamp(128 + deviation, 0, 255));
    }
  } else {
    const std::uint16_t* row = image.u16.row(y) + x0;
    const std::uint8_t* bins = m_bin16.data();
    for (int k = 0; k < width; ++k) {
      const int deviation = static_cast<int>(bins[row[k]]) - ((background[k] + kRound) >> 16);
      out[k] = static_cast<std::uint8_t>(std::clamp(128 + deviation, 0, 255));
    }
  }
}

void HistogramFilter::countOutsideFlattened(const MonoImage& image, const Roi& roi) {
  // As countOutside, on the flattened bins.
  constexpr int kRowStep = 4;
  constexpr int kColumnStep = 4;
  constexpr std::uint32_t kWeight = kRowStep * kColumnStep;
  constexpr std::int32_t kRound = 1 << 15;
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  const int w = image.width();
  const int x1 = roi.x0 + roi.width;
  for (int y = 0; y < image.height(); y += kRowStep) {
    const bool beside = y >= roi.y0 && y < roi.y0 + roi.height;
    backgroundRow(y, 0, w);
    const std::int32_t* background = m_background_row.data();
    for (int x = 0; x < w; x += kColumnStep) {
      if (beside && x >= roi.x0 && x < x1) {
        x = x1 - 1 - (x1 - 1) % kColumnStep;
        continue;
      }
      const int bin = eight_bit ? image.u8.row(y)[x] : m_bin16[image.u16.row(y)[x]];
      const int deviation = bin - ((background[x] + kRound) >> 16);
      m_histogram[static_cast<std::size_t>(std::clamp(128 + deviation, 0, 255))] += kWeight;
    }
  }
}

void HistogramFilter::applyFlattened(const MonoImage& image, const Roi& roi, ResponseImage& out) {
  // The flattened bins go straight into the response rows, are counted there, and are replaced by their
  // eq. 12 response in place: no frame-sized buffer of their own.
  if (image.depth != MonoImage::Depth::kU8) buildBins16(image.max_code);
  measureBackground(image);
  m_histogram.fill(0U);
  for (int y = 0; y < roi.height; ++y) {
    backgroundRow(roi.y0 + y, roi.x0, roi.width);
    std::uint8_t* flat = out.row(y);
    flattenRow(image, roi.y0 + y, roi.x0, roi.width, flat);
    for (int x = 0; x < roi.width; ++x) ++m_histogram[flat[x]];
  }
  if (m_count_outside) countOutsideFlattened(image, roi);
  buildTable();
  const std::uint8_t* table = m_table.data();
  for (int y = 0; y < roi.height; ++y) {
    std::uint8_t* row = out.row(y);
    for (int x = 0; x < roi.width; ++x) row[x] = table[row[x]];
  }
}

void HistogramFilter::buildTable() {
  // Eq. 12 once per bin: 256 exps per frame.
  const double peak = std::max(1U, *std::max_element(m_histogram.begin(), m_histogram.end()));
  for (int b = 0; b < 256; ++b) {
    const double g = std::exp(-static_cast<double>(m_histogram[b]) / peak * m_beta);
    m_table[b] = static_cast<std::uint8_t>(std::lround(255.0 * g));
  }
}

void HistogramFilter::apply(const MonoImage& image, const Roi& roi, ResponseImage& out) {
  const bool eight_bit = image.depth == MonoImage::Depth::kU8;
  if (m_block_px > 0 && m_flatten) {
    applyFlattened(image, roi, out);
    return;
  }
  if (eight_bit) {
    countBins8(image.u8, roi);
  } else {
    buildBins16(image.max_code);
    countBins16(image.u16, roi);
  }
  if (m_count_outside) countOutside(image, roi);
  buildTable();
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
