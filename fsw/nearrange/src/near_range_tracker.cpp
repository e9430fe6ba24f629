#include "visnav/nearrange/near_range_tracker.hpp"

#include <algorithm>
#include <cmath>

namespace visnav {

const char* toString(TrackStatus status) {
  switch (status) {
    case TrackStatus::kTracking: return "tracking";
    case TrackStatus::kDegraded: return "degraded";
    case TrackStatus::kLost: return "lost";
  }
  return "unknown";
}

LoadError NearRangeTracker::init(const PinholeCamera& camera, const PolygonModel& model,
                                 const NearRangeParams& params) {
  if (const char* problem = params.crossCheck())
    return LoadError::failure(std::string("nearrange: ") + problem);
  if (params.scanline_half_length_px * 2 + 1 > kMaxScanlineSamples)
    return LoadError::failure("nearrange: scanline_half_length_px exceeds the supported maximum of 64");
  if (camera.width() <= 0 || camera.height() <= 0) return LoadError::failure("nearrange: camera has no size");
  if (model.edges().empty()) return LoadError::failure("nearrange: model has no edges");
  m_camera = camera;
  m_model = model;
  m_params = params;
  m_edge_params.contrast_delta = params.contrast_delta;
  m_edge_params.step_window = params.step_window_px;
  m_edge_params.step_min_z = params.step_min_z;
  m_edge_params.candidate_min_share = params.edge_candidate_min_share;
  m_edge_params.texture_bins = params.texture_bins;
  m_edge_params.texture_min_log_gain = params.texture_min_log_gain;
  m_edge_params.texture_min_variance_ratio = params.texture_min_variance_ratio;
  m_edge_params.subpixel = params.subpixel;
  m_visibility = {params.visibility_enter_low_deg, params.visibility_enter_high_deg,
                  params.visibility_exit_low_deg, params.visibility_exit_high_deg};

  const std::size_t surfaces = model.surfaces().size();
  const std::size_t edges = model.edges().size();
  const std::size_t points = edges * static_cast<std::size_t>(params.max_scanlines_per_edge);
  m_surface_tracked.reserve(surfaces);
  m_surface_front.reserve(surfaces);
  m_edge_selected.reserve(edges);
  m_polarity.reserve(edges * kPolarityBins);
  m_polarity_next.reserve(edges * kPolarityBins);
  m_edges.reserve(edges);
  m_scan_points.reserve(points);
  m_points_ideal.reserve(points);
  m_inlier.reserve(params.max_scanlines_per_edge);
  m_scratch.reserve(params.max_scanlines_per_edge);
  // Each face can give one chamfer corner per vertex too (findChamferCorners).
  m_vertex_obs.reserve(2 * surfaces * static_cast<std::size_t>(model.maxSurfaceVertices()));
  m_chamfer_corners.reserve(surfaces * static_cast<std::size_t>(model.maxSurfaceVertices()));
  m_slot_of_edge.reserve(edges);
  m_edge_obs.reserve(points);
  m_confusable_partner.reserve(edges);
  m_edge_bounds_narrow_face.reserve(edges);
  m_vertex_px.reserve(model.vertices().size());
  m_vertex_c.reserve(model.vertices().size());
  m_occluders.reserve(surfaces);
  m_vertex_in_front.reserve(model.vertices().size());
  m_vertex_best_sin.reserve(model.vertices().size());
  m_vertex_best_px.reserve(model.vertices().size());
  m_vertex_best_var.reserve(model.vertices().size());
  m_vertex_best_interior.reserve(model.vertices().size());
  m_vertex_best_narrow.reserve(model.vertices().size());
  for (std::size_t i = 0; i < model.vertices().size(); ++i) {
    m_vertex_best_sin.push(0.0);
    m_vertex_best_px.push(Vec2::Zero());
    m_vertex_best_var.push(0.0);
    m_vertex_best_interior.push(0.0);
    m_vertex_best_narrow.push(0.0);
    m_vertex_px.push(Vec2::Zero());
    m_vertex_c.push(Vec3::Zero());
    m_vertex_in_front.push(0);
  }
  for (std::size_t i = 0; i < surfaces; ++i) {
    m_surface_tracked.push(0);
    m_surface_front.push(0);
  }
  for (std::size_t i = 0; i < edges; ++i) {
    m_edge_selected.push(0);
    m_confusable_partner.push(-1);
    m_edge_bounds_narrow_face.push(0U);
    m_slot_of_edge.push(-1);
  }
  for (std::size_t i = 0; i < edges * kPolarityBins; ++i) {
    m_polarity.push(0);
    m_polarity_next.push(0);
  }
  findChamferCorners();  // before the relabels, which map its corners
  findModelMirrors();
  findNearTwins();
  reset();
  return LoadError::success();
}

void NearRangeTracker::reset() {
  for (auto& tracked : m_surface_tracked) tracked = 0;
  for (auto& p : m_polarity) p = 0;
  m_first_frame = true;
}

double NearRangeTracker::elapsedUs(std::int64_t& since) const {
  if (m_clock == nullptr) return 0.0;
  const std::int64_t now = m_clock();
  const double us = static_cast<double>(now - since) * 1e-3;
  since = now;
  return us;
}

void NearRangeTracker::updateSurfaces(const Pose& predicted) {
  const auto& surfaces = m_model.surfaces();
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const SurfaceView view = viewSurface(surfaces[s], predicted);
    // On the first frame there is no history: enter thresholds decide.
    const bool was = !m_first_frame && m_surface_tracked[s] != 0U;
    m_surface_tracked[s] = updateVisibility(was, view, m_visibility) ? 1U : 0U;
    m_surface_front[s] = view.front_facing ? 1U : 0U;
  }
  m_first_frame = false;
}

