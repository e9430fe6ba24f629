// The far-range direction/distance estimator (paper sec. III): low-level filters (edge, histogram), their
// weighted sum (eq. 13/14), cluster analysis (eq. 15), selection of the target cluster, direction through
// the camera model (distortion removed) and distance d = gamma / sqrt(n) (eq. 16), or f R / extent when the
// target's radius R is known and that is nearer (far_range_params.hpp, extent_distance_min_px). It needs no
// initialisation like a tracker; the robust method keeps a light track (last position, velocity, size) to
// gate the next selection and to restrict the search to a region of interest (sec. V).
// All memory is sized in init(); estimate() allocates nothing, throws nothing, and every loop is bounded by
// the image size or a capacity fixed at init.
#pragma once

#include <array>
#include <cstdint>

#include "visnav/core/image_view.hpp"
#include "visnav/core/status.hpp"
#include "visnav/core/types.hpp"
#include "visnav/farrange/cluster_finder.hpp"
#include "visnav/farrange/edge_filter.hpp"
#include "visnav/farrange/far_range_params.hpp"
#include "visnav/farrange/histogram_filter.hpp"
#include "visnav/farrange/outline_sharpness.hpp"
#include "visnav/farrange/silhouette_extent.hpp"
#include "visnav/farrange/weighted_sum.hpp"
#include "visnav/geometry/camera.hpp"

