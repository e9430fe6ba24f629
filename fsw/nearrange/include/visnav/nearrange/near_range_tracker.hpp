// The near-range 6-DOF edge tracker (paper sec. II): project the model with the predicted pose, measure
// edge points on scanlines across every edge of every tracked surface, fit lines by RANSAC, intersect them
// into vertices and fit the pose by Levenberg-Marquardt. All memory is sized in init(); track() allocates
// nothing, throws nothing and every loop in it is bounded by a capacity fixed at init.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/image_view.hpp"
#include "visnav/core/rng.hpp"
#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/line2d.hpp"
#include "visnav/geometry/model_symmetry.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/nearrange/edge_detector.hpp"
#include "visnav/nearrange/near_range_params.hpp"
#include "visnav/nearrange/pose_fit.hpp"
#include "visnav/nearrange/ransac_line.hpp"
#include "visnav/nearrange/surface_visibility.hpp"

namespace visnav {

enum class TrackStatus : std::uint8_t {
  kTracking = 0,  ///< every measured line consistent, residual small
  kDegraded = 1,  ///< a pose was fitted but some lines failed or the residual is elevated
  kLost = 2,      ///< no trustworthy pose: the reported pose is the prediction, covariance inflated
};
const char* toString(TrackStatus status);

/// Why a frame is not kTracking (bit set; several may hold).
enum TrackFlag : std::uint32_t {
  kFlagNoSurface = 1U << 0,         ///< no surface passes the visibility hysteresis
  kFlagTooFewLines = 1U << 1,       ///< not enough usable lines for the chosen residual
  kFlagLineRejected = 1U << 2,      ///< at least one line failed its point count / inlier ratio
  kFlagSolverFailed = 1U << 3,      ///< LM did not converge or had too few residuals
  kFlagResidualHigh = 1U << 4,      ///< rms above degraded_rms_px
  kFlagResidualTooHigh = 1U << 5,   ///< rms above max_rms_px
  kFlagOutOfImage = 1U << 6,        ///< projected model leaves the image
  kFlagTextureFallback = 1U << 7,   ///< some edge points came from the texture split (information)
  kFlagResidualFallback = 1U << 8,  ///< vertex residual lacked corners: point-to-line residual used instead
  kFlagSilhouetteOnly = 1U << 9,    ///< no surface passes the sec. II-H gate: only the outline was measured
  /// The depth-mirrored pose (Necker reversal; a plate's other tilt) explains the lines as well: the image
  /// does not say which is true (status degraded; never good evidence on its own).
  kFlagAmbiguous = 1U << 10,
  /// Asked for (setNearTwinChecks): a near twin of the model (a turn mapping it onto itself within
  /// near_twin_rival_max_rel, e.g. a near-square plate's quarter turn) explains the same lines as well.
  /// Information for the caller's rival test; the status is not changed by it.
  kFlagNearTwinRival = 1U << 11,
  /// A tracked face is seen nearly edge-on, as a strip narrower than confusable_edge_separation_px between
  /// two parallel edges: the step test cannot resolve them, and the lines fitted there may be biased by up
  /// to the strip's width, which their scatter does not show (information; the status is not changed).
  kFlagNarrowFace = 1U << 12,
};

/// Per-stage execution time of one track() call [us] (zeros when no clock is set).
struct NearRangeTiming {
  double project_us = 0.0;
  double scan_us = 0.0;
  double ransac_us = 0.0;
  double pose_us = 0.0;
  double total_us = 0.0;
};

/// What a fit's covariance scale (pixel_sigma_px^2 units) was made of: the larger of the residual's
/// a-posteriori factor and the vertices' mean variance from their lines' scatter; bias_factor_per_px2 x b^2
/// is what a systematic line-end error b adds to the latter (line_end_bias_px). Zero where not computed.
struct CovarianceTerms {
  double residual_factor = 0.0;
  double vertex_factor = 0.0;
  double bias_factor_per_px2 = 0.0;
  /// x b_i^2: what interior_edge_bias_px b_i adds to vertex_factor (the interior lines' share of the former).
  double interior_factor_per_px2 = 0.0;
  /// x b_n^2: what narrow_face_edge_bias_px b_n adds (the share of lines bounding a narrow face).
  double narrow_factor_per_px2 = 0.0;
};

struct NearRangeResult {
  TrackStatus status = TrackStatus::kLost;
  std::uint32_t flags = 0;
  Pose pose;                       ///< T_c_m; the prediction when lost
  Mat6 covariance = Mat6::Zero();  ///< over (omega, dt), CONVENTIONS.md; from the points' scatter
  /// covariance x this: the pose's uncertainty with each line end's systematic error (line_end_bias_px)
  /// added, which more points do not average away; what a delivered pose's validity is judged on. 1 where
  /// not computed (a point-to-line fit, a lost frame).
  double systematic_gain = 1.0;
  CovarianceTerms covariance_terms;
  double quality = 0.0;  ///< [0, 1]: share of usable lines x mean inlier ratio x residual term
  int tracked_surfaces = 0;
  std::uint64_t tracked_surface_mask = 0;  ///< bit i: surface i (first 64 surfaces)
  int lines_total = 0;  ///< selected edges long enough to cast scanlines across (the measurable ones)
  int lines_used = 0;
  int silhouette_lines = 0;  ///< measured edges selected as outline only (not of a tracked surface)
  /// Steps found on an interior edge's scanlines nearer its parallel outline neighbour than the edge itself
  /// (findConfusableEdges): the neighbour's, not taken.
  int confusable_points = 0;
  /// Scanlines not cast because their point of the model edge is hidden behind another front-facing surface
  /// nearer the camera (occluded_scanlines: a panel in front of a body edge).
  int occluded_scanlines = 0;
  int scanlines =
      0;  ///< scanlines cast across the predicted edges (edge support = inlier_points / scanlines)
  int edge_points = 0;
  int inlier_points = 0;
  int texture_points = 0;
  int weak_step_points = 0;  ///< significant steps below contrast_delta (the paper's weak contrast)
  int vertices = 0;
  double rms_px = 0.0;
  int lm_iterations = 0;
  /// With kFlagNearTwinRival: the near twin's fit that explains the lines as well (for the caller's
  /// continuity test).
  Pose near_twin_rival;
  /// With kFlagAmbiguous: the depth-mirrored fit that explains the lines as well (for the caller's
  /// continuity test).
  Pose mirrored_rival;
  NearRangeTiming timing;
};

/// The tracker's working state for one measured model edge this frame (also what overlays draw, paper fig.
/// 3).
struct EdgeMeasurement {
  int model_edge = -1;
  int first_point = 0;  ///< range [first_point, first_point + point_count) in the point arrays
  int point_count = 0;
  int scanlines = 0;                ///< cast across it; 0: too short to measure (not counted in lines_total)
  bool confusable = false;          ///< interior edge beside a parallel outline edge (findConfusableEdges)
  bool interior = false;            ///< both its faces front-facing at the prediction (interior_edge_bias_px)
  bool bounds_narrow_face = false;  ///< one of a kFlagNarrowFace strip's two edges (narrow_face_edge_bias_px)
  bool line_ok = false;
  Line2d line;  ///< fitted line, ideal pixels
  /// Variance of the fitted line's normal offset at its ends [px^2]: 4 s^2 / n from its n inliers' scatter s
  /// about it (the end of a least-squares segment is known four times worse than its centroid).
  double end_variance_px2 = 0.0;
  Vec2 predicted_a_px;  ///< projected model edge endpoints, raw pixels
  Vec2 predicted_b_px;
};
/// One scanline across a predicted edge and the edge point found on it (tracker working state).
struct ScanPoint {
  Vec2 scan_centre_px;  ///< raw pixels
  Vec2 scan_normal;     ///< unit, raw pixels
  Vec2 edge_px;         ///< measured edge point, raw pixels (valid when method != kNone)
  EdgeMethod method = EdgeMethod::kNone;
  bool inlier = false;
  std::int8_t polarity = 0;       ///< brightness step sign along scan_normal (outwards)
  std::uint8_t polarity_bin = 0;  ///< position along the edge, for the learned polarity
};

using MonotonicClockNs = std::int64_t (*)();

class NearRangeTracker {
 public:
  /// Allocates every buffer from the model and params. Returns an error naming the offending setting.
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const NearRangeParams& params);
  /// Per-stage timing source (e.g. CLOCK_MONOTONIC). nullptr (default) reports zero timings.
  void setClock(MonotonicClockNs clock) { m_clock = clock; }
  /// Forget surface visibility and polarity history (e.g. after re-acquisition).
  void reset();
  /// Whether the following track() calls also refit the model's near twins to the measured lines
  /// (kFlagNearTwinRival): up to kMaxNearTwins LM fits a frame, so the caller asks for it only while it
  /// has to tell a track from its twins (a branch not yet confirmed). Off after init.
  void setNearTwinChecks(bool on) { m_near_twin_checks = on; }
  /// Near twins the model has (within near_twin_rival_max_rel, at most kMaxNearTwins).
  int nearTwinCount() const { return m_relabel_count - m_mirror_count; }

