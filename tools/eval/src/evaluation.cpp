#include "visnav/eval/evaluation.hpp"

#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace visnav::eval {
namespace {

// Far-range errors of one row against its truth frame (far_valid rows only).
void scoreFarRange(const ReplayRow& row, const Pose& truth, FrameRecord& rec) {
  if (!row.far_valid) return;
  const Vec3 direction =
      directionFromAzimuthElevation(row.far_azimuth_deg * kRadPerDeg, row.far_elevation_deg * kRadPerDeg);
  rec.far_scored = farRangeError(direction, row.far_distance_m, truth.t_c_m, rec.far_error);
}

// Mode counts, transitions and final mode; far-range statistics.
void summariseModesAndFarRange(const std::vector<ReplayRow>& replay, const std::vector<FrameRecord>& frames,
                               EvaluationSummary& s) {
  std::vector<double> direction, distance;
  ReplayMode previous = ReplayMode::kUnknown;
  for (const FrameRecord& f : frames) {
    if (f.far_scored) {
      direction.push_back(f.far_error.direction_deg);
      distance.push_back(f.far_error.distance_pct);
    }
    if (f.mode == ReplayMode::kUnknown) continue;
    ++s.mode_frames[static_cast<std::size_t>(f.mode)];
    if (previous != ReplayMode::kUnknown && f.mode != previous)
      s.transitions.push_back({f.frame, previous, f.mode});
    previous = f.mode;
  }
  s.far_direction_deg = absStats(direction);
  s.far_distance_pct = absStats(distance);
  const ReplayRow* last = nullptr;
  for (const ReplayRow& r : replay) {
    s.has_modes = s.has_modes || r.mode != ReplayMode::kUnknown;
    if (last == nullptr || r.frame > last->frame) last = &r;
  }
  if (last != nullptr) s.final_mode = last->mode;
  std::vector<double> nis;
  for (const ReplayRow& r : replay) {
    if (!r.has_nis) continue;
    nis.push_back(r.nis);
    s.nis_mean += r.nis;
    s.nis_above_gate += r.nis > kNisGate6Dof ? 1 : 0;
  }
  s.nis = absStats(nis);
  s.nis_mean = nis.empty() ? 0.0 : s.nis_mean / static_cast<double>(nis.size());
}

}  // namespace

Evaluation evaluate(const PinholeCamera& camera, const PolygonModel& model,
                    const std::vector<TruthPose>& truth, const std::vector<ReplayRow>& replay,
                    const EvaluationOptions& options) {
  Evaluation ev;
  ev.envelope_px = options.envelope_px;
  const std::size_t n_env = options.envelope_px.size();
  std::unordered_map<std::int64_t, const ReplayRow*> by_frame;
  for (const ReplayRow& r : replay) by_frame[r.frame] = &r;

  EnvelopeSolver solver(camera, model, options.envelope);
  EvaluationSummary& s = ev.summary;
  s.envelopes.resize(n_env);
  for (std::size_t d = 0; d < n_env; ++d) s.envelopes[d].delta_px = options.envelope_px[d];
  std::vector<std::vector<double>> axis_errors(kAxisCount);
  std::vector<double> attitude_errors;
  const int stride = options.envelope_stride < 1 ? 1 : options.envelope_stride;
  int matched = 0;

  ev.frames.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const TruthPose& t = truth[i];
    FrameRecord rec;
    rec.frame = t.frame;
    rec.timestamp_ns = t.timestamp_ns;
    rec.distance_m = t.pose.t_c_m.z();
    const auto it = by_frame.find(t.frame);
    if (it != by_frame.end()) {
      ++matched;
      rec.status = it->second->status;
      rec.mode = it->second->mode;
      scoreFarRange(*it->second, t.pose, rec);
      if (isTracked(rec.status) && it->second->has_pose) {
        rec.scored = true;
        Pose reference = t.pose;
        double best_deg = attitudeErrorDeg(it->second->pose, t.pose);
        for (const Mat3& symmetry : options.model_symmetries) {
          Pose twin = t.pose;
          twin.R_c_m = t.pose.R_c_m * symmetry;
          const double deg = attitudeErrorDeg(it->second->pose, twin);
          if (deg < best_deg) {
            best_deg = deg;
            reference = twin;
          }
        }
        rec.error = poseError(it->second->pose, reference);
        rec.attitude_error_deg = best_deg;
        for (int a = 0; a < kAxisCount; ++a) axis_errors[a].push_back(rec.error[a]);
        attitude_errors.push_back(rec.attitude_error_deg);
      }
    }
    switch (rec.status) {
      case TrackStatus::kTracking: ++s.frames_tracking; break;
      case TrackStatus::kDegraded: ++s.frames_degraded; break;
      case TrackStatus::kLost: ++s.frames_lost; break;
      case TrackStatus::kInit: ++s.frames_init; break;
      case TrackStatus::kMissing: ++s.frames_missing; break;
    }
    if (i % static_cast<std::size_t>(stride) == 0 && n_env > 0) {
      solver.compute(t.pose, options.envelope_px, rec.envelopes);
    } else {
      rec.envelopes.assign(n_env, FrameEnvelope{});
    }
    rec.inside.assign(n_env, 0);
    for (std::size_t d = 0; d < n_env; ++d) {
      const FrameEnvelope& env = rec.envelopes[d];
      if (!env.valid) continue;
      EnvelopeSummary& es = s.envelopes[d];
      ++es.frames_with_envelope;
      es.failed_solves += env.failed_solves;
      bool inside = rec.scored;
      for (int a = 0; a < kAxisCount; ++a) {
        es.max_envelope[a] = std::max(es.max_envelope[a], env.max_abs[a]);
        if (std::fabs(rec.error[a]) > env.max_abs[a]) inside = false;
      }
      rec.inside[d] = inside ? 1 : 0;
      if (inside) ++es.inside_count;
    }
    ev.frames.push_back(std::move(rec));
  }
  s.frames_evaluated = static_cast<int>(truth.size());
  s.track_loss_count = s.frames_lost + s.frames_missing;
  s.unmatched_replay_rows = static_cast<int>(replay.size()) - matched;
  for (int a = 0; a < kAxisCount; ++a) s.axes[a] = absStats(axis_errors[a]);
  s.attitude = absStats(attitude_errors);
  for (EnvelopeSummary& es : s.envelopes)
    es.inside_fraction =
        es.frames_with_envelope > 0 ? static_cast<double>(es.inside_count) / es.frames_with_envelope : 0.0;
  summariseModesAndFarRange(replay, ev.frames, s);
  return ev;
}

const char* nothingToScore(const EvaluationSummary& summary) {
  if (summary.frames_evaluated == 0) return "the sequence has no truth frame to score against";
  if (summary.frames_missing == summary.frames_evaluated)
    return "the replay has no row for any truth frame (empty replay?): nothing to score";
  return nullptr;
}

int envelopeIndex(const Evaluation& evaluation, double delta_px) {
  for (std::size_t d = 0; d < evaluation.envelope_px.size(); ++d)
    if (std::fabs(evaluation.envelope_px[d] - delta_px) < 1e-12) return static_cast<int>(d);
  return -1;
}

std::string insideLine(const EnvelopeSummary& s) {
  char buf[160];
  std::snprintf(buf, sizeof(buf), "inside %g px envelope (all 6 axes): %.2f%% (%d/%d)", s.delta_px,
                100.0 * s.inside_fraction, s.inside_count, s.frames_with_envelope);
  return buf;
}

}  // namespace visnav::eval
