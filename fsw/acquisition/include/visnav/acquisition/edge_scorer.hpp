// Scores a pose hypothesis against a WorkingImage: projects the model's visible edges (outline and, with a
// lower weight, edges between two front faces), samples them at a bounded count and averages the image's
// gradient component along each edge's normal there. Also refines a hypothesis by a bounded pattern search
// on that score. Buffers are sized in init(); nothing allocates afterwards.
#pragma once

#include "visnav/acquisition/working_image.hpp"
#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::acq {

struct ScorerSettings {
  int samples = 64;                   ///< edge samples per hypothesis (bounded cost)
  double internal_edge_weight = 0.5;  ///< weight of edges between two front faces (outline: 1)
};

/// How well a pose and the window's edges agree both ways.
struct EdgeAgreement {
  double precision = 0.0;  ///< share of the model's visible edge length with an image edge under it
  double recall = 0.0;     ///< share of the window's strong-edge magnitude lying on a model edge
  double f1 = 0.0;         ///< harmonic mean: a pose must explain the image and be explained by it
};

/// A lateral shift of a projected model (working px) and its score (EdgeScorer::bestShifts).
struct ShiftPeak {
  Vec2 shift = Vec2::Zero();
  double score = 0.0;
};

/// Pattern-search refinement settings (steps halve per level). The evidence goes from the coarse spread
/// (first third of the levels) over the fine spread to the raw channels (last third).
struct RefineSettings {
  int levels = 6;
  int sweeps_per_level = 2;
  double rotation_step_rad = 0.1;
  double lateral_step_working_px = 4.0;
  double range_step_rel = 0.06;
};

class EdgeScorer {
 public:
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const ScorerSettings& settings);

  /// Mean saturated edge evidence of the model at `pose` in [0, 1], or -1 when no edge is visible or a
  /// vertex is behind the camera.
  double score(const Pose& pose, const WorkingImage& image, Evidence level);
  /// As score(), with the samples first shifted so that their centroid lands on `align_to` (working
  /// coordinates), then the best of (2 n + 1)^2 further shifts by multiples of `step_px` around it
  /// (n = shift_steps). The shift used (working px) is returned in `shift`.
  double scoreAligned(const Pose& pose, const WorkingImage& image, Evidence level, const Vec2& align_to,
                      int shift_steps, double step_px, Vec2& shift);

  /// The model at `pose` slid over the window: its score at every shift on a grid `step_px` apart within
  /// `max_shift_px` of no shift (coarse evidence), the best peaks at least `min_separation_px` apart (greedy
  /// suppression: a shift near a better kept one is dropped), each then refined on the fine evidence over
  /// the 5 x 5 shifts `step_px / 2` apart around it. Writes up to `capacity` peaks with a score > 0, best
  /// first, and returns their count (0 when no edge is visible). Bounded: (2 max_shift / step + 1)^2 + 25
  /// capacity evaluations of the samples.
  int bestShifts(const Pose& pose, const WorkingImage& image, double max_shift_px, double step_px,
                 double min_separation_px, ShiftPeak* out, int capacity);

  /// Two-way agreement at `pose`: precision from the fine-spread evidence above the window's presence
  /// threshold, recall from the strong pixels within `tolerance_px` of a visible model edge whose normal is
  /// within 35 deg of their gradient. Bounded: strong pixels x visible edges.
  EdgeAgreement agreement(const Pose& pose, const WorkingImage& image, double tolerance_px);

  /// Moves the pose laterally by a working-image shift at the pose's distance (small-angle).
  Pose shifted(const Pose& pose, const WorkingImage& image, const Vec2& shift_working_px) const;

  /// Bounded coordinate pattern search over (rotation about the camera axes, lateral shift, range).
  /// Returns the final score (raw evidence); `pose` receives the refined pose. Evaluations are counted.
  double refine(const WorkingImage& image, const RefineSettings& settings, Pose& pose, int& evaluations);

 private:
  bool projectVisibleEdges(const Pose& pose, const WorkingImage& image);
  /// Projects and samples the visible edges into m_samples; false when nothing is visible.
  bool sample(const Pose& pose, const WorkingImage& image);
  double evaluate(const WorkingImage& image, Evidence level, const Vec2& offset) const;

  struct ProjectedEdge {
    Vec2 a;  ///< working coordinates
    Vec2 b;
    ChannelBlend blend;  ///< of the edge's normal
    double weight = 1.0;
  };

  PinholeCamera m_camera;
  PolygonModel m_model;
  ScorerSettings m_settings;
  BoundedBuffer<Vec3> m_vertices_c;
  BoundedBuffer<Vec2> m_vertices_w;
  BoundedBuffer<std::uint8_t> m_front;
  BoundedBuffer<ProjectedEdge> m_edges;
  struct Sample {
    double x = 0.0;  ///< working coordinates
    double y = 0.0;
    ChannelBlend blend;
    double weight = 1.0;
  };
  BoundedBuffer<Sample> m_samples;
  double m_sample_weight = 0.0;
  Vec2 m_sample_centroid = Vec2::Zero();
};

}  // namespace visnav::acq
