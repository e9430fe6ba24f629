// --trace: the per-frame text of visnav-campaign (tools/campaign/README.md, "Trace"). The run loop that
// fills the inputs: runner.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trace_parts.hpp"

namespace visnav::campaign {
namespace {

// How the truth shows a model edge: 'i' interior (both faces front-facing), 'o' on the outline (one, or an
// open edge of a front face), 'h' hidden (no front face).
char edgeKindSeen(const PolygonModel& model, const ModelEdge& edge, const Pose& truth) {
  const auto front = [&model, &truth](int surface) {
    if (surface < 0) return false;
    const ModelSurface& s = model.surfaces()[static_cast<std::size_t>(surface)];
    return (truth.R_c_m * s.normal_m).dot(truth.transform(s.centroid_m)) < 0.0;
  };
  const int fronts = (front(edge.surface_left) ? 1 : 0) + (front(edge.surface_right) ? 1 : 0);
  return fronts == 2 ? 'i' : (fronts == 1 ? 'o' : 'h');
}

std::string traceEdges(const NearRangeTracker& tracker, const Pose& fit, const Pose& truth_pose,
                       const std::vector<Symmetry>& symmetries) {
  // Each measured edge: model edge, points, and the fitted line's distance (ideal px) from the edge's true
  // projection at both ends, and after "|" the 1-sigma the tracker gave those ends (its end_variance_px2);
  // a line far from the truth is what a wrong fit was built on. The truth is taken as the twin the fit is
  // nearest to: on a symmetric model the fit's edge k is the twin's edge k (before 2026-12-04 the plain
  // truth: a box fitted on its z180 twin showed every edge ~50 px off, box/7035).
  Pose truth = truth_pose;
  truth.R_c_m = nearestTwinOfTruth(fit.R_c_m, truth_pose.R_c_m, symmetries);
  std::string out = " edges:";
  const PolygonModel& model = tracker.model();
  const BoundedBuffer<EdgeMeasurement>& edges = tracker.lastEdges();
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const EdgeMeasurement& e = edges[i];
    const ModelEdge& me = model.edges()[static_cast<std::size_t>(e.model_edge)];
    Vec2 a;
    Vec2 b;
    const bool projected =
        tracker.camera().projectIdeal(truth.transform(model.vertices()[static_cast<std::size_t>(me.v0)]),
                                      a) &&
        tracker.camera().projectIdeal(truth.transform(model.vertices()[static_cast<std::size_t>(me.v1)]), b);
    const char kind = edgeKindSeen(model, me, truth);
    const char* confusable = e.confusable ? "*" : "";
    char buf[80];
    if (e.line_ok && projected)
      std::snprintf(buf, sizeof buf, " %d%c%s:%d(%.2f,%.2f|%.2f)", e.model_edge, kind, confusable,
                    e.point_count, e.line.signedDistance(a), e.line.signedDistance(b),
                    std::sqrt(e.end_variance_px2));
    else
      std::snprintf(buf, sizeof buf, " %d%c%s:%d(-)", e.model_edge, kind, confusable, e.point_count);
    out += buf;
  }
  return out + "\n";
}

// A verification that ended no_candidate: each refined candidate's error (dp m, da deg) and what the
// verifying tracker made of it (status, rms, quality, and the tracked pose's error), then the coarse
// search's best. A right refined candidate the tracker refused is a verification loss; none right, the
// search's.
std::string traceVerification(const acq::Acquisition& acquisition, const Pose& truth,
                              const std::vector<Symmetry>& symmetries) {
  const auto error = [&truth, &symmetries](const Pose& pose) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.2f,%.1f", (pose.t_c_m - truth.t_c_m).norm(),
                  attitudeErrorModuloDeg(pose.R_c_m, truth.R_c_m, symmetries));
    return std::string(buf);
  };
  std::string out = "       verify:";
  const BoundedBuffer<acq::AcquisitionCandidate>& refined = acquisition.refined();
  const BoundedBuffer<acq::AcquisitionVerifyPass>& passes = acquisition.verifyPasses();
  for (std::size_t i = 0; i < refined.size(); ++i) {
    out += " [" + error(refined[i].pose);
    if (i < passes.size()) {
      const acq::AcquisitionVerifyPass& v = passes[i];
      char buf[60];
      std::snprintf(buf, sizeof buf, "->s%d rms=%.2f q=%.2f ", static_cast<int>(v.status), v.rms_px,
                    v.quality);
      out += buf + error(v.pose);
    }
    out += "]";
  }
  out += "\n       coarse:";
  for (const acq::AcquisitionCandidate& c : acquisition.candidates()) out += " [" + error(c.pose) + "]";
  return out + "\n";
}

}  // namespace