namespace visnav::far {

/// Why a frame has no target, or what is special about it (bit set; several may hold).
enum FarRangeFlag : std::uint32_t {
  kFlagNoCluster = 1U << 0,          ///< no response above t_in
  kFlagNoCandidate = 1U << 1,        ///< clusters exist, none accepted (size, shape, gate)
  kFlagClusterCapacity = 1U << 2,    ///< more spawn pixels than max_clusters
  kFlagPixelCapacity = 1U << 3,      ///< a cluster's growth stopped at max_cluster_pixels
  kFlagRoi = 1U << 4,                ///< searched a region of interest only
  kFlagRoiFallback = 1U << 5,        ///< the region yielded no target: the full frame was searched
  kFlagGated = 1U << 6,              ///< selected inside the gate of the prediction
  kFlagCoasting = 1U << 7,           ///< no target this frame, the track is kept (robust)
  kFlagAtBorder = 1U << 8,           ///< the target touches the image border: n is too small
  kFlagAmbiguous = 1U << 9,          ///< a second acceptable cluster came close in score
  kFlagUnconfirmed = 1U << 10,       ///< picked without a track (largest plausible cluster)
  kFlagExtended = 1U << 11,          ///< found by its outline on the edge response alone (extended target)
  kFlagExtentDistance = 1U << 12,    ///< distance_m from the cluster's extent and the target's radius
  kFlagRefutedSkipped = 1U << 13,    ///< a cluster inside a refuted region was passed over (refuteLastFix)
  kFlagFlattened = 1U << 14,         ///< found over the flattened background (background_fallback_only)
  kFlagPrintedWins = 1U << 15,       ///< the printed search ended a flattened track (printed_search_wins)
  kFlagRecheckSwitched = 1U << 16,   ///< a track recheck found a far larger, hand-over-near target elsewhere
  kFlagSilhouetteExtent = 1U << 17,  ///< distance_m from the block-mean silhouette's extent (silhouette_*)
};

/// Execution time of one estimate() per stage [us] (zeros when no clock is set).
struct FarRangeTiming {
  double edge_us = 0.0;
  double histogram_us = 0.0;
  double extra_us = 0.0;  ///< filters added with setExtraFilters()
  double combine_us = 0.0;
  double cluster_us = 0.0;
  double select_us = 0.0;
  double total_us = 0.0;
};

struct FarRangeResult {
  bool valid = false;
  Vec3 direction_c = Vec3::UnitZ();  ///< unit line of sight, camera frame
  double azimuth_rad = 0.0;          ///< atan2(x, z)
  double elevation_rad = 0.0;        ///< atan2(-y, hypot(x, z)): up in the image is positive
  double distance_m = 0.0;           ///< eq16_distance_m, or extent_distance_m (kFlagExtentDistance)
  double eq16_distance_m = 0.0;      ///< eq. 16, gamma / sqrt(n)
  double extent_px = 0.0;            ///< largest distance of a cluster pixel from its centre of mass
  /// f x target radius / extent_px: the distance from the cluster's extent (0 without setTargetRadius())
  double extent_distance_m = 0.0;
  /// The block-mean silhouette's extent about the fix (SilhouetteExtent), 0: not measured or not found
  double silhouette_extent_px = 0.0;
  Vec2 centroid_px = Vec2::Zero();  ///< raw pixels
  int cluster_pixels = 0;           ///< n used in eq. 16 (filled n for the robust method)
  int raw_pixels = 0;               ///< n of eq. 15 (responses above t_out)
  /// measureOutlineSharpness of the selected cluster (robust method; -1: not measured, too small or cut)
  double outline_sharpness = -1.0;
  int boundary_pixels = 0;   ///< outline pixels of the filled cluster (robust)
  double circularity = 0.0;  ///< eq. 15 of the selected cluster
  int cluster_count = 0;     ///< clusters found in the searched region
  int selected = -1;         ///< index in clusters()
  double quality = 0.0;      ///< [0, 1], 0 when not valid
  std::uint32_t flags = 0;   ///< FarRangeFlag
  Roi roi;                   ///< region searched last
  FarRangeTiming timing;
};

using MonotonicClockNs = std::int64_t (*)();

class FarRangeEstimator {
 public:
  /// Allocates every buffer for the camera's image size. Rejects invalid parameters (eq. 14 included).
  LoadError init(const PinholeCamera& camera, const FarRangeParams& params);
  void setClock(MonotonicClockNs clock) { m_clock = clock; }
  /// Init-time (after init()): more low-level filters next to the edge and histogram filters (the filter set
  /// is open, sec. III-B). `weights` lists all 2 + count weights of eq. 13 (edge, histogram, extras) and must
  /// sum to 1 (eq. 14); they replace edge_weight / histogram_weight. The filters are not owned and must live
  /// as long as the estimator. count 0 keeps the two filters with the two weights given.
  LoadError setExtraFilters(ResponseFilter* const* filters, int count, const double* weights);
  /// Init-time: the target's bounding radius [m] (the model's), for extent_distance_m. 0: unknown.
  void setTargetRadius(double radius_m) { m_target_radius_m = radius_m > 0.0 ? radius_m : 0.0; }
  /// recheck_frames: a cluster found by the recheck replaces the track only when its distance (as report()
  /// would give it) is at most this (the navigation pipeline gives its acquisition hand-over distance);
  /// 0: no distance condition.
  void setRecheckMaxDistance(double distance_m) {
    m_recheck_max_distance_m = distance_m > 0.0 ? distance_m : 0.0;
  }
  /// Forget the track (after a mode change or a ground command). Refuted regions stay.
  void reset();
  /// `frames` frames passed without estimate() (another mode looked at them): the track coasts over them,
  /// its gate widening as for frames without a target, and ends past max_coast_frames.
  void skipFrames(int frames);
  /// The last valid fix was looked at and holds no target (acquisition found no edge structure at its cue):
  /// its region is passed over for refuted_fix_frames frames (see FarRangeParams). Returns false when there
  /// is no fix to refute or the feature is off. At most kMaxRefuted regions; a new one replaces the oldest.
  bool refuteLastFix();
  /// Forget every refuted region (a ground command to re-acquire).
  void clearRefuted();
  int refutedCount() const;
  static constexpr int kMaxRefuted = 4;
  /// A cluster within this factor of a refuted fix's n (either way), where it was, is that fix again.
  static constexpr double kRefutedSizeRatio = 4.0;
  /// refuted_follow: a region refuted again is passed over for refuted_fix_frames x 2^(refutations - 1)
  /// frames, up to this many doublings ...
  static constexpr int kMaxRefutedDoublings = 3;
  /// ... and only when its n grew less than this factor since the region's last refutation.
  static constexpr double kRefutedStaticGrowth = 1.25;
  /// Optional prediction for the next frame from a navigation filter: gates the robust selection like a
  /// track would (direction in the camera frame, distance for the expected size).
  void setPrediction(const Vec3& direction_c, double distance_m);

  /// One frame (size must match the camera). Returns kInvalidArgument for a wrong image, else kOk; whether a
  /// target was found is out.valid.
  Status estimate(const MonoImage& image, FarRangeResult& out);