  /// One frame. `predicted` is the pose to project with (the last pose or a filter prediction);
  /// `frame_index` seeds RANSAC so the same frame gives the same result.
  Status track(const MonoImage& image, const Pose& predicted, std::uint64_t frame_index,
               NearRangeResult& out);

  const NearRangeParams& params() const { return m_params; }
  const PolygonModel& model() const { return m_model; }
  const PinholeCamera& camera() const { return m_camera; }
  const BoundedBuffer<EdgeMeasurement>& lastEdges() const { return m_edges; }
  const BoundedBuffer<ScanPoint>& lastScanPoints() const { return m_scan_points; }

 private:
  /// Minimum edge points for the point-to-line fit: two per degree of freedom, so the 6-DOF fit keeps
  /// redundancy to detect a bad point (a structural bound, not a tuning knob).
  static constexpr int kMinEdgePointsForPose = 12;
  /// The vertex residual needs four corners (eight residuals for six unknowns); rejecting one line must
  /// leave that many, so the leave-one-out search needs one more.
  static constexpr int kMinLinesForVertexPose = 4;
  static constexpr int kMinLinesForLineRejection = kMinLinesForVertexPose + 1;
  /// Neighbouring lines closer than ~2.9 deg to parallel give no vertex: their intersection error grows as
  /// 1 / sin(angle), 20x the line error here (geometry, not tuning).
  static constexpr double kMinVertexSinAngle = 0.05;
  /// Point-to-line with three non-parallel lines still fixes 6 DOF (the vertex residual's fallback).
  static constexpr int kMinLinesForPointToLine = 3;
  /// A mirrored rival is "as good" when its rms is at most this multiple of the fit's (or within one
  /// pixel_sigma_px of it), and "distinct" when it differs by more than these (modulo symmetries): what the
  /// campaign counts as wrong (5 % of the range, 5 deg).
  static constexpr double kRivalRmsFactor = 2.0;
  static constexpr double kRivalDistinctRel = 0.05;
  static constexpr double kRivalDistinctDeg = 5.0;
  /// A rival still shows a surface turned up to 15 deg past grazing (sin 15 deg; rivalShowsMeasuredEdges).
  static constexpr double kRivalGrazingCos = 0.2588;