void NearRangeTracker::transformVertices(const Pose& predicted) {
  for (std::size_t v = 0; v < m_model.vertices().size(); ++v)
    m_vertex_c[v] = predicted.transform(m_model.vertices()[v]);
}

bool NearRangeTracker::outwardReference(const ModelEdge& edge, const Pose& predicted,
                                        Vec2& centroid_px) const {
  // Outward side: away from the projected centroid of a tracked (else front-facing) surface owning the edge.
  const auto owns = [&](int s, const BoundedBuffer<std::uint8_t>& flag) { return s >= 0 && flag[s] != 0U; };
  int owner = owns(edge.surface_left, m_surface_tracked) ? edge.surface_left : -1;
  if (owner < 0) owner = owns(edge.surface_right, m_surface_tracked) ? edge.surface_right : -1;
  if (owner < 0) owner = owns(edge.surface_left, m_surface_front) ? edge.surface_left : edge.surface_right;
  return owner >= 0 &&
         m_camera.project(predicted.transform(m_model.surfaces()[owner].centroid_m), centroid_px);
}

bool NearRangeTracker::measureScanline(const MonoImage& image, int model_edge, const Vec3& a_c,
                                       const Vec3& b_c, double t, int index, const Vec2& centroid_px,
                                       ScanPoint& sp) {
  const Vec3 p_c = a_c + t * (b_c - a_c);
  const Vec3 q_c = p_c + 1e-3 * (b_c - a_c);
  Vec2 ahead;
  if (!m_camera.project(p_c, sp.scan_centre_px) || !m_camera.project(q_c, ahead)) return false;
  const Vec2 tangent = ahead - sp.scan_centre_px;
  if (tangent.squaredNorm() < 1e-18) return false;
  sp.scan_normal = Vec2(-tangent.y(), tangent.x()).normalized();
  if (sp.scan_normal.dot(sp.scan_centre_px - centroid_px) < 0.0) sp.scan_normal = -sp.scan_normal;
  // Dither each scanline's sample phase by a low-discrepancy offset in [-0.5, 0.5) px: a pixel-level
  // hit (texture split, n + 0.5) is then quantised differently on every scanline and the line fit
  // averages the quantisation out instead of inheriting one shared bias of up to 0.5 px.
  const double golden = 0.6180339887498949 * (index + 1);
  sp.scan_centre_px += (golden - std::floor(golden) - 0.5) * sp.scan_normal;
  const int bin = std::min(static_cast<int>(t * kPolarityBins), kPolarityBins - 1);
  sp.polarity_bin = static_cast<std::uint8_t>(bin);
  const int expected = m_params.polarity_mode == static_cast<int>(EdgePolarityMode::kLearned)
                           ? m_polarity[model_edge * kPolarityBins + bin]
                           : 0;
  const int half = m_params.scanline_half_length_px;
  double samples[kMaxScanlineSamples];
  if (!sampleScanlineBand(image, sp.scan_centre_px, sp.scan_normal, half,
                          m_params.scanline_band_half_width_px, samples))
    return false;
  const EdgeHit hit = findEdge(samples, 2 * half + 1, m_edge_params, expected);
  if (hit.method == EdgeMethod::kNone) return false;
  sp.method = hit.method;
  sp.polarity = static_cast<std::int8_t>(hit.polarity);
  sp.edge_px = sp.scan_centre_px + hit.offset_px * sp.scan_normal;
  return true;
}

