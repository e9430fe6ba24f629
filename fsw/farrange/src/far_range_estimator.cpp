#include "visnav/farrange/far_range_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace visnav::far {

LoadError FarRangeEstimator::init(const PinholeCamera& camera, const FarRangeParams& params) {
  if (camera.width() < 3 || camera.height() < 3 || camera.width() > 65535 || camera.height() > 65535)
    return LoadError::failure("far range: image size must be 3..65535 px per side");
  if (const char* problem = params.crossCheck()) return LoadError::failure(problem);
  m_camera = camera;
  m_params = params;
  m_robust = params.method == static_cast<int>(FarRangeMethod::kRobust);
  const double lambdas[2] = {params.edge_weight, params.histogram_weight};
  LoadError error = m_sum.setWeights(lambdas, 2);
  if (!error.ok) return error;
  m_extra_count = 0;
  const int w = camera.width();
  const int h = camera.height();
  EdgeFilterSettings edge;
  edge.kernel = static_cast<EdgeKernel>(params.edge_kernel);
  // The published method divides by the single maximum (eq. 10).
  edge.percentile = m_robust ? params.edge_percentile : 100.0;
  edge.percentile_factor = m_robust ? params.edge_percentile_factor : 1.0;
  edge.ref_floor = m_robust ? params.edge_ref_floor : 0.0;
  m_edge.init(w, h, edge);
  m_histogram.init(params.beta);
  // Robust: a region of interest is judged with the whole frame's histogram (eq. 11 is over the image).
  m_histogram.setCountOutsideRoi(m_robust);
  m_histogram.setBackgroundBlock(m_robust ? params.background_block_px : 0, w, h);
  m_flatten_as_fallback = m_robust && params.background_block_px > 0 && params.background_fallback_only;
  m_histogram.setFlattening(!m_flatten_as_fallback);
  m_sum.init(w);
  m_edge_response.init(w, h);
  m_histogram_response.init(w, h);
  m_combined.init(w, h);
  m_row_max.reserve(static_cast<std::size_t>(h));
  m_edge_row_max.reserve(static_cast<std::size_t>(h));
  m_finder.init(w, h, params.max_clusters, params.max_cluster_pixels);
  if (m_robust && params.silhouette_min_half_px > 0.0) m_silhouette.init();
  // "Exceeds t": S / 255 > t  <=>  S > floor(255 t) for the integer S.
  m_t_in_q = static_cast<std::uint8_t>(std::floor(params.t_in * 255.0));
  m_t_out_q = static_cast<std::uint8_t>(std::floor(params.t_out * 255.0));
  m_ext_spawn_q = static_cast<std::uint8_t>(std::floor(params.extended_spawn * 255.0));
  m_ext_grow_q = static_cast<std::uint8_t>(std::floor(params.extended_grow * 255.0));
  reset();
  return LoadError::success();
}

LoadError FarRangeEstimator::setExtraFilters(ResponseFilter* const* filters, int count,
                                             const double* weights) {
  if (count < 0 || count > kMaxExtraFilters) return LoadError::failure("far range: 0 to 6 extra filters");
  for (int i = 0; i < count; ++i) {
    if (filters[i] == nullptr)
      return LoadError::failure("far range: extra filter " + std::to_string(i) + " is null");
  }
  LoadError error = m_sum.setWeights(weights, 2 + count);  // eq. 14 over all filters
  if (!error.ok) return error;
  for (int i = 0; i < count; ++i) {
    m_extra_filters[static_cast<std::size_t>(i)] = filters[i];
    m_extra_responses[static_cast<std::size_t>(i)].init(m_camera.width(), m_camera.height());
  }
  m_extra_count = count;
  return LoadError::success();
}

void FarRangeEstimator::reset() {
  m_track = Track{};
  m_track_flattened = false;
  m_has_prediction = false;
}

