#include "visnav/acquisition/edge_scorer.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::acq {

LoadError EdgeScorer::init(const PinholeCamera& camera, const PolygonModel& model,
                           const ScorerSettings& settings) {
  if (model.edges().empty()) return LoadError::failure("acquisition: model has no edges");
  if (settings.samples < 4) return LoadError::failure("acquisition: fewer than 4 samples per hypothesis");
  m_camera = camera;
  m_model = model;
  m_settings = settings;
  m_vertices_c.reserve(model.vertices().size());
  m_vertices_w.reserve(model.vertices().size());
  m_front.reserve(model.surfaces().size());
  m_edges.reserve(model.edges().size());
  // At most `samples` spread by length plus one rounding sample per edge.
  m_samples.reserve(static_cast<std::size_t>(settings.samples) + 2U * model.edges().size());
  return LoadError::success();
}

bool EdgeScorer::projectVisibleEdges(const Pose& pose, const WorkingImage& image) {
  m_vertices_c.clear();
  m_vertices_w.clear();
  m_front.clear();
  m_edges.clear();
  for (const Vec3& v : m_model.vertices()) {
    const Vec3 p = pose.transform(v);
    Vec2 px;
    if (!(p.z() > 1e-3) || !m_camera.project(p, px)) return false;
    m_vertices_c.push(p);
    m_vertices_w.push(image.toWorking(px));
  }
  bool any = false;
  for (const ModelSurface& s : m_model.surfaces()) {
    // Front-facing (CONVENTIONS.md): outward normal against the line of sight to the centroid.
    const bool front = (pose.R_c_m * s.normal_m).dot(pose.transform(s.centroid_m)) < 0.0;
    m_front.push(front ? 1U : 0U);
    any = any || front;
  }
  if (!any) return false;
  for (const ModelEdge& e : m_model.edges()) {
    const bool left = e.surface_left >= 0 && m_front[static_cast<std::size_t>(e.surface_left)] != 0U;
    const bool right = e.surface_right >= 0 && m_front[static_cast<std::size_t>(e.surface_right)] != 0U;
    if (!left && !right) continue;
    ProjectedEdge pe;
    pe.a = m_vertices_w[static_cast<std::size_t>(e.v0)];
    pe.b = m_vertices_w[static_cast<std::size_t>(e.v1)];
    const Vec2 d = pe.b - pe.a;
    if (d.squaredNorm() < 1e-12) continue;
    pe.blend = ChannelBlend::of(std::atan2(d.x(), -d.y()));  // angle of the normal (-d.y, d.x)
    pe.weight = (left && right) ? m_settings.internal_edge_weight : 1.0;
    if (pe.weight > 0.0) m_edges.push(pe);
  }
  return !m_edges.empty();
}

bool EdgeScorer::sample(const Pose& pose, const WorkingImage& image) {
  m_samples.clear();
  if (!projectVisibleEdges(pose, image)) return false;
  double total_length = 0.0;
  for (const ProjectedEdge& e : m_edges) total_length += (e.b - e.a).norm();
  if (!(total_length > 0.0)) return false;
  const double spacing = total_length / m_settings.samples;
  m_sample_weight = 0.0;
  Vec2 sum = Vec2::Zero();
  for (const ProjectedEdge& e : m_edges) {
    const double length = (e.b - e.a).norm();
    // Samples at the centres of equal pieces: at least one per edge, about `spacing` apart.
    const int count = std::max(1, static_cast<int>(length / spacing + 0.5));
    for (int i = 0; i < count; ++i) {
      Sample s;
      const Vec2 p = e.a + ((i + 0.5) / count) * (e.b - e.a);
      s.x = p.x();
      s.y = p.y();
      s.blend = e.blend;
      s.weight = e.weight;
      if (!m_samples.push(s)) break;
      m_sample_weight += e.weight;
      sum += e.weight * p;
    }
  }
  m_sample_centroid = sum / m_sample_weight;
  return m_sample_weight > 0.0;
}