void NearRangeTracker::measureEdge(const MonoImage& image, const Pose& predicted, int e,
                                   NearRangeResult& out) {
  // Sec. II-D: scanlines spread evenly over the projected edge between the vertex margins.
  const ModelEdge& edge = m_model.edges()[e];
  const Vec3 a_c = predicted.transform(m_model.vertices()[edge.v0]);
  const Vec3 b_c = predicted.transform(m_model.vertices()[edge.v1]);
  EdgeMeasurement slot;
  slot.model_edge = e;
  slot.interior = interiorEdge(edge);
  slot.bounds_narrow_face = m_edge_bounds_narrow_face[e] != 0U;
  slot.first_point = static_cast<int>(m_scan_points.size());
  if (!m_camera.project(a_c, slot.predicted_a_px) || !m_camera.project(b_c, slot.predicted_b_px)) {
    out.flags |= kFlagOutOfImage;
    return;
  }
  Vec2 centroid_px;
  if (!outwardReference(edge, predicted, centroid_px)) return;
  const double length_px = (slot.predicted_b_px - slot.predicted_a_px).norm();
  if (length_px >= m_params.min_edge_length_px) {
    const double usable_px = length_px - 2.0 * m_params.vertex_margin_px;
    // A short edge still gets min_scanlines_per_edge scanlines, packed no closer than 1 px. The counts are
    // bounded in floating point before the conversion: a vertex just in front of the camera projects an
    // edge millions of pixels long, and converting that count to int overflowed (campaign_ci under UBSan).
    const double capacity = static_cast<double>(m_params.max_scanlines_per_edge);
    int count = usable_px > 0.0
                    ? static_cast<int>(std::min(usable_px / m_params.scanline_spacing_px + 1.0, capacity))
                    : 0;
    if (usable_px > 0.0 && count < m_params.min_scanlines_per_edge)
      count =
          std::min(m_params.min_scanlines_per_edge, static_cast<int>(std::min(usable_px + 1.0, capacity)));
    count = std::min(count, m_params.max_scanlines_per_edge);
    out.scanlines += count;
    slot.scanlines = count;
    // A confusable interior edge (findConfusableEdges) keeps only the steps nearer its own predicted line
    // than its outline neighbour's: the neighbour's step is never taken for its own.
    const int partner = m_confusable_partner[e];
    slot.confusable = partner >= 0;
    const Line2d own_line = Line2d::throughPoints(slot.predicted_a_px, slot.predicted_b_px);
    const Line2d partner_line = partner >= 0 ? Line2d::throughPoints(m_vertex_px[m_model.edges()[partner].v0],
                                                                     m_vertex_px[m_model.edges()[partner].v1])
                                             : own_line;
    int hidden = 0;
    for (int i = 0; i < count; ++i) {
      const double along_px =
          count == 1 ? 0.5 * length_px
                     : m_params.vertex_margin_px + usable_px * i / static_cast<double>(count - 1);
      if (m_params.occluded_scanlines && occluded(a_c + (along_px / length_px) * (b_c - a_c), edge)) {
        ++hidden;
        continue;
      }
      ScanPoint sp;
      if (!measureScanline(image, e, a_c, b_c, along_px / length_px, i, centroid_px, sp)) continue;
      if (partner >= 0 && std::fabs(partner_line.signedDistance(sp.edge_px)) <
                              std::fabs(own_line.signedDistance(sp.edge_px))) {
        ++out.confusable_points;
        continue;
      }
      if (sp.method == EdgeMethod::kTexture) ++out.texture_points;
      if (sp.method == EdgeMethod::kStep) ++out.weak_step_points;
      if (!m_scan_points.push(sp)) break;
      m_points_ideal.push(m_camera.undistortPixel(sp.edge_px));
    }
    // Hidden scanlines were never cast: an edge mostly behind another part is as short as what shows.
    slot.scanlines -= hidden;
    out.scanlines -= hidden;
    out.occluded_scanlines += hidden;
  }
  slot.point_count = static_cast<int>(m_scan_points.size()) - slot.first_point;
  out.edge_points += slot.point_count;
  m_edges.push(slot);
}