  const FarRangeParams& params() const { return m_params; }
  const PinholeCamera& camera() const { return m_camera; }
  /// Debug views of the last frame (valid until the next estimate()).
  const ResponseImage& combinedResponse() const { return m_combined; }
  const ResponseImage& edgeResponse() const { return m_edge_response; }
  const ResponseImage& histogramResponse() const { return m_histogram_response; }
  const BoundedBuffer<Cluster>& clusters() const { return m_finder.clusters(); }
  const ClusterFinder& clusterFinder() const { return m_finder; }
  const EdgeFilter& edgeFilter() const { return m_edge; }
  const HistogramFilter& histogramFilter() const { return m_histogram; }

 private:
  struct Track {
    bool active = false;
    Vec2 position_px = Vec2::Zero();
    Vec2 velocity_px = Vec2::Zero();  ///< per frame
    bool has_velocity = false;
    double size_px = 0.0;  ///< n of the last accepted target
    double half_extent_px = 0.0;
    int misses = 0;
    int frames_since_check = 0;  ///< fixes since the track began or was last rechecked (recheck_frames)
    double size_at_check = 0.0;  ///< n then
  };
  struct Gate {
    bool active = false;
    Vec2 centre_px = Vec2::Zero();
    double radius_px = 0.0;
    double size_px = 0.0;
    double half_extent_px = 0.0;
  };

  double elapsedUs(std::int64_t& since) const;
  /// Filters, combines and clusters `roi`. `edges_ready`: the edge and extra responses already hold this
  /// region of this image (only the histogram filter changed), so they are not computed again.
  void searchRegion(const MonoImage& image, const Roi& roi, FarRangeResult& out, bool edges_ready = false);
  int selectPaper() const;
  int selectRobust(const Gate& gate, std::uint32_t& flags);
  /// min_outline_sharpness: the cluster is measured (big enough, inside the image) and its outline is a
  /// ramp, not a body's edge.
  bool lacksSharpOutline(const Cluster& c) const;
  /// measureOutlineSharpness of a solid cluster (filled n at least kMinSharpnessFill of the disc of its
  /// radius); a sparse one is not measured.
  OutlineSharpness sharpnessOf(const Cluster& c) const;
  /// lacksSharpOutline of the cluster as the hull `h` would stand for it (adoptHull).
  bool hullLacksSharpOutline(const Cluster& c, const OutlineHull& h) const;
  static constexpr double kMinSharpnessFill = 0.4;
  void prepareCandidates();
  int searchExtended(const Gate& gate, std::uint32_t& flags);
  int preferEnclosingOutline(const Gate& gate, int selected, std::uint32_t& flags);
  /// Clusters of this frame's edge response (eq. 10) alone, for the outline searches (outline_search.cpp);
  /// clusters under min_keep_px are dropped as they are found.
  void clusterEdgeResponse(int min_keep_px);
  /// After an outline search: eq. 13's clusters found again from the same response; returns the selection.
  int restoreEq13Clusters(const Gate& gate);
  /// Without a track: the largest closed, sharp outline (untracked_outline_fill_ratio), or -1.
  int searchSilhouette(std::uint32_t& flags);
  /// Without a track: eq. 13's choice, or a closed outline extended_enclose_ratio times its n.
  int preferSilhouette(int selected, std::uint32_t& flags);
  struct HullChoice {
    int index = -1;  ///< the first member's cluster, -1: none
    double n = 0.0;  ///< the hull's n (area less its outline, as usedPixels)
    double second_n = 0.0;
    OutlineHull shape;
  };
  static constexpr int kHullReachPx = 2;  ///< an outline pixel this near the hull covers it
  /// The best hull of one or two outline fragments (outline_min_coverage, untracked_outline_fill_ratio):
  /// the largest without a gate, else scored as searchExtended scores.
  void bestHullShape(const Gate& gate, std::uint32_t& flags, HullChoice& choice);
  /// The hull as the cluster's filled shape, for report() and the track.
  void adoptHull(Cluster& c, const OutlineHull& h) const;
  int recheckTrack(const MonoImage& image, const Gate& gate, FarRangeResult& out);
  bool takesTheTrackOver(int rival, const Gate& gate, double tracked_n) const;
  struct ClusterDistances {
    double eq16_m = 0.0;       ///< gamma / sqrt(n) (eq. 16)
    double extent_m = 0.0;     ///< f R / r_max (0 without the target's radius)
    bool from_extent = false;  ///< the nearer and far enough out to count: delivered (kFlagExtentDistance)
    double delivered() const { return from_extent ? extent_m : eq16_m; }
  };
  ClusterDistances distancesOf(const Cluster& c) const;  ///< what report() delivers, and the recheck tests
  Gate currentGate() const;
  int usedPixels(const Cluster& c) const;   ///< n of eq. 16 for this method
  Vec2 usedCentre(const Cluster& c) const;  ///< its centre: of the filled cluster when holes are filled
  bool touchesImageBorder(const Cluster& c) const;
  void report(const Cluster& c, const Gate& gate, FarRangeResult& out) const;
  void updateTrack(const FarRangeResult& out);
  /// silhouette_*: measures the fix's block-mean silhouette and delivers its extent's distance when nearer.
  static constexpr int kSilhouetteAttempts =
      4;  ///< windows tried, each twice the last, within silhouette_max_half_px
  void measureSilhouette(FarRangeResult& out);