 public:
  /// Near twins refitted a frame at most (the smallest separations first): a near-cube box has 23.
  static constexpr int kMaxNearTwins = 8;

 private:
  /// At most three axis mirrors of the model frame map it onto itself.
  static constexpr int kMaxMirrors = 3;
  static constexpr int kMaxRelabels = kMaxMirrors + kMaxNearTwins;

  double elapsedUs(std::int64_t& since) const;
  void updateSurfaces(const Pose& predicted);
  void selectEdges(NearRangeResult& out);
  bool findConfusableEdges();  ///< true: a face is seen as a narrow strip (m_vertex_c must be this frame's)
  /// Both faces of `edge` front-facing at the prediction (updateSurfaces).
  bool interiorEdge(const ModelEdge& edge) const;
  /// m_vertex_c: every model vertex in the camera frame at the prediction, once a frame.
  void transformVertices(const Pose& predicted);
  void measureEdges(const MonoImage& image, const Pose& predicted, NearRangeResult& out);
  /// This frame's occluders (m_occluders): every front-facing surface with its plane and image bounds
  /// (m_vertex_c must be this frame's).
  void prepareOccluders(const Pose& predicted);
  /// True when the ray to p_c (camera frame) crosses an occluder other than `edge`'s own faces before
  /// reaching it.
  bool occluded(const Vec3& p_c, const ModelEdge& edge) const;
  void measureEdge(const MonoImage& image, const Pose& predicted, int model_edge, NearRangeResult& out);
  bool outwardReference(const ModelEdge& edge, const Pose& predicted, Vec2& centroid_px) const;
  bool measureScanline(const MonoImage& image, int model_edge, const Vec3& a_c, const Vec3& b_c, double t,
                       int index, const Vec2& centroid_px, ScanPoint& sp);
  bool fitPose(const Pose& predicted, Pose& pose, PoseFitResult& fit, NearRangeResult& out);
  void finishMeasured(const Pose& predicted, const Pose& pose, const PoseFitResult& fit,
                      NearRangeResult& out);
  void fitLines(std::uint64_t frame_index, NearRangeResult& out);
  int collectVertices(int excluded_slot);
  int collectEdgePoints(int excluded_slot);
  bool solvePose(const Pose& predicted, int excluded_slot, int lines_used, Pose& pose, PoseFitResult& fit,
                 int& vertices, std::uint32_t& flags);
  bool rejectWorstLine(const Pose& predicted, bool solved, Pose& pose, PoseFitResult& fit,
                       NearRangeResult& out);
  /// True when a start mirrored in depth about the target (composed with a mirror symmetry of the model, so
  /// a rotation) converges to a distinct pose that fits the same lines about as well.
  bool mirroredRivalFits(const Pose& pose, const PoseFitResult& fit, int lines_used, Pose& rival_out);
  /// True when every measured outline line of `pose`, relabelled through mirror `k`, lies on an edge
  /// `rival` shows (a surface owning it faces the camera or is within kRivalGrazingCos past grazing): a
  /// rival that explains the outline with back-facing edges is no pose the tracker could hold.
  bool rivalShowsMeasuredEdges(const Pose& pose, const Pose& rival, int k) const;
  /// True when a near twin of `pose` (ModelSymmetries::nearTwin), its lines and corners relabelled onto the
  /// twin's features, converges to a distinct pose that fits them about as well and shows them.
  bool nearTwinRivalFits(const Pose& pose, const PoseFitResult& fit, int lines_used, Pose& rival_out);
  /// Fills relabel slot m_relabel_count with the features `map` (x -> map x + offset) makes of each vertex
  /// and edge, if every vertex lands within tolerance_m of one. Init only.
  bool addRelabel(const Mat3& map, const Vec3& offset, double tolerance_m, int near_index);
  void findModelMirrors();
  void findNearTwins();
  void findChamferCorners();
  void finishLost(const Pose& predicted, NearRangeResult& out) const;
  double covarianceScale(const PoseFitResult& fit, std::uint32_t flags, NearRangeResult& out) const;

