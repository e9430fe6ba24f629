// The silhouette of a dim extended target around a far-range fix (ours, not the paper's). Eq. 13's response
// and the outline search find the parts of a dim, noisy target whose edges or grey levels stand out: a bright
// face of a plate seen edge-on, a satellite's body without its panels. Such a fragment's extent puts the
// target 1.5-9x too far (campaign cao/5029: 51 m at 12.9 m, never handed over). Averaged over blocks
// of pixels the noise falls with the block's side, and the whole silhouette stands apart from a background
// fitted to the window's border: the window's brightness less that plane, thresholded in the noise of the
// border's block means, grown from the fix, is the silhouette; its extent is the one f R / extent needs.
#pragma once

#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/image_view.hpp"
#include "visnav/core/types.hpp"

namespace visnav::far {

/// What measure() found: the connected region of blocks set apart from the background that holds the fix.
struct SilhouetteMeasure {
  bool found = false;           ///< a region holding the fix and clear of the window's border
  bool touches_window = false;  ///< the region reached the window's border ring (leak, or window too small)
  bool cut_by_image = false;    ///< ... where the image border clipped the window: a larger one cannot help
  Vec2 centroid_px = Vec2::Zero();  ///< centre of its blocks, raw pixels
  double extent_px = 0.0;           ///< largest distance of a block's centre from centroid_px
  int blocks = 0;                   ///< blocks in the region
  int block_px = 0;                 ///< side of a block
  double noise = 0.0;               ///< 1-sigma of a block's mean about the plane, [0, 1] brightness
  /// The region's median departure over the strongest about the fix: under 2 level_ratio it is not found
  double median_level_ratio = 0.0;
};

class SilhouetteExtent {
 public:
  /// Blocks per window side at most: bounds memory (kMaxSide^2 means) and the flood fill.
  static constexpr int kMaxSide = 64;

  /// Init-time: allocates the window's buffers.
  void init();

  /// The region of blocks of at least `min_block_px` (more for a window wider than kMaxSide blocks) in the
  /// square of half side `half_px` about `centre_px` whose mean departs from the plane fitted to the
  /// window's border ring by more than `k_sigma` times the ring's robust spread (either polarity), grown
  /// 8-connected from the departing block nearest `centre_px` within `seed_radius_px` over the blocks that
  /// also depart by `level_ratio` of the strongest departure within `seed_radius_px` (0: any departing
  /// block); a region whose median departure is under twice that share of the strongest is not found. The
  /// window is clipped to the image; a region on a clipped side is cut by the image border and is not found.
  SilhouetteMeasure measure(const MonoImage& image, const Vec2& centre_px, double half_px,
                            double seed_radius_px, int min_block_px, double k_sigma,
                            double level_ratio = 0.0);

 private:
  BoundedBuffer<float> m_means;        ///< block means, row-major
  BoundedBuffer<float> m_work;         ///< ring residuals for the median
  BoundedBuffer<std::uint8_t> m_mask;  ///< 0: background, 1: departs, 2: in the region
  BoundedBuffer<std::int32_t> m_stack;
};

}  // namespace visnav::far