  PinholeCamera m_camera;
  FarRangeParams m_params;
  bool m_flatten_as_fallback = false;  ///< background_fallback_only
  bool m_track_flattened = false;      ///< the last fix was found over the flattened background
  bool m_robust = true;
  double m_target_radius_m = 0.0;
  double m_recheck_max_distance_m = 0.0;
  MonotonicClockNs m_clock = nullptr;
  MonoImage m_frame;  ///< the frame estimate() works on: a view, used during that call only
  EdgeFilter m_edge;
  HistogramFilter m_histogram;
  WeightedSum m_sum;
  static constexpr int kMaxExtraFilters = WeightedSum::kMaxInputs - 2;
  std::array<ResponseFilter*, kMaxExtraFilters> m_extra_filters{};
  std::array<ResponseImage, kMaxExtraFilters> m_extra_responses;
  int m_extra_count = 0;
  ClusterFinder m_finder;
  SilhouetteExtent m_silhouette;
  ResponseImage m_edge_response;
  ResponseImage m_histogram_response;
  ResponseImage m_combined;
  BoundedBuffer<std::uint8_t> m_row_max;
  BoundedBuffer<std::uint8_t> m_edge_row_max;  ///< the outline search's, so m_row_max stays eq. 13's
  std::uint8_t m_t_in_q = 229;
  std::uint8_t m_t_out_q = 127;
  std::uint8_t m_ext_spawn_q = 252;
  std::uint8_t m_ext_grow_q = 153;
  Track m_track;
  struct Refuted {
    Vec2 centre_px = Vec2::Zero();
    double radius_px = 0.0;
    double pixels = 0.0;  ///< n of the refuted fix
    int frames_left = 0;  ///< 0: not passed over (expired or unused)
    int refutations = 0;  ///< times refuted (0: unused); kept after expiry while followed (refuted_follow)
  };
  std::array<Refuted, kMaxRefuted> m_refuted{};
  /// A cluster of `pixels` (n) centred at centre_px is a refuted fix seen again.
  bool refuted(const Vec2& centre_px, double pixels) const;
  /// A cluster of `pixels` centred at centre_px is where region r was refuted (within its radius, like size).
  static bool sameRegion(const Refuted& r, const Vec2& centre_px, double pixels);
  /// refuted_follow: each remembered region moves to the like-sized cluster of this search nearest its
  /// centre.
  void followRefuted();
  /// refuted() for a candidate cluster; sets kFlagRefutedSkipped when it is.
  bool passedOver(const Cluster& c, std::uint32_t& flags) const;
  bool m_has_last_fix = false;  ///< m_last_fix_* hold the last valid fix (reset() keeps them)
  Vec2 m_last_fix_px = Vec2::Zero();
  double m_last_fix_extent_px = 0.0;
  double m_last_fix_pixels = 0.0;
  bool m_last_fix_outline = false;  ///< the last fix was found by an outline search (kFlagExtended)
  bool m_has_prediction = false;
  Vec2 m_prediction_px = Vec2::Zero();
  double m_prediction_size_px = 0.0;
};

}  // namespace visnav::far
