// Histogram filter of paper sec. III-B: a 256-bin integer histogram of the ROI (eq. 11) and the rarity
// response G = exp(-h(bin) / max(h) * beta) (eq. 12), evaluated once per bin into a 256-entry lookup table
// per frame, then one table lookup per pixel (no exp per pixel). Eq. 11's 1 / (N #J) cancels in h / max(h),
// so raw counts are used. 16-bit images are binned to 256 as eq. 11 writes it: floor(v / max_code * 255).
#pragma once

#include <array>
#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/farrange/response_filter.hpp"

namespace visnav::far {

class HistogramFilter final : public ResponseFilter {
 public:
  /// Init-time: allocates the 16-bit binning table.
  void init(double beta);
  /// Eq. 11 is over the whole image. When on and a region of interest is searched, the pixels outside it
  /// are still counted, on a sparse grid (every 4th row and column, weight 16), so G inside the region
  /// is the full frame's G (a smaller population would make the target's bins look less rare).
  void setCountOutsideRoi(bool on) { m_count_outside = on; }
  /// Init-time (allocates): when block_px > 0, eq. 11 bins each sample's deviation from the frame's smooth
  /// background instead of the sample: 128 + bin - background, clamped to 0..255. The background is the
  /// median bin of block_px x block_px blocks (from every 4th row and column), bilinear between block
  /// centres. A target whose grey levels lie inside a gradient's or a limb's spread is then rare against the
  /// flat residual where it was common against the frame. 0: eq. 11 as printed.
  void setBackgroundBlock(int block_px, int width, int height);
  /// Whether apply() flattens (default: whenever setBackgroundBlock gave a block size).
  void setFlattening(bool on) { m_flatten = on; }
  const char* name() const override { return "histogram"; }
  void apply(const MonoImage& image, const Roi& roi, ResponseImage& out) override;

  /// Last frame's histogram (counts per bin) and response table (255 = 1.0).
  const std::array<std::uint32_t, 256>& histogram() const { return m_histogram; }
  const std::array<std::uint8_t, 256>& responseTable() const { return m_table; }
  /// Eq. 11's bin of a sample of an image with the given max code.
  static int binOf(std::uint32_t value, std::uint32_t max_code);

 private:
  void buildBins16(std::uint16_t max_code);
  void countBins8(const ImageView8& view, const Roi& roi);
  void countOutside(const MonoImage& image, const Roi& roi);
  void countBins16(const ImageView16& view, const Roi& roi);
  void measureBackground(const MonoImage& image);
  /// The background bin (x 65536) along row y, at every column of [x0, x0 + width), into m_background_row.
  void backgroundRow(int y, int x0, int width);
  void flattenRow(const MonoImage& image, int y, int x0, int width, std::uint8_t* out) const;
  void buildTable();
  void countOutsideFlattened(const MonoImage& image, const Roi& roi);
  void applyFlattened(const MonoImage& image, const Roi& roi, ResponseImage& out);

  double m_beta = 100.0;
  bool m_count_outside = false;
  std::array<std::uint32_t, 256> m_histogram{};
  std::array<std::uint8_t, 256> m_table{};
  BoundedBuffer<std::uint8_t> m_bin16;  ///< 16-bit sample -> bin, for m_bin16_max_code
  std::uint32_t m_bin16_max_code = 0;
  // Background flattening (setBackgroundBlock).
  int m_block_px = 0;
  bool m_flatten = true;
  int m_blocks_x = 0;
  int m_blocks_y = 0;
  BoundedBuffer<std::int32_t> m_block_median;    ///< median bin x 256 per block, row-major
  BoundedBuffer<std::int32_t> m_block_row;       ///< block medians interpolated to one image row, x 256
  BoundedBuffer<std::int32_t> m_background_row;  ///< background bin x 65536 per column of the current row
};

}  // namespace visnav::far