void FarRangeEstimator::skipFrames(int frames) {
  if (!m_track.active || frames <= 0) return;
  if (frames > m_params.max_coast_frames - m_track.misses) {
    m_track = Track{};
  } else {
    m_track.misses += frames;
  }
  m_has_prediction = false;
}

void FarRangeEstimator::setPrediction(const Vec3& direction_c, double distance_m) {
  Vec2 px;
  const double sqrt_n = distance_m > 0.0 ? m_params.gamma / distance_m : 0.0;
  // A distance so small that eq. 16's size overflows is no prediction either.
  if (!(distance_m > 0.0) || !std::isfinite(sqrt_n * sqrt_n) || !m_camera.project(direction_c, px)) return;
  m_has_prediction = true;
  m_prediction_px = px;
  m_prediction_size_px = sqrt_n * sqrt_n;
}

double FarRangeEstimator::elapsedUs(std::int64_t& since) const {
  if (m_clock == nullptr) return 0.0;
  const std::int64_t now = m_clock();
  const double us = static_cast<double>(now - since) * 1e-3;
  since = now;
  return us;
}

void FarRangeEstimator::searchRegion(const MonoImage& image, const Roi& roi, FarRangeResult& out,
                                     bool edges_ready) {
  std::int64_t stamp = m_clock != nullptr ? m_clock() : 0;
  m_edge_response.setRoi(roi);
  m_histogram_response.setRoi(roi);
  m_combined.setRoi(roi);
  if (!edges_ready) m_edge.apply(image, roi, m_edge_response);
  out.timing.edge_us += elapsedUs(stamp);
  m_histogram.apply(image, roi, m_histogram_response);
  out.timing.histogram_us += elapsedUs(stamp);
  const ResponseImage* inputs[WeightedSum::kMaxInputs] = {&m_edge_response, &m_histogram_response};
  for (int i = 0; i < m_extra_count; ++i) {
    ResponseImage& response = m_extra_responses[static_cast<std::size_t>(i)];
    response.setRoi(roi);
    if (!edges_ready) m_extra_filters[static_cast<std::size_t>(i)]->apply(image, roi, response);
    inputs[2 + i] = &response;
  }
  out.timing.extra_us += m_extra_count > 0 ? elapsedUs(stamp) : 0.0;
  m_sum.apply(inputs, m_combined, m_row_max.data());
  out.timing.combine_us += elapsedUs(stamp);
  m_finder.find(m_combined, m_row_max.data(), m_t_in_q, m_t_out_q);
  if (m_robust) {
    prepareCandidates();
    followRefuted();
  }
  out.timing.cluster_us += elapsedUs(stamp);
  out.roi = roi;
  out.cluster_count = static_cast<int>(m_finder.clusters().size());
  if (m_finder.seedsSkipped() > 0) out.flags |= kFlagClusterCapacity;
  if (m_finder.pixelCapacityHit()) out.flags |= kFlagPixelCapacity;
}