double EdgeScorer::evaluate(const WorkingImage& image, Evidence level, const Vec2& offset) const {
  // The window's evidence is saturated (WorkingImage::prepare): the score is the supported share, in [0, 1].
  // Plain scalars in the innermost loop (the sanitizer build runs it ~10^7 times per box acquisition).
  const double ox = offset.x();
  const double oy = offset.y();
  double sum = 0.0;
  for (const Sample& s : m_samples) sum += s.weight * image.evidence(s.x + ox, s.y + oy, s.blend, level);
  return sum / (m_sample_weight * image.cap());
}

double EdgeScorer::score(const Pose& pose, const WorkingImage& image, Evidence level) {
  return sample(pose, image) ? evaluate(image, level, Vec2::Zero()) : -1.0;
}

double EdgeScorer::scoreAligned(const Pose& pose, const WorkingImage& image, Evidence level,
                                const Vec2& align_to, int shift_steps, double step_px, Vec2& shift) {
  if (!sample(pose, image)) return -1.0;
  const Vec2 base = align_to - m_sample_centroid;
  // The centred shift first: on a plateau of the evidence (saturated, spread) it wins the tie.
  double best = evaluate(image, level, base);
  shift = base;
  for (int j = -shift_steps; j <= shift_steps; ++j) {
    for (int i = -shift_steps; i <= shift_steps; ++i) {
      if (i == 0 && j == 0) continue;
      const Vec2 offset = base + step_px * Vec2(i, j);
      const double s = evaluate(image, level, offset);
      if (s > best) {
        best = s;
        shift = offset;
      }
    }
  }
  return best;
}

int EdgeScorer::bestShifts(const Pose& pose, const WorkingImage& image, double max_shift_px, double step_px,
                           double min_separation_px, ShiftPeak* out, int capacity) {
  if (capacity <= 0 || !(step_px > 0.0) || !(max_shift_px >= 0.0) || !sample(pose, image)) return 0;
  const int steps = static_cast<int>(max_shift_px / step_px);
  const double max2 = max_shift_px * max_shift_px;
  const double sep2 = min_separation_px * min_separation_px;
  int count = 0;
  for (int j = -steps; j <= steps; ++j) {
    for (int i = -steps; i <= steps; ++i) {
      const Vec2 offset = step_px * Vec2(i, j);
      if (offset.squaredNorm() > max2) continue;
      const double s = evaluate(image, Evidence::kCoarse, offset);
      if (!(s > 0.0)) continue;
      bool suppressed = false;
      for (int k = 0; k < count && !suppressed; ++k)
        suppressed = out[k].score >= s && (out[k].shift - offset).squaredNorm() < sep2;
      if (suppressed) continue;
      int kept = 0;  // drop the worse peaks this one suppresses
      for (int k = 0; k < count; ++k)
        if ((out[k].shift - offset).squaredNorm() >= sep2) out[kept++] = out[k];
      count = kept;
      int at = count;  // sorted insert, best first; the worst falls off a full list
      while (at > 0 && out[at - 1].score < s) --at;
      if (at >= capacity) continue;
      for (int k = std::min(count, capacity - 1); k > at; --k) out[k] = out[k - 1];
      out[at] = ShiftPeak{offset, s};
      count = std::min(count + 1, capacity);
    }
  }
  // Each peak to the fine evidence: the coarse spread's plateau leaves it up to half a step off.
  const double fine_step = 0.5 * step_px;
  for (int k = 0; k < count; ++k) {
    const Vec2 centre = out[k].shift;
    double best = evaluate(image, Evidence::kFine, centre);
    for (int j = -2; j <= 2; ++j) {
      for (int i = -2; i <= 2; ++i) {
        if (i == 0 && j == 0) continue;
        const Vec2 offset = centre + fine_step * Vec2(i, j);
        const double s = evaluate(image, Evidence::kFine, offset);
        if (s > best) {
          best = s;
          out[k].shift = offset;
        }
      }
    }
  }
  return count;
}