void NearRangeTracker::fitLines(std::uint64_t frame_index, NearRangeResult& out) {
  const RansacParams ransac{m_params.ransac_threshold_px, m_params.ransac_iterations};
  double ratio_sum = 0.0;
  for (EdgeMeasurement& slot : m_edges) {
    // A panel's thickness or a foreshortened edge is too short to measure: it is no evidence either way,
    // so it neither counts as a line nor as a rejected one (the evidence test compares used with total).
    // An edge with fewer scanlines than a line needs (a chamfer seen from afar) can never give one.
    if (slot.scanlines < m_params.min_points_per_line) continue;
    // A confusable edge whose own step was not found (flat lighting: it has none) is no evidence either.
    if (slot.confusable && slot.point_count < m_params.min_points_per_line) continue;
    ++out.lines_total;
    if (slot.point_count < m_params.min_points_per_line) {
      out.flags |= kFlagLineRejected;
      continue;
    }
    // Seeded per frame and edge: identical input gives identical output, whatever ran before.
    m_rng.reseed(static_cast<std::uint64_t>(m_params.ransac_seed) ^ (frame_index * 0x9E3779B97F4A7C15ULL),
                 static_cast<std::uint64_t>(slot.model_edge));
    const RansacResult fit = fitLineRansac(m_points_ideal.data() + slot.first_point, slot.point_count, ransac,
                                           m_rng, m_inlier.data(), m_scratch.data());
    const double ratio = fit.ok ? static_cast<double>(fit.inliers) / slot.point_count : 0.0;
    slot.line = fit.line;
    slot.line_ok =
        fit.ok && fit.inliers >= m_params.min_points_per_line && ratio >= m_params.min_inlier_ratio;
    if (!slot.line_ok) {
      out.flags |= kFlagLineRejected;
      continue;
    }
    ++out.lines_used;
    out.inlier_points += fit.inliers;
    // The line's own scatter (floored at the configured edge-point sigma) sets how well its ends are known:
    // that of its points, not of the inliers the threshold cut from them (uncutScatterVariance).
    double sum_sq = 0.0;
    for (int i = 0; i < slot.point_count; ++i)
      if (m_inlier[i] != 0U) {
        const double d = slot.line.signedDistance(m_points_ideal[slot.first_point + i]);
        sum_sq += d * d;
      }
    double point_var = sum_sq / std::max(1, fit.inliers - 2);
    if (m_params.uncut_line_scatter)
      point_var = uncutScatterVariance(point_var, m_params.ransac_threshold_px);
    const double scatter2 = std::max(point_var, m_params.pixel_sigma_px * m_params.pixel_sigma_px);
    slot.end_variance_px2 = 4.0 * scatter2 / fit.inliers;
    ratio_sum += ratio;
    // Remember each inlier's polarity at its place on the edge for the next frame.
    int votes[kPolarityBins] = {};
    for (int i = 0; i < slot.point_count; ++i) {
      ScanPoint& sp = m_scan_points[slot.first_point + i];
      sp.inlier = m_inlier[i] != 0U;
      if (sp.inlier) votes[sp.polarity_bin] += sp.polarity;
    }
    for (int b = 0; b < kPolarityBins; ++b)
      m_polarity_next[slot.model_edge * kPolarityBins + b] =
          static_cast<std::int8_t>(votes[b] > 0 ? 1 : (votes[b] < 0 ? -1 : 0));
  }
  out.quality = out.lines_total > 0 && out.lines_used > 0
                    ? (static_cast<double>(out.lines_used) / out.lines_total) * (ratio_sum / out.lines_used)
                    : 0.0;
}

