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

void HistogramFilter::setBackgroundBlock(int block_px, int width, int height) {
  m_block_px = block_px > 0 && width > 0 && height > 0 ? block_px : 0;
  if (m_block_px == 0) return;
  m_blocks_x = (width + m_block_px - 1) / m_block_px;
  m_blocks_y = (height + m_block_px - 1) / m_block_px;
  m_block_mean.reserve(static_cast<std::size_t>(m_blocks_x) * static_cast<std::size_t>(m_blocks_y));
  m_block_row.reserve(static_cast<std::size_t>(m_blocks_x));
  m_background_row.reserve(static_cast<std::size_t>(width));
  m_flat_row.reserve(static_cast<std::size_t>(width));
}

int HistogramFilter::sampleBin(const MonoImage& image, int x, int y) const {
  return image.depth == MonoImage::Depth::kU8 ? image.u8.row(y)[x] : m_bin16[image.u16.row(y)[x]];
}

void HistogramFilter::measureBackground(const MonoImage& image) {
  // Every 4th row and column of each block (a sixteenth of the frame): the background is smooth by
  // definition, and a small target moves a block's mean by its share of the block.
  constexpr int kStep = 4;
  const int w = image.width();
  const int h = image.height();
  for (int by = 0; by < m_blocks_y; ++by) {
    const int y1 = std::min(h, (by + 1) * m_block_px);
    for (int bx = 0; bx < m_blocks_x; ++bx) {
      const int x1 = std::min(w, (bx + 1) * m_block_px);
      std::int64_t sum = 0;
      std::int64_t count = 0;
      for (int y = by * m_block_px; y < y1; y += kStep) {
        for (int x = bx * m_block_px; x < x1; x += kStep) {
          sum += sampleBin(image, x, y);
          ++count;
        }
      }
      m_block_mean[static_cast<std::size_t>(by * m_blocks_x + bx)] =
          count > 0 ? static_cast<std::int32_t>((sum * 256 + count / 2) / count) : 128 * 256;
    }
  }
}

void HistogramFilter::backgroundRow(int y, int x0, int width) {
  // Bilinear between block centres (block index + 1/2), held flat beyond the outer centres. Integer, with
  // 8 fractional bits; the column position is stepped, not divided, per pixel.
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
  const std::int32_t* upper = m_block_mean.data() + static_cast<std::ptrdiff_t>(j0) * m_blocks_x;
  const std::int32_t* lower = m_block_mean.data() + static_cast<std::ptrdiff_t>(j1) * m_blocks_x;
  for (int i = 0; i < m_blocks_x; ++i)
    m_block_row[static_cast<std::size_t>(i)] = (upper[i] * (256 - wy) + lower[i] * wy) >> 8;
  const std::int32_t* row = m_block_row.data();
  int i0 = 0;
  int r = 0;  // x - half - i0 * block, in [0, block)
  const int d0 = x0 - half;
  if (d0 > 0) {
    i0 = d0 / m_block_px;
    r = d0 - i0 * m_block_px;
  }
  std::int32_t* out = m_background_row.data();
  for (int k = 0; k < width; ++k) {
    const int x = x0 + k;
    if (x <= half || i0 >= m_blocks_x - 1) {
      out[k] = row[std::min(i0, m_blocks_x - 1)];
    } else {
      const int wx = (r * 256) / m_block_px;
      out[k] = (row[i0] * (256 - wx) + row[i0 + 1] * wx) >> 8;
    }
    if (x >= half && ++r == m_block_px) {
      r = 0;
      ++i0;
    }
  }
}

void HistogramFilter::countFlattened(const MonoImage& image, const Roi& roi) {
  m_histogram.fill(0U);
  std::uint8_t* flat = m_flat_row.data();
  for (int y = roi.y0; y < roi.y0 + roi.height; ++y) {
    backgroundRow(y, roi.x0, roi.width);
    flattenRow(image, y, roi.x0, roi.width, flat);
    for (int k = 0; k < roi.width; ++k) ++m_histogram[flat[k]];
  }
}

void HistogramFilter::flattenRow(const MonoImage& image, int y, int x0, int width, std::uint8_t* out) const {
  const std::int32_t* background = m_background_row.data();
  for (int k = 0; k < width; ++k) {
    const int deviation = sampleBin(image, x0 + k, y) - ((background[k] + 128) >> 8);
    out[k] = static_cast<std::uint8_t>(std::clamp(128 + deviation, 0, 255));
  }
}

void HistogramFilter::countOutsideFlattened(const MonoImage& image, const Roi& roi) {
  // As countOutside, on the flattened bins.
  constexpr int kRowStep = 4;
  constexpr int kColumnStep = 4;
  constexpr std::uint32_t kWeight = kRowStep * kColumnStep;
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
      const int deviation = sampleBin(image, x, y) - ((background[x] + 128) >> 8);
      m_histogram[static_cast<std::size_t>(std::clamp(128 + deviation, 0, 255))] += kWeight;
    }
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
  if (m_block_px > 0) {
    if (!eight_bit) buildBins16(image.max_code);
    measureBackground(image);
    countFlattened(image, roi);
    if (m_count_outside) countOutsideFlattened(image, roi);
    buildTable();
    std::uint8_t* flat = m_flat_row.data();
    for (int y = 0; y < roi.height; ++y) {
      backgroundRow(roi.y0 + y, roi.x0, roi.width);
      flattenRow(image, roi.y0 + y, roi.x0, roi.width, flat);
      std::uint8_t* g_row = out.row(y);
      for (int x = 0; x < roi.width; ++x) g_row[x] = m_table[flat[x]];
    }
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