Status FarRangeEstimator::estimate(const MonoImage& image, FarRangeResult& out) {
  out = FarRangeResult{};
  if (image.empty() || image.width() != m_camera.width() || image.height() != m_camera.height()) {
    return Status::kInvalidArgument;
  }
  std::int64_t start = m_clock != nullptr ? m_clock() : 0;
  m_frame = image;
  for (Refuted& r : m_refuted) r.frames_left = r.frames_left > 0 ? r.frames_left - 1 : 0;
  const Roi full = Roi::full(m_camera.width(), m_camera.height());
  Gate gate = m_robust ? currentGate() : Gate{};
  const bool untracked = m_robust && !gate.active;
  int selected = -1;
  // recheck_frames: this frame is searched whole, and the track is checked against its largest cluster.
  const bool recheck = m_robust && m_params.recheck_frames > 0 && m_track.active && !m_has_prediction &&
                       m_track.frames_since_check >= m_params.recheck_frames;
  if (m_robust && m_flatten_as_fallback && m_params.printed_search_wins && m_track_flattened) {
    // A fix over the flattened background is a fallback, and so is its track: once eq. 11 as printed finds
    // a target in the whole frame again, that target is taken as it would be without flattening (campaign
    // plate/114: a drifting blob found flattened on a frame without target was held 140 frames, 6-8 deg
    // off the plate, which the printed search finds on its own).
    searchRegion(image, full, out);
    std::uint32_t printed_flags = 0U;
    const int printed = selectRobust(Gate{}, printed_flags);
    if (printed >= 0) {
      m_track = Track{};
      m_track_flattened = false;
      gate = Gate{};
      selected = printed;
      out.flags |= printed_flags | kFlagPrintedWins;
    }
  }
  if (recheck) {
    // The whole frame first; a frame the recheck does not switch is then searched as any other, so it
    // gives the same fix as without the recheck.
    const std::uint32_t flags_before = out.flags;
    selected = recheckTrack(image, gate, out);
    if (selected >= 0) {
      gate = Gate{};
    } else {
      out.flags = flags_before;
    }
  }
  if (selected < 0 && m_robust && m_params.use_roi && gate.active) {
    // The region holds the gate and the target's expected extent with a margin (sec. V).
    // Bounded before the int casts: a gate grown over many misses (or NaN) held to 16 image sides, as good
    // as infinite once clipped, far within int.
    const double image_side = 16.0 * static_cast<double>(std::max(m_camera.width(), m_camera.height()));
    double half =
        std::max(gate.radius_px + gate.half_extent_px, m_params.roi_extent_factor * gate.half_extent_px) +
        m_params.roi_min_half_px;
    if (!(half <= image_side)) half = image_side;
    const double cx = std::clamp(gate.centre_px.x(), -half, m_camera.width() + half);
    const double cy = std::clamp(gate.centre_px.y(), -half, m_camera.height() + half);
    const Roi roi = Roi{static_cast<int>(std::floor(cx - half)), static_cast<int>(std::floor(cy - half)),
                        static_cast<int>(2.0 * half) + 1, static_cast<int>(2.0 * half) + 1}
                        .clipped(full.width, full.height);
    if (!roi.empty() && roi.area() < full.area()) {
      out.flags |= kFlagRoi;
      // A target tracked over the flattened background is looked for the same way in its region.
      const bool flatten = m_flatten_as_fallback && m_track_flattened;
      if (flatten) m_histogram.setFlattening(true);
      searchRegion(image, roi, out);
      if (flatten) m_histogram.setFlattening(false);
      std::int64_t stamp = m_clock != nullptr ? m_clock() : 0;
      selected = selectRobust(gate, out.flags);
      if (selected < 0) selected = searchExtended(gate, out.flags);
      out.timing.select_us += elapsedUs(stamp);
      if (selected >= 0 && flatten) out.flags |= kFlagFlattened;
      if (selected < 0) out.flags |= kFlagRoiFallback;
    }
  }
  if (selected < 0) {
    searchRegion(image, full, out);
    std::int64_t stamp = m_clock != nullptr ? m_clock() : 0;
    selected = m_robust ? selectRobust(gate, out.flags) : selectPaper();
    if (selected < 0 && m_robust) selected = searchExtended(gate, out.flags);
    out.timing.select_us += elapsedUs(stamp);
  }
  if (selected < 0 && m_flatten_as_fallback) {
    // Nothing in the whole frame: a target inside a gradient's or a limb's grey levels is rare only
    // against the flattened background (background_fallback_only).
    m_histogram.setFlattening(true);
    searchRegion(image, full, out, true);  // the full frame's edge responses are this frame's already
    m_histogram.setFlattening(false);
    std::int64_t stamp = m_clock != nullptr ? m_clock() : 0;
    selected = selectRobust(gate, out.flags);
    if (selected < 0) selected = searchExtended(gate, out.flags);
    out.timing.select_us += elapsedUs(stamp);
    if (selected >= 0) out.flags |= kFlagFlattened;
  }
  if (untracked) {
    selected = preferSilhouette(selected, out.flags);
  } else if (selected >= 0 && m_robust && (out.flags & kFlagExtended) == 0U) {
    selected = preferEnclosingOutline(gate, selected, out.flags);
  }
  if (selected >= 0) {
    out.cluster_count = static_cast<int>(m_finder.clusters().size());
    out.selected = selected;
    report(m_finder.clusters()[static_cast<std::size_t>(selected)], gate, out);
    measureSilhouette(out);
  } else {
    out.flags |= m_finder.clusters().empty() ? kFlagNoCluster : kFlagNoCandidate;
  }
  if (m_robust) updateTrack(out);
  if (out.valid) m_track_flattened = (out.flags & kFlagFlattened) != 0U;
  if (!out.valid && m_track.active) out.flags |= kFlagCoasting;
  if (out.valid) {
    m_has_last_fix = true;
    m_last_fix_px = out.centroid_px;
    m_last_fix_extent_px = out.extent_px;
    m_last_fix_pixels = out.cluster_pixels;
    m_last_fix_outline = (out.flags & kFlagExtended) != 0U;
  }
  m_has_prediction = false;  // a filter prediction holds for one frame
  m_frame = MonoImage{};
  out.timing.total_us = elapsedUs(start);
  return Status::kOk;
}

