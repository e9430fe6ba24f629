// Cluster analysis of paper sec. III-B: a cluster is spawned at every response above t_in not yet in a
// cluster and grows over 8-connected responses above t_out. The growth is a breadth-first search whose queue
// is the cluster's own pixel list (fixed capacity, no recursion). Per cluster: size n, centre of mass,
// largest distance from it, circularity (eq. 15), bounding box and second-moment axis ratio; optionally the
// size and centre of the cluster with its holes filled.
#pragma once

#include <cstdint>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/types.hpp"
#include "visnav/farrange/outline_sharpness.hpp"
#include "visnav/farrange/response_filter.hpp"

namespace visnav::far {

struct Cluster {
  int first_pixel = 0;         ///< range in ClusterFinder::pixels()
  int pixel_count = 0;         ///< n of eq. 15 / 16
  Vec2 com_px = Vec2::Zero();  ///< centre of mass, raw pixels (pixel centres at +0.5, CONVENTIONS.md)
  double max_radius_px = 0.0;  ///< max_a |p_a - p_COM| of eq. 15
  double circularity = 0.0;    ///< eq. 15
  double axis_ratio = 1.0;     ///< sqrt of the second-moment eigenvalue ratio (1 = round, large = line);
                               ///< of the filled cluster once fillHoles() ran
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;  ///< bounding box, inclusive, image pixels
  int peak_response = 0;                           ///< largest S in the cluster (255 = 1.0)
  bool truncated = false;                          ///< growth stopped at the pixel capacity
  bool at_roi_border = false;  ///< touches the searched region's border (may continue outside)
  int filled_count = 0;        ///< n with enclosed holes filled (0 until fillHoles())
  Vec2 filled_com_px = Vec2::Zero();
  int boundary_count = 0;  ///< filled pixels with a 4-neighbour outside (0 until fillHoles())
  /// FarRangeEstimator::sharpnessOf's last result for this cluster as it stands (its centre and radius):
  /// selection and the fix's report read it once; fillHoles() and a hull's adoption clear it.
  mutable OutlineSharpness sharpness;
  mutable bool sharpness_known = false;

  /// Half of the bounding box's longer side [px].
  double halfExtentPx() const {
    const int w = x_max - x_min + 1;
    const int h = y_max - y_min + 1;
    return 0.5 * (w > h ? w : h);
  }
};

/// The convex hull of an outline's clusters (ClusterFinder::outlineHull).
struct OutlineHull {
  double area_px = 0.0;  ///< pixels inside the hull: polygon area over pixel centres + half its perimeter
  double perimeter_px = 0.0;      ///< of the polygon over pixel centres
  double coverage = 0.0;          ///< share of 1-px steps along the hull with a member pixel within reach
  double concentration = 0.0;     ///< share of the members' pixels within reach + 1 of the hull's boundary
  Vec2 centre_px = Vec2::Zero();  ///< the polygon's centroid (pixel centres at +0.5)
  double max_radius_px = 0.0;     ///< farthest hull vertex from it
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;  ///< bounding box of the members, inclusive
  int pixel_count = 0;                             ///< the members' pixels
};

class ClusterFinder {
 public:
  /// Init-time: label image and work buffers for an image of width x height.
  void init(int width, int height, int max_clusters, int max_pixels);

  /// Clusters of `response` over its ROI. `row_max` (one per ROI row) lets rows without a spawn pixel be
  /// skipped. Thresholds in response units (255 = 1.0): spawn where S > t_in_q, grow where S > t_out_q.
  /// Clusters of fewer than `min_keep_px` pixels are not kept (their pixels stay labelled, so they are not
  /// spawned again): on a noisy edge response the speckle would otherwise use up max_clusters before the
  /// scan reaches the target.
  void find(const ResponseImage& response, const std::uint8_t* row_max, std::uint8_t t_in_q,
            std::uint8_t t_out_q, int min_keep_px = 0);
  /// Fills the cluster's enclosed holes (exterior flood fill, 4-connected, of its padded bounding box) and
  /// sets filled_count / filled_com_px. Cost: twice the bounding-box area.
  void fillHoles(Cluster& cluster);
  static constexpr int kMaxReachPx = 4;
  /// The convex hull of clusters `members` (1 or 2 indices into clusters()), its coverage by their pixels
  /// within `reach_px` (0 .. kMaxReachPx) and, when that coverage reaches `min_coverage`, the share of their
  /// pixels within reach_px + 1 of its boundary. False for a degenerate hull (a line). Cost: the members'
  /// pixels, their bounding box twice, (2 reach + 1)^2 per pixel of the hull's perimeter, and the members'
  /// pixels times the hull's vertices.
  bool outlineHull(const int* members, int count, int reach_px, double min_coverage, OutlineHull& out);

  BoundedBuffer<Cluster>& clusters() { return m_clusters; }
  const BoundedBuffer<Cluster>& clusters() const { return m_clusters; }
  /// Pixels of all clusters of the last frame, packed as (y << 16) | x.
  const BoundedBuffer<std::uint32_t>& pixels() const { return m_pixels; }
  int seedsSkipped() const { return m_seeds_skipped; }  ///< spawn pixels left when max_clusters was reached
  bool pixelCapacityHit() const { return m_pixel_capacity_hit; }

 private:
  void grow(const ResponseImage& response, int seed_x, int seed_y, std::uint8_t t_out_q, int min_keep_px);
  void measure(Cluster& c, const Roi& roi) const;

  int m_width = 0;
  int m_height = 0;
  BoundedBuffer<std::uint16_t> m_label;  ///< cluster id + 1 per image pixel, 0 = none
  BoundedBuffer<Cluster> m_clusters;
  BoundedBuffer<std::uint32_t> m_pixels;      ///< all clusters' pixels (y << 16 | x); the growth queue
  BoundedBuffer<std::uint8_t> m_fill;         ///< padded bounding box for fillHoles
  BoundedBuffer<std::uint32_t> m_fill_stack;  ///< also the hull's input points
  BoundedBuffer<std::uint32_t> m_hull;        ///< hull vertices, (x << 16) | y
  BoundedBuffer<int> m_row_lo;                ///< per row of a hull's box: leftmost and rightmost member
  BoundedBuffer<int> m_row_hi;
  int m_seeds_skipped = 0;
  bool m_pixel_capacity_hit = false;
};

}  // namespace visnav::far