void NearRangeTracker::finishLost(const Pose& predicted, NearRangeResult& out) const {
  out.status = TrackStatus::kLost;
  out.pose = predicted;
  out.covariance = Mat6::Identity() * 1e6;  // "do not trust": a prediction, not a measurement
  out.systematic_gain = 1.0;
  out.covariance_terms = CovarianceTerms{};
  out.quality = 0.0;
}

void NearRangeTracker::measureEdges(const MonoImage& image, const Pose& predicted, NearRangeResult& out) {
  if (m_params.occluded_scanlines) prepareOccluders(predicted);
  m_edges.clear();
  m_scan_points.clear();
  m_points_ideal.clear();
  for (std::size_t e = 0; e < m_model.edges().size(); ++e)
    if (m_edge_selected[e] != 0U) measureEdge(image, predicted, static_cast<int>(e), out);
  // Which slot measured each model edge: the chamfer corners (collectVertices) look their edges up in it
  // on every solve of the frame.
  for (int& slot : m_slot_of_edge) slot = -1;
  for (int i = 0; i < static_cast<int>(m_edges.size()); ++i) m_slot_of_edge[m_edges[i].model_edge] = i;
  if (out.texture_points > 0) out.flags |= kFlagTextureFallback;
}

namespace {

double residualVarianceFactor(const PoseFitResult& fit, double pixel_sigma_px) {
  // The configured edge-point sigma is a floor: when the fit's own residuals say the measurements scatter
  // more (blur, noise, a grazing face), the covariance grows with the a-posteriori variance factor
  // s^2 / sigma^2, s^2 = cost / (m - 6), so it stays honest at every range and in every scene.
  const int dof = fit.lm.residual_count - 6;
  if (dof <= 0 || !(pixel_sigma_px > 0.0)) return 1.0;
  const double s2 = fit.lm.final_cost / dof;
  return std::max(1.0, s2 / (pixel_sigma_px * pixel_sigma_px));
}

}  // namespace

double NearRangeTracker::covarianceScale(const PoseFitResult& fit, std::uint32_t flags,
                                         NearRangeResult& out) const {
  // The LM's covariance assumes pixel_sigma_px per residual. Eq. 7's residuals are vertices made by
  // intersecting two fitted lines: each is known as well as those lines' ends, divided by the sine of their
  // angle (collectVertices), which is often several times pixel_sigma_px under noise and blur; and with 4
  // vertices the fit has only 2 degrees of freedom left, so its own residual says little. The larger of
  // the two honest scales is used (campaign plate/12 frame 0: 1.6 deg 1-sigma reported, 12.5 deg off).
  const double sigma2 = m_params.pixel_sigma_px * m_params.pixel_sigma_px;
  const double residual_factor = residualVarianceFactor(fit, m_params.pixel_sigma_px);
  double scale = residual_factor;
  out.covariance_terms = CovarianceTerms{};
  out.covariance_terms.residual_factor = residual_factor;
  out.systematic_gain = 1.0;
  const bool vertex_fit = m_params.pose_residual == static_cast<int>(PoseResidualMode::kVertex) &&
                          (flags & kFlagResidualFallback) == 0U;
  if (vertex_fit && !m_vertex_obs.empty() && sigma2 > 0.0) {
    double sum = 0.0;
    double inv_sin2_sum = 0.0;
    double interior_sum = 0.0;
    double narrow_sum = 0.0;
    for (const VertexObservation& obs : m_vertex_obs) {
      sum += obs.variance_px2;
      inv_sin2_sum += obs.inv_sin2;
      interior_sum += obs.interior_inv_sin2;
      narrow_sum += obs.narrow_inv_sin2;
    }
    const double count = static_cast<double>(m_vertex_obs.size());
    out.covariance_terms.vertex_factor = sum / count / sigma2;
    out.covariance_terms.bias_factor_per_px2 = inv_sin2_sum / count / sigma2;
    out.covariance_terms.interior_factor_per_px2 = interior_sum / count / sigma2;
    out.covariance_terms.narrow_factor_per_px2 = narrow_sum / count / sigma2;
    scale = std::max(scale, out.covariance_terms.vertex_factor);
    // Each line end's systematic error (line_end_bias_px) moves a vertex by b / sin of its lines' angle on
    // each axis, like the scatter does, but more points do not shrink it (NavigationPipeline::deliver judges
    // validity on it).
    const double bias2 = m_params.line_end_bias_px * m_params.line_end_bias_px;
    const double interior2 = m_params.interior_edge_bias_px * m_params.interior_edge_bias_px;
    const double narrow2 = m_params.narrow_face_edge_bias_px * m_params.narrow_face_edge_bias_px;
    const double with_bias =
        std::max(residual_factor, out.covariance_terms.vertex_factor +
                                      bias2 * out.covariance_terms.bias_factor_per_px2 +
                                      interior2 * out.covariance_terms.interior_factor_per_px2 +
                                      narrow2 * out.covariance_terms.narrow_factor_per_px2);
    if (scale > 0.0) out.systematic_gain = with_bias / scale;
  }
  return scale;
}