  static constexpr int kPolarityBins = 16;

  /// Where the lines of two edges of one face meet across the short edge between them (a chamfered or
  /// octagonal outline seen from afar: its short edges are too short to measure, so its long ones share no
  /// vertex). The intersection of two coplanar 3D lines projects to the intersection of their images, so
  /// it is observed like a vertex (eq. 6) whenever the bridge edge is too short this frame to give a line.
  struct ChamferCorner {
    int edge_a = -1;
    int edge_b = -1;
    int bridge = -1;
    Vec3 point_m = Vec3::Zero();
  };

  PinholeCamera m_camera;
  PolygonModel m_model;
  NearRangeParams m_params;
  EdgeSearchParams m_edge_params;
  VisibilityThresholds m_visibility;
  MonotonicClockNs m_clock = nullptr;
  Pcg32 m_rng;

  BoundedBuffer<std::uint8_t> m_surface_tracked;  ///< hysteresis state per surface
  BoundedBuffer<std::uint8_t> m_surface_front;    ///< front-facing with the predicted pose, this frame
  BoundedBuffer<std::uint8_t> m_edge_selected;    ///< per model edge, this frame
  BoundedBuffer<Vec2> m_vertex_px;                ///< per model vertex: projected with the prediction, raw px
  BoundedBuffer<Vec3> m_vertex_c;                 ///< per model vertex: camera frame at the prediction
  /// A front-facing surface as a possible occluder this frame: plane n_c . x = d (camera frame), and the
  /// bounding box of its projection (unbounded when a vertex is behind the camera).
  struct Occluder {
    int surface = -1;
    Vec3 n_c = Vec3::Zero();
    double d = 0.0;
    Vec2 min_px = Vec2::Zero();
    Vec2 max_px = Vec2::Zero();
  };
  BoundedBuffer<Occluder> m_occluders;
  BoundedBuffer<std::uint8_t> m_vertex_in_front;  ///< per model vertex: in front of the camera, projected
  BoundedBuffer<int> m_confusable_partner;        ///< per model edge: its parallel outline neighbour, or -1
  BoundedBuffer<std::uint8_t> m_edge_bounds_narrow_face;  ///< per model edge: bounds a kFlagNarrowFace strip
  BoundedBuffer<std::int8_t> m_polarity;                  ///< per model edge x kPolarityBins, last frame
  BoundedBuffer<std::int8_t> m_polarity_next;