EdgeAgreement EdgeScorer::agreement(const Pose& pose, const WorkingImage& image, double tolerance_px) {
  EdgeAgreement a;
  if (!sample(pose, image)) return a;
  const double present = image.presenceThreshold();
  double hit = 0.0;
  for (const Sample& s : m_samples)
    hit += image.evidence(s.x, s.y, s.blend, Evidence::kFine) >= present ? s.weight : 0.0;
  a.precision = hit / m_sample_weight;
  constexpr double kMinCos = 0.819;  // cos 35 deg
  double explained = 0.0, total = 0.0;
  for (const StrongPixel& q : image.strongPixels()) {
    const double magnitude = q.gradient.norm();
    total += magnitude;
    for (const ProjectedEdge& e : m_edges) {
      const Vec2 d = e.b - e.a;
      const double length2 = d.squaredNorm();
      const Vec2 normal(-d.y(), d.x());
      if (std::fabs(normal.dot(q.gradient)) < kMinCos * std::sqrt(length2) * magnitude) continue;
      const double t = std::clamp((q.p - e.a).dot(d) / length2, 0.0, 1.0);
      if ((e.a + t * d - q.p).squaredNorm() <= tolerance_px * tolerance_px) {
        explained += magnitude;
        break;
      }
    }
  }
  a.recall = total > 0.0 ? explained / total : 0.0;
  a.f1 = a.precision + a.recall > 0.0 ? 2.0 * a.precision * a.recall / (a.precision + a.recall) : 0.0;
  return a;
}

Pose EdgeScorer::shifted(const Pose& pose, const WorkingImage& image, const Vec2& shift_working_px) const {
  // A lateral move dt = z * shift / f keeps the distance: first-order image shift of the model origin.
  const CameraIntrinsics& k = m_camera.intrinsics();
  const double z = pose.t_c_m.z();
  Pose out = pose;
  out.t_c_m.x() += z * shift_working_px.x() * image.scale() / k.fx_px;
  out.t_c_m.y() += z * shift_working_px.y() * image.scale() / k.fy_px;
  return out;
}

double EdgeScorer::refine(const WorkingImage& image, const RefineSettings& settings, Pose& pose,
                          int& evaluations) {
  const CameraIntrinsics& k = m_camera.intrinsics();
  double rotation = settings.rotation_step_rad;
  double lateral_px = settings.lateral_step_working_px;
  double range_rel = settings.range_step_rel;
  Pose best = pose;
  double best_score = -1.0;
  for (int level = 0; level < settings.levels; ++level) {
    const int third = 3 * level / settings.levels;
    const Evidence evidence =
        third == 0 ? Evidence::kCoarse : (third == 1 ? Evidence::kFine : Evidence::kRaw);
    best_score = score(best, image, evidence);
    ++evaluations;
    for (int sweep = 0; sweep < settings.sweeps_per_level; ++sweep) {
      bool improved = false;
      for (int dim = 0; dim < 6; ++dim) {
        for (const double sign : {1.0, -1.0}) {
          Pose trial = best;
          if (dim < 3) {
            trial.R_c_m = expSo3(Vec3::Unit(dim) * (sign * rotation)) * best.R_c_m;  // about the model origin
          } else if (dim < 5) {
            const double f = dim == 3 ? k.fx_px : k.fy_px;
            trial.t_c_m[dim - 3] += sign * lateral_px * image.scale() * best.t_c_m.z() / f;
          } else {
            trial.t_c_m *= 1.0 + sign * range_rel;
          }
          const double s = score(trial, image, evidence);
          ++evaluations;
          if (s > best_score) {
            best_score = s;
            best = trial;
            improved = true;
            break;  // keep this direction's sign; next dimension
          }
        }
      }
      if (!improved) break;
    }
    rotation *= 0.5;
    lateral_px *= 0.5;
    range_rel *= 0.5;
  }
  pose = best;
  return best_score;
}

}  // namespace visnav::acq