std::string traceLine(const FrameOutcome& f, const NearRangeResult& near, const nav::FilterUpdate& update) {
  char buf[340];
  const int n = std::snprintf(
      buf, sizeof buf,
      "%4d r=%7.2f %-11s near=%d flags=%04x lines=%d/%d sil=%d scan=%d in=%d tex=%d weak=%d vtx=%d rms=%.3f "
      "q=%.2f sa=%.2f sp=%.3f nis=%s%.1f faults=%04x pose=%d wh=%02x dp=%.3f da=%.2f%s%s\n",
      f.frame, f.range_m, nav::toString(f.mode), static_cast<int>(near.status), near.flags, near.lines_used,
      near.lines_total, near.silhouette_lines, near.scanlines, near.inlier_points, near.texture_points,
      near.weak_step_points, near.vertices, near.rms_px, near.quality,
      std::sqrt(near.covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad,
      std::sqrt(near.covariance.bottomRightCorner<3, 3>().trace()) / std::max(f.range_m, 1e-9),
      update.status == Status::kOk ? "" : "-", update.status == Status::kOk ? update.nis : 0.0,
      static_cast<unsigned>(f.fault_bits), f.pose_valid ? 1 : 0, static_cast<unsigned>(f.withheld),
      f.pose_valid ? f.position_error_m / f.range_m : 0.0, f.pose_valid ? f.attitude_error_deg : 0.0,
      f.wrong ? " WRONG" : "", f.visible ? "" : " (not visible)");
  return std::string(buf,
                     static_cast<std::size_t>(std::max(0, std::min(n, static_cast<int>(sizeof buf) - 1))));
}

namespace detail {

double farDirectionErrorDeg(const far::FarRangeResult& fr, const Pose& truth) {
  return std::acos(std::clamp(fr.direction_c.dot(truth.t_c_m.normalized()), -1.0, 1.0)) * kDegPerRad;
}

double targetAngularRadiusDeg(const Scene& scene, const Pose& truth) {
  return std::atan(scene.model.boundingRadius() / truth.t_c_m.norm()) * kDegPerRad;
}

std::string traceFrame(const FrameTraceInputs& in) {
  const FrameOutcome& f = in.f;
  const nav::NavigationPipeline& pipeline = in.pipeline;
  const NearRangeResult& o = in.oracle_result;
  const Pose& truth = in.truth;
  const Scene& scene = in.scene;
  const PinholeCamera& camera = in.camera;
  std::string out = traceLine(f, pipeline.lastNearRange(), in.update);
  if (f.oracle >= 0 && in.oracle != nullptr) {
    const nav::PoseSigmas& sigma = in.oracle_sigma;
    char buf[260];
    std::snprintf(buf, sizeof buf,
                  "       oracle: near=%d good=%d lines=%d/%d rms=%.3f sa=%.2f dp=%.3f da=%.2f flags=%04x "
                  "in=%d pts=%d scan=%d\n",
                  static_cast<int>(o.status),
                  o.status != TrackStatus::kLost && nav::imageEvidenceGood(o, in.navigation) ? 1 : 0,
                  o.lines_used, o.lines_total, o.rms_px, sigma.attitude_deg,
                  (o.pose.t_c_m - truth.t_c_m).norm() / f.range_m,
                  attitudeErrorModuloDeg(o.pose.R_c_m, truth.R_c_m, scene.symmetries), o.flags,
                  o.inlier_points, o.edge_points, o.scanlines);
    out += buf;
    if (o.lines_total > 0) out += "       oracle" + traceEdges(*in.oracle, o.pose, truth, scene.symmetries);
  }
  if (pipeline.lastNearRange().lines_total > 0)
    out +=
        "      " + traceEdges(pipeline.nearRange(), pipeline.lastNearRange().pose, truth, scene.symmetries);
  if (pipeline.filter().initialised()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "       filter: v=%.3f m/s w=%.2f deg/s, prediction for the next frame\n",
                  pipeline.filter().velocity().norm(),
                  pipeline.filter().angularVelocity().norm() * kDegPerRad);
    out += buf;
  }
  // In its own mode, or beside far range (acquire_beside_far_range): the frame's result says it ran.
  if (f.mode == nav::NavMode::kAcquisition ||
      pipeline.lastAcquisition().state != acq::AcquisitionState::kIdle) {
    const acq::AcquisitionResult& a = pipeline.lastAcquisition();
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "       acquisition: state=%d failure=%s hyp=%d/%d verified=%d best=%.3f snr=%.1f\n",
                  static_cast<int>(a.state), acq::toString(a.failure), a.hypotheses_done, a.hypotheses_total,
                  a.candidates_verified, a.best_score, a.edge_snr);
    out += buf;
    if (a.state == acq::AcquisitionState::kConfirming || a.state == acq::AcquisitionState::kSucceeded) {
      // The candidate against the truth, and its rival and depth-reversed twins: which one was right.
      const acq::Acquisition& acquisition = pipeline.acquisition();
      const ModelSymmetries& sym = acquisition.symmetries();
      std::snprintf(buf, sizeof buf, "       candidate: dp=%.3f da=%.2f", (a.pose.t_c_m - truth.t_c_m).norm(),
                    attitudeErrorModuloDeg(a.pose.R_c_m, truth.R_c_m, scene.symmetries));
      out += buf;
      if (acquisition.rivalAlive()) {
        std::snprintf(buf, sizeof buf, " rival: dp=%.3f da=%.2f",
                      (acquisition.rivalPose().t_c_m - truth.t_c_m).norm(),
                      attitudeErrorModuloDeg(acquisition.rivalPose().R_c_m, truth.R_c_m, scene.symmetries));
        out += buf;
      }
      if (acquisition.mirrorAlive()) {
        std::snprintf(buf, sizeof buf, " twin rival: da=%.2f",
                      attitudeErrorModuloDeg(acquisition.mirrorPose().R_c_m, truth.R_c_m, scene.symmetries));
        out += buf;
      }
      for (int m = 0; m < sym.mirrorCount(); ++m) {
        const Pose twin = sym.mirrorTwin(a.pose, m);
        std::snprintf(buf, sizeof buf, " mirror%d: da=%.2f", m,
                      attitudeErrorModuloDeg(twin.R_c_m, truth.R_c_m, scene.symmetries));
        out += buf;
      }
      out += "\n";
    }
  }
  if (f.mode == nav::NavMode::kFarRange) {
    const far::FarRangeResult& fr = pipeline.lastFarRange();
    char buf[260];
    // dir_err: the fix's line of sight against the target's (deg); rad: the target's angular radius
    // (deg).
    const double dir_err_deg = farDirectionErrorDeg(fr, truth);
    const double radius_deg = targetAngularRadiusDeg(scene, truth);
    std::snprintf(buf, sizeof buf,
                  "       far: valid=%d n=%d raw=%d clusters=%d flags=%04x d=%.1f c=%.3f q=%.2f "
                  "dir_err=%.2fdeg rad=%.2fdeg sharp=%.2f refused=%llu\n",
                  fr.valid ? 1 : 0, fr.cluster_pixels, fr.raw_pixels, fr.cluster_count,
                  static_cast<unsigned>(fr.flags), fr.distance_m, fr.circularity, fr.quality, dir_err_deg,
                  radius_deg, fr.outline_sharpness,
                  static_cast<unsigned long long>(pipeline.modes().refusedHandOvers()));
    out += buf;
  }
  const nav::ReacquisitionStep& rs = pipeline.lastReacquisition();
  if (rs.hypotheses > 0 || rs.candidate || rs.found) {
    // Where the search looked against where the target is, in image pixels: the prediction's centre (can
    // the grid reach the target at all?) and the outline cue's best match from where this frame's search
    // started (the prediction, the rate rung, the motion hedge's held position); -1: not projected, no
    // cue.
    const Pose predicted = pipeline.predictedPose();
    Vec2 truth_px, predicted_px, cue_offset_px, searched_px;
    const bool centres =
        camera.project(truth.t_c_m, truth_px) && camera.project(predicted.t_c_m, predicted_px);
    const double predicted_off_px = centres ? (predicted_px - truth_px).norm() : -1.0;
    const bool searched = centres && camera.project(rs.searched_t_c_m, searched_px);
    const double cue_off_px = searched && pipeline.reacquisition().bestCueOffset(cue_offset_px)
                                  ? (searched_px + cue_offset_px - truth_px).norm()
                                  : -1.0;
    char buf[440];
    std::snprintf(
        buf, sizeof buf,
        "       reacq: starts=%d cue=%d radius=%dpx lost=%d weak=%d inconsistent=%d ambiguous=%d "
        "candidate=%d found=%d best_q=%.2f pred_dp=%.3f pred_da=%.2f pred_lat=%.1fdeg pred_rng=%.3f "
        "last_dp=%.3f last_da=%.2f acq=%d/%d snr=%.1f fcue=%d ocue=%d pred_off=%.0fpx cue_off=%.0fpx "
        "rung=%.2fm hold=%d%s%s\n",
        rs.hypotheses, rs.cue_starts, rs.search_radius_px, rs.starts_lost, rs.starts_weak,
        rs.starts_inconsistent, rs.ambiguous ? 1 : 0, rs.candidate ? 1 : 0, rs.found ? 1 : 0, rs.best_quality,
        (predicted.t_c_m - truth.t_c_m).norm(),
        attitudeErrorModuloDeg(predicted.R_c_m, truth.R_c_m, scene.symmetries),
        std::acos(std::clamp(predicted.t_c_m.normalized().dot(truth.t_c_m.normalized()), -1.0, 1.0)) *
            kDegPerRad,
        predicted.t_c_m.norm() / truth.t_c_m.norm() - 1.0,
        (pipeline.lastTrustedPose().t_c_m - truth.t_c_m).norm(),
        attitudeErrorModuloDeg(pipeline.lastTrustedPose().R_c_m, truth.R_c_m, scene.symmetries),
        rs.acquisition_state, rs.acquisition_failure, rs.acquisition_edge_snr, rs.far_cue ? 1 : 0,
        rs.outline_cue ? 1 : 0, predicted_off_px, cue_off_px, rs.rate_rung_range_m, rs.motion_hedge ? 1 : 0,
        rs.by_acquisition ? " (found by acquisition)" : "",
        rs.twin_by_continuity ? " (near twin told apart by continuity)" : "");
    out += buf;
    if (rs.acquisition_state == static_cast<int>(acq::AcquisitionState::kFailed) &&
        rs.acquisition_failure == static_cast<int>(acq::AcquisitionFailure::kNoCandidate))
      out += traceVerification(pipeline.acquisition(), truth, scene.symmetries);
  }
  return out;
}

}  // namespace detail
}  // namespace visnav::campaign