FarRangeEstimator::ClusterDistances FarRangeEstimator::distancesOf(const Cluster& c) const {
  ClusterDistances d;
  d.eq16_m = m_params.gamma / std::sqrt(static_cast<double>(usedPixels(c)));
  // The target's bounding sphere seen at the cluster's extent. eq. 16's n counts response pixels, and an
  // extended target's outline has far fewer than its area (a plate at 12 m read 65 m). Both read too far
  // on a fragment of the target (the extent on a satellite whose panels are dark), and too far is a dead
  // end (never handed over) where too near costs one failed acquisition: the nearer of the two is taken.
  if (m_target_radius_m > 0.0 && c.max_radius_px > 0.0) {
    d.extent_m = m_camera.intrinsics().fx_px * m_target_radius_m / c.max_radius_px;
    d.from_extent = m_params.extent_distance_min_px > 0.0 &&
                    c.max_radius_px >= m_params.extent_distance_min_px && d.extent_m < d.eq16_m;
  }
  return d;
}

void FarRangeEstimator::report(const Cluster& c, const Gate& gate, FarRangeResult& out) const {
  const bool filled = m_robust && m_params.fill_holes && c.filled_count > 0;
  out.centroid_px = filled ? c.filled_com_px : c.com_px;
  out.cluster_pixels = filled ? usedPixels(c) : c.pixel_count;
  out.raw_pixels = c.pixel_count;
  out.boundary_pixels = c.boundary_count;
  out.circularity = c.circularity;
  // Direction: undistort the centre of mass, then back-project (CONVENTIONS.md).
  out.direction_c = m_camera.bearing(out.centroid_px);
  const Vec3& d = out.direction_c;
  out.azimuth_rad = std::atan2(d.x(), d.z());
  out.elevation_rad = std::atan2(-d.y(), std::hypot(d.x(), d.z()));
  const ClusterDistances distances = distancesOf(c);
  out.eq16_distance_m = distances.eq16_m;
  out.extent_distance_m = distances.extent_m;
  out.distance_m = distances.delivered();
  if (distances.from_extent) out.flags |= kFlagExtentDistance;
  out.extent_px = c.max_radius_px;
  if (touchesImageBorder(c)) out.flags |= kFlagAtBorder;
  out.valid = true;
  if (m_robust) {
    const OutlineSharpness sharpness = sharpnessOf(c);
    out.outline_sharpness = sharpness.measured ? sharpness.ratio : -1.0;
  }
  if (!m_robust) {
    out.quality = c.circularity;
    return;
  }
  // Robust quality: size consistency with the prediction (0.5 without one), halved when ambiguous or cut
  // by the image border.
  double q = 0.5;
  if (gate.active && gate.size_px > 0.0) q = std::exp(-std::abs(std::log(out.cluster_pixels / gate.size_px)));
  if ((out.flags & kFlagAmbiguous) != 0U) q *= 0.5;
  if ((out.flags & kFlagAtBorder) != 0U) q *= 0.5;
  out.quality = q;
}