void NearRangeTracker::finishMeasured(const Pose& predicted, const Pose& pose, const PoseFitResult& fit,
                                      NearRangeResult& out) {
  constexpr std::uint32_t kLostFlags =
      kFlagTooFewLines | kFlagSolverFailed | kFlagResidualTooHigh | kFlagOutOfImage;
  if ((out.flags & kLostFlags) != 0U) {
    finishLost(predicted, out);
    return;
  }
  out.pose = pose;
  out.covariance = fit.covariance * covarianceScale(fit, out.flags, out);
  const double r = fit.rms_px / m_params.degraded_rms_px;
  out.quality *= 1.0 / (1.0 + r * r);
  out.status =
      (out.flags & (kFlagLineRejected | kFlagResidualHigh | kFlagResidualFallback | kFlagAmbiguous)) != 0U
          ? TrackStatus::kDegraded
          : TrackStatus::kTracking;
  // Only a trusted frame teaches the polarity of the next one.
  for (std::size_t i = 0; i < m_polarity.size(); ++i) m_polarity[i] = m_polarity_next[i];
}

Status NearRangeTracker::track(const MonoImage& image, const Pose& predicted, std::uint64_t frame_index,
                               NearRangeResult& out) {
  out = NearRangeResult{};
  std::int64_t start = m_clock != nullptr ? m_clock() : 0;
  std::int64_t stamp = start;
  if (image.empty() || image.width() != m_camera.width() || image.height() != m_camera.height()) {
    finishLost(predicted, out);
    return Status::kInvalidArgument;
  }
  // Quantisation noise of one band-averaged sample: the floor of the scanlines' own noise estimate.
  m_edge_params.noise_floor = 1.0 / (std::max(static_cast<double>(image.max_code), 1.0) * std::sqrt(12.0)) /
                              std::sqrt(2.0 * m_params.scanline_band_half_width_px + 1.0);
  updateSurfaces(predicted);  // 1 surfaces (sec. II-H)
  selectEdges(out);
  transformVertices(predicted);
  if (findConfusableEdges()) out.flags |= kFlagNarrowFace;
  out.timing.project_us = elapsedUs(stamp);
  if ((out.flags & kFlagNoSurface) != 0U) {
    finishLost(predicted, out);
    out.timing.total_us = elapsedUs(start);
    return Status::kOk;
  }
  measureEdges(image, predicted, out);  // 2-4 scanlines, edge points (eq. 4/5), undistortion
  out.timing.scan_us = elapsedUs(stamp);
  for (std::size_t i = 0; i < m_polarity_next.size(); ++i) m_polarity_next[i] = 0;
  fitLines(frame_index, out);  // 5 RANSAC lines (sec. II-E)
  out.timing.ransac_us = elapsedUs(stamp);
  Pose pose = predicted;
  PoseFitResult fit;
  fitPose(predicted, pose, fit, out);  // 6-7 vertices (eq. 6) and LM (eq. 7)
  out.timing.pose_us = elapsedUs(stamp);
  finishMeasured(predicted, pose, fit, out);  // 8 verdict
  out.timing.total_us = elapsedUs(start);
  return Status::kOk;
}

}  // namespace visnav