  BoundedBuffer<EdgeMeasurement> m_edges;
  BoundedBuffer<ScanPoint> m_scan_points;
  BoundedBuffer<Vec2> m_points_ideal;  ///< edge points in ideal pixels, parallel to m_scan_points
  BoundedBuffer<std::uint8_t> m_inlier;
  BoundedBuffer<Vec2> m_scratch;
  BoundedBuffer<VertexObservation> m_vertex_obs;
  BoundedBuffer<double> m_vertex_best_sin;  ///< per model vertex: best |sin| of a measured line pair
  BoundedBuffer<Vec2> m_vertex_best_px;
  BoundedBuffer<double> m_vertex_best_var;       ///< per model vertex: its observation's per-axis variance
  BoundedBuffer<double> m_vertex_best_interior;  ///< per model vertex: its lines' interior share (0, 1/2, 1)
  BoundedBuffer<double> m_vertex_best_narrow;    ///< per model vertex: its lines' narrow-face share
  BoundedBuffer<ChamferCorner> m_chamfer_corners;
  BoundedBuffer<int> m_slot_of_edge;  ///< per model edge: its m_edges slot this frame, or -1 (measureEdges)
  BoundedBuffer<EdgePointObservation> m_edge_obs;
  ModelSymmetries m_symmetries;
  /// How a rival's fit relabels the measured features: the model point x measured for the kept pose is the
  /// rival's feature nearest to map x + offset (a mirror M: M x; a near twin S about the centroid c:
  /// S^T (x - c) + c).
  struct Relabel {
    Mat3 map = Mat3::Identity();
    Vec3 offset = Vec3::Zero();
    int near_index = -1;           ///< ModelSymmetries::near index (near twins only)
    BoundedBuffer<int> to_vertex;  ///< model vertex -> the rival's vertex
    BoundedBuffer<int> to_edge;    ///< model edge -> the rival's edge
    BoundedBuffer<int> to_corner;  ///< chamfer corner -> the rival's chamfer corner
  };
  /// Slots [0, m_mirror_count): axis reflections of the model frame that map the model onto itself;
  /// [m_mirror_count, m_relabel_count): near twins.
  std::array<Relabel, kMaxRelabels> m_relabels;
  int m_mirror_count = 0;
  int m_relabel_count = 0;
  int m_relabel = -1;  ///< the rival fit's relabel slot: observations relabelled to the rival's features
  bool m_near_twin_checks = false;
  bool m_first_frame = true;
};

}  // namespace visnav