void FarRangeEstimator::measureSilhouette(FarRangeResult& out) {
  if (!m_robust || !(m_params.silhouette_min_half_px > 0.0) || !(m_target_radius_m > 0.0) || !out.valid ||
      !(out.extent_px >= m_params.extent_distance_min_px))
    return;
  // Experimental, off by default (fsw/farrange/README.md item 11): a glow as bright as the target and
  // touching it joins the silhouette, which then reads the target up to 2x too near (campaign box/6: 15 m
  // at 29 m, never acquired). The window holds the fix with room for a target several times its extent. It
  // doubles (bounded) until a silhouette is taken: a window inside a target many times the fix's size fits
  // its background on the target itself, and finds nothing or the fragment again. A silhouette is taken
  // only when it holds the fix and reaches beyond it (a fix's own extent stands otherwise), and only a
  // body's: its outline must be sharp (a glow's is a ramp; without this rule box/6 read 17-22 m at 58-417 m).
  double half = std::max(m_params.silhouette_min_half_px, 4.0 * out.extent_px);
  SilhouetteMeasure s;
  bool taken = false;
  for (int attempt = 0; attempt < kSilhouetteAttempts && !taken; ++attempt) {
    s = m_silhouette.measure(m_frame, out.centroid_px, half, out.extent_px, m_params.silhouette_block_px,
                             m_params.silhouette_k_sigma, m_params.silhouette_level_ratio);
    if (s.found && s.extent_px > out.extent_px && (s.centroid_px - out.centroid_px).norm() <= s.extent_px) {
      const OutlineSharpness sharpness = measureOutlineSharpness(m_frame, s.centroid_px, s.extent_px);
      taken = sharpness.measured && sharpness.ratio >= m_params.min_outline_sharpness;
    }
    if (taken || s.cut_by_image || half >= m_params.silhouette_max_half_px) break;
    half = std::min(2.0 * half, m_params.silhouette_max_half_px);
  }
  if (!taken) return;
  out.silhouette_extent_px = s.extent_px;
  const double distance_m = m_camera.intrinsics().fx_px * m_target_radius_m / s.extent_px;
  if (distance_m < out.distance_m) {
    out.distance_m = distance_m;
    out.extent_distance_m = distance_m;
    out.flags |= kFlagSilhouetteExtent | kFlagExtentDistance;
  }
}

void FarRangeEstimator::updateTrack(const FarRangeResult& out) {
  Track& t = m_track;
  if (out.valid) {
    const Cluster& c = m_finder.clusters()[static_cast<std::size_t>(out.selected)];
    if (t.active) {
      const Vec2 step = (out.centroid_px - t.position_px) / static_cast<double>(1 + t.misses);
      t.velocity_px = t.has_velocity ? Vec2(0.5 * (t.velocity_px + step)) : step;
      t.has_velocity = true;
      ++t.frames_since_check;
    } else {
      t.velocity_px.setZero();
      t.has_velocity = false;
      t.frames_since_check = 0;
      t.size_at_check = out.cluster_pixels;
    }
    t.active = true;
    t.position_px = out.centroid_px;
    t.size_px = out.cluster_pixels;
    t.half_extent_px = c.halfExtentPx();
    t.misses = 0;
    return;
  }
  if (!t.active) return;
  ++t.misses;
  if (t.misses > m_params.max_coast_frames) t = Track{};
}

}  // namespace visnav::far
