#include "visnav/campaign/runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "visnav/core/frame.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/navigation/fdir_monitor.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::campaign {
namespace {

constexpr std::size_t kMaxTransitionRecords = 64;

// FrameOutcome::oracle from the truth-started tracker's result: a fit the pipeline could deliver (not lost,
// the image evidence good, certain by [navigation] max_valid_*_sigma) and right by the campaign's
// confidently-wrong thresholds.
int oracleVerdict(const NearRangeResult& o, const nav::PoseSigmas& sigma, const Pose& truth,
                  const Scene& scene, const nav::NavigationParams& navigation, const Thresholds& th) {
  if (o.status == TrackStatus::kLost || !nav::imageEvidenceGood(o, navigation)) return 0;
  const bool right =
      !poseErrorIsWrong((o.pose.t_c_m - truth.t_c_m).norm(), truth.t_c_m.norm(),
                        attitudeErrorModuloDeg(o.pose.R_c_m, truth.R_c_m, scene.symmetries), th);
  const bool certain = (navigation.max_valid_attitude_sigma_deg <= 0.0 ||
                        sigma.attitude_deg <= navigation.max_valid_attitude_sigma_deg) &&
                       (navigation.max_valid_position_sigma_rel <= 0.0 ||
                        sigma.position_rel <= navigation.max_valid_position_sigma_rel);
  return right && certain ? 2 : 1;
}

// The far fix's line of sight against the model origin's [deg].
double farDirectionErrorDeg(const far::FarRangeResult& fr, const Pose& truth) {
  return std::acos(std::clamp(fr.direction_c.dot(truth.t_c_m.normalized()), -1.0, 1.0)) * kDegPerRad;
}

// The target's angular radius (its bounding sphere) seen from the camera [deg].
double targetAngularRadiusDeg(const Scene& scene, const Pose& truth) {
  return std::atan(scene.model.boundingRadius() / truth.t_c_m.norm()) * kDegPerRad;
}

// --dump-frames: one 8-bit binary PGM per frame.
bool dumpFrame(const std::string& dir, const Scene& scene, int index, const std::uint8_t* pixels, int w,
               int h) {
  std::string name = scene.name;
  std::replace(name.begin(), name.end(), '/', '-');
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%04d.pgm", index);
  std::ofstream out(dir + "/" + name + suffix, std::ios::binary);
  out << "P5\n" << w << " " << h << "\n255\n";
  out.write(reinterpret_cast<const char*>(pixels), static_cast<std::streamsize>(w) * h);
  return static_cast<bool>(out);
}

}  // namespace

void summariseScene(const Scene& scene, const Thresholds& th, SceneResult& r) {
  r.visible = r.expected = r.tracked = r.accurate = r.wrong = r.pose_frames = 0;
  r.max_position_error_rel = r.max_attitude_error_deg = 0.0;
  r.nis_count = 0;
  r.far_fixes = r.far_off_target = 0;
  double nis_sum = 0.0;
  int first_expected = -1;
  for (FrameOutcome& f : r.frames) {
    // Approach scenes: a 6-DOF pose is due within the near band (truth depth <= th.near_range_max_m).
    f.expected = f.visible && (!scene.approach || scene.truth(f.frame).t_c_m.z() <= th.near_range_max_m);
    r.visible += f.visible ? 1 : 0;
    if (f.expected) {
      if (first_expected < 0) first_expected = f.frame;
      ++r.expected;
      r.tracked += f.tracked ? 1 : 0;
      r.accurate += f.accurate ? 1 : 0;
    }
    r.wrong += f.wrong ? 1 : 0;
    if (f.pose_valid) {
      ++r.pose_frames;
      r.max_position_error_rel = std::max(r.max_position_error_rel, f.position_error_m / f.range_m);
      r.max_attitude_error_deg = std::max(r.max_attitude_error_deg, f.attitude_error_deg);
    }
    if (f.has_nis) {
      ++r.nis_count;
      nis_sum += f.nis;
    }
    if (f.in_view && f.far_valid) {
      ++r.far_fixes;
      r.far_off_target += f.far_off_target ? 1 : 0;
    }
  }
  r.nis_mean = r.nis_count > 0 ? nis_sum / r.nis_count : 0.0;
  r.tracked_fraction = r.expected > 0 ? static_cast<double>(r.tracked) / r.expected : -1.0;
  r.accurate_fraction = r.expected > 0 ? static_cast<double>(r.accurate) / r.expected : -1.0;
  r.events = recoveryEvents(r.frames, !scene.approach);
  r.recovery_never = 0;
  r.recovery_max = -1;
  for (const RecoveryEvent& e : r.events) {
    if (e.latency < 0)
      ++r.recovery_never;
    else
      r.recovery_max = std::max(r.recovery_max, e.latency);
  }
  r.acquisition_latency = -2;
  if (scene.approach && first_expected >= 0) {
    r.acquisition_latency = -1;
    for (std::size_t i = static_cast<std::size_t>(first_expected); i < r.frames.size(); ++i)
      if (r.frames[i].tracked) {
        r.acquisition_latency = static_cast<int>(i) - first_expected;
        break;
      }
  }
}

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

SceneResult runScene(const Scene& scene, const nav::PipelineParams& base, bool timing, const Thresholds& th,
                     bool trace, bool oracle_asked, const std::string& dump_dir) {
  SceneResult res;
  const std::int64_t wall_start = timing ? exec::monotonicNowNs() : 0;
  const PinholeCamera camera(scene.camera);
  synthetic::Renderer renderer;
  if (LoadError e = renderer.init(camera, scene.model, scene.render); !e.ok) {
    res.error = LoadError::failure(scene.name + ": " + e.message);
    return res;
  }
  nav::PipelineParams params = base;
  params.farrange.gamma = scene.gamma;  // calibrated for this target and camera, as a user would
  auto pipeline = std::make_unique<nav::NavigationPipeline>();
  if (LoadError e = pipeline->init(camera, scene.model, params); !e.ok) {
    res.error = LoadError::failure(scene.name + ": pipeline: " + e.message);
    return res;
  }
  if (timing) pipeline->setClock(&exec::monotonicNowNs);
  // --trace / --oracle: on every visible frame without a valid pose, a tracker started at the truth says
  // whether the image supports the pose at all (the frame is then a search's or a gate's loss, not the
  // image's).
  std::unique_ptr<NearRangeTracker> oracle;
  if (trace || oracle_asked) {
    oracle = std::make_unique<NearRangeTracker>();
    if (!oracle->init(camera, scene.model, params.nearrange).ok) oracle.reset();
  }
  if (!scene.approach) pipeline->startNearRange(scene.truth(0), 0);
  const std::uint64_t transitions_start = pipeline->modes().transitionCount();

  const int w = scene.camera.width_px;
  const int h = scene.camera.height_px;
  std::vector<std::uint8_t> image(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  res.frames.resize(static_cast<std::size_t>(scene.frames));
  Pose hidden;  // eclipse: the target is drawn behind the camera, the background stays
  hidden.t_c_m = Vec3(0.0, 0.0, -1000.0);
  for (int i = 0; i < scene.frames; ++i) {
    const Pose truth = scene.truth(i);
    const bool eclipsed = scene.eclipsed(i);
    const std::int64_t t_ns = scene.timestampNs(i);
    renderer.setFrameIndex(i);
    renderer.render(eclipsed ? hidden : truth,
                    synthetic::Renderer::frameSeed(scene.noise_seed, static_cast<std::uint64_t>(i)),
                    image.data(), w);
    if (!dump_dir.empty() && !dumpFrame(dump_dir, scene, i, image.data(), w, h)) {
      res.error =
          LoadError::failure(scene.name + ": cannot write frame " + std::to_string(i) + " to " + dump_dir);
      return res;
    }
    Frame frame;
    frame.image = MonoImage::from8(ImageView8(image.data(), w, h));
    frame.exposure_time_ns = t_ns;
    frame.sequence = static_cast<std::uint64_t>(i);
    const std::uint64_t transitions_before = pipeline->modes().transitionCount();
    nav::NavSolution sol;
    pipeline->process(&frame, t_ns, sol);  // simulated clock: processed at its exposure time

    FrameOutcome& f = res.frames[static_cast<std::size_t>(i)];
    f.frame = i;
    f.eclipsed = eclipsed;
    f.slew = scene.events.slew && i == scene.events.slew_frame;
    f.visible = targetVisible(camera, scene.model, truth, eclipsed, th);
    f.in_view = targetInView(camera, truth, eclipsed);
    f.range_m = truth.t_c_m.norm();
    f.mode = sol.mode;
    f.pose_valid = sol.pose_valid;
    f.fault_bits = sol.fault_bits;
    if (sol.pose_valid) {
      f.position_error_m = (sol.pose.t_c_m - truth.t_c_m).norm();
      f.attitude_error_deg = attitudeErrorModuloDeg(sol.pose.R_c_m, truth.R_c_m, scene.symmetries);
    }
    // Delivered or withheld 6-DOF measurement (deliver() sets a covariance and a quality > 0; coasting
    // sets quality 0).
    f.has_candidate = sol.quality > 0.0 && sol.covariance(0, 0) > 0.0;
    if (f.has_candidate) {
      f.candidate_position_error_m = (sol.pose.t_c_m - truth.t_c_m).norm();
      f.candidate_range_m = sol.pose.t_c_m.norm();
      f.candidate_attitude_error_deg = attitudeErrorModuloDeg(sol.pose.R_c_m, truth.R_c_m, scene.symmetries);
      const nav::PoseSigmas sigma = nav::poseSigmas(sol.pose, sol.covariance);  // as the pipeline judged it
      f.attitude_sigma_deg = sigma.attitude_deg;
      f.position_sigma_rel = sigma.position_rel;
    }
    f.near_flags = pipeline->lastNearRange().flags;
    f.withheld = sol.withheld;
    if (f.has_candidate && sol.mode == nav::NavMode::kNearRange) {
      const NearRangeResult& near = pipeline->lastNearRange();
      f.systematic_gain = near.systematic_gain;
      f.cov_residual_factor = near.covariance_terms.residual_factor;
      f.cov_vertex_factor = near.covariance_terms.vertex_factor;
      f.cov_bias_factor_per_px2 = near.covariance_terms.bias_factor_per_px2;
      f.cov_interior_factor_per_px2 = near.covariance_terms.interior_factor_per_px2;
      f.cov_narrow_factor_per_px2 = near.covariance_terms.narrow_factor_per_px2;
    }
    f.lines_used = pipeline->lastNearRange().lines_used;
    f.lines_total = pipeline->lastNearRange().lines_total;
    f.scanlines = pipeline->lastNearRange().scanlines;
    f.inlier_points = pipeline->lastNearRange().inlier_points;
    f.evidence_good = nav::imageEvidenceGood(pipeline->lastNearRange(), params.navigation);
    f.reacquired = pipeline->lastReacquisition().found;
    f.symmetric_twins = sol.symmetric_twins;
    f.shows_face = pipeline->lastPoseShowedAFace();
    f.twin_by_continuity = sol.twin_by_continuity;
    f.kept_branch = pipeline->lastFitKeptTheBranch();
    f.mirror_resolved = pipeline->lastMirrorResolved();
    f.pose_filtered = pipeline->lastPoseFiltered();
    f.fit_attitude_sigma_deg = pipeline->lastFitAttitudeSigmaDeg();
    f.narrow_break = pipeline->lastFollowedNarrowBreak();
    f.near_twin_rival = pipeline->lastNearTwinRival();
    f.find_on_branch = !f.reacquired || pipeline->lastFindOnKnownBranch();
    f.jumped = pipeline->lastPoseJumped();
    f.range_broken = pipeline->lastFitBrokeRange();
    const nav::FilterUpdate& u = pipeline->lastPoseUpdate();
    if (u.status == Status::kOk && u.dof == 6) {
      f.has_nis = true;
      f.nis = u.nis;
    }
    f.process_us = sol.timing.process_us;
    f.far_valid = sol.far.valid;
    f.far_distance_m = sol.far.distance_m;
    if (f.far_valid) {
      f.far_eq16_distance_m = pipeline->lastFarRange().eq16_distance_m;
      f.far_extent_px = pipeline->lastFarRange().extent_px;
      f.far_extent_distance_m = pipeline->lastFarRange().extent_distance_m;
      f.far_direction_error_deg = farDirectionErrorDeg(pipeline->lastFarRange(), truth);
      f.far_off_target = f.in_view && f.far_direction_error_deg >
                                          targetAngularRadiusDeg(scene, truth) + th.far_on_target_margin_deg;
    }
    classifyFrame(f, th);
    NearRangeResult o;
    nav::PoseSigmas oracle_sigma;
    if (oracle && f.visible && !f.pose_valid) {
      oracle->reset();
      oracle->track(frame.image, truth, static_cast<std::uint64_t>(i), o);
      oracle_sigma = nav::poseSigmas(o.pose, o.covariance);
      f.oracle = oracleVerdict(o, oracle_sigma, truth, scene, params.navigation, th);
      f.oracle_evidence = static_cast<int>(nav::imageEvidenceVerdict(o, params.navigation));
    }
    if (trace) {
      res.trace += traceLine(f, pipeline->lastNearRange(), u);
      if (f.oracle >= 0) {
        const nav::PoseSigmas& sigma = oracle_sigma;
        char buf[260];
        std::snprintf(
            buf, sizeof buf,
            "       oracle: near=%d good=%d lines=%d/%d rms=%.3f sa=%.2f dp=%.3f da=%.2f flags=%04x "
            "in=%d pts=%d scan=%d\n",
            static_cast<int>(o.status),
            o.status != TrackStatus::kLost && nav::imageEvidenceGood(o, params.navigation) ? 1 : 0,
            o.lines_used, o.lines_total, o.rms_px, sigma.attitude_deg,
            (o.pose.t_c_m - truth.t_c_m).norm() / f.range_m,
            attitudeErrorModuloDeg(o.pose.R_c_m, truth.R_c_m, scene.symmetries), o.flags, o.inlier_points,
            o.edge_points, o.scanlines);
        res.trace += buf;
        if (o.lines_total > 0)
          res.trace += "       oracle" + traceEdges(*oracle, o.pose, truth, scene.symmetries);
      }
      if (pipeline->lastNearRange().lines_total > 0)
        res.trace += "      " + traceEdges(pipeline->nearRange(), pipeline->lastNearRange().pose, truth,
                                           scene.symmetries);
      if (pipeline->filter().initialised()) {
        char buf[160];
        std::snprintf(
            buf, sizeof buf, "       filter: v=%.3f m/s w=%.2f deg/s, prediction for the next frame\n",
            pipeline->filter().velocity().norm(), pipeline->filter().angularVelocity().norm() * kDegPerRad);
        res.trace += buf;
      }
      if (f.mode == nav::NavMode::kAcquisition) {
        const acq::AcquisitionResult& a = pipeline->lastAcquisition();
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "       acquisition: state=%d failure=%s hyp=%d/%d verified=%d best=%.3f snr=%.1f\n",
                      static_cast<int>(a.state), acq::toString(a.failure), a.hypotheses_done,
                      a.hypotheses_total, a.candidates_verified, a.best_score, a.edge_snr);
        res.trace += buf;
        if (a.state == acq::AcquisitionState::kConfirming || a.state == acq::AcquisitionState::kSucceeded) {
          // The candidate against the truth, and its rival and depth-reversed twins: which one was right.
          const acq::Acquisition& acquisition = pipeline->acquisition();
          const ModelSymmetries& sym = acquisition.symmetries();
          std::snprintf(buf, sizeof buf, "       candidate: dp=%.3f da=%.2f",
                        (a.pose.t_c_m - truth.t_c_m).norm(),
                        attitudeErrorModuloDeg(a.pose.R_c_m, truth.R_c_m, scene.symmetries));
          res.trace += buf;
          if (acquisition.rivalAlive()) {
            std::snprintf(
                buf, sizeof buf, " rival: dp=%.3f da=%.2f",
                (acquisition.rivalPose().t_c_m - truth.t_c_m).norm(),
                attitudeErrorModuloDeg(acquisition.rivalPose().R_c_m, truth.R_c_m, scene.symmetries));
            res.trace += buf;
          }
          if (acquisition.mirrorAlive()) {
            std::snprintf(
                buf, sizeof buf, " twin rival: da=%.2f",
                attitudeErrorModuloDeg(acquisition.mirrorPose().R_c_m, truth.R_c_m, scene.symmetries));
            res.trace += buf;
          }
          for (int m = 0; m < sym.mirrorCount(); ++m) {
            const Pose twin = sym.mirrorTwin(a.pose, m);
            std::snprintf(buf, sizeof buf, " mirror%d: da=%.2f", m,
                          attitudeErrorModuloDeg(twin.R_c_m, truth.R_c_m, scene.symmetries));
            res.trace += buf;
          }
          res.trace += "\n";
        }
      }
      if (f.mode == nav::NavMode::kFarRange) {
        const far::FarRangeResult& fr = pipeline->lastFarRange();
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
                      static_cast<unsigned long long>(pipeline->modes().refusedHandOvers()));
        res.trace += buf;
      }
      const nav::ReacquisitionStep& rs = pipeline->lastReacquisition();
      if (rs.hypotheses > 0 || rs.candidate || rs.found) {
        // Where the search looked against where the target is, in image pixels: the prediction's centre (can
        // the grid reach the target at all?) and the outline cue's best match from where this frame's search
        // started (the prediction, the rate rung, the motion hedge's held position); -1: not projected, no
        // cue.
        const Pose predicted = pipeline->predictedPose();
        Vec2 truth_px, predicted_px, cue_offset_px, searched_px;
        const bool centres =
            camera.project(truth.t_c_m, truth_px) && camera.project(predicted.t_c_m, predicted_px);
        const double predicted_off_px = centres ? (predicted_px - truth_px).norm() : -1.0;
        const bool searched = centres && camera.project(rs.searched_t_c_m, searched_px);
        const double cue_off_px = searched && pipeline->reacquisition().bestCueOffset(cue_offset_px)
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
            rs.starts_inconsistent, rs.ambiguous ? 1 : 0, rs.candidate ? 1 : 0, rs.found ? 1 : 0,
            rs.best_quality, (predicted.t_c_m - truth.t_c_m).norm(),
            attitudeErrorModuloDeg(predicted.R_c_m, truth.R_c_m, scene.symmetries),
            std::acos(std::clamp(predicted.t_c_m.normalized().dot(truth.t_c_m.normalized()), -1.0, 1.0)) *
                kDegPerRad,
            predicted.t_c_m.norm() / truth.t_c_m.norm() - 1.0,
            (pipeline->lastTrustedPose().t_c_m - truth.t_c_m).norm(),
            attitudeErrorModuloDeg(pipeline->lastTrustedPose().R_c_m, truth.R_c_m, scene.symmetries),
            rs.acquisition_state, rs.acquisition_failure, rs.acquisition_edge_snr, rs.far_cue ? 1 : 0,
            rs.outline_cue ? 1 : 0, predicted_off_px, cue_off_px, rs.rate_rung_range_m,
            rs.motion_hedge ? 1 : 0, rs.by_acquisition ? " (found by acquisition)" : "",
            rs.twin_by_continuity ? " (near twin told apart by continuity)" : "");
        res.trace += buf;
      }
    }
    if (pipeline->modes().transitionCount() != transitions_before &&
        res.transitions.size() < kMaxTransitionRecords) {
      const nav::ModeTransition& t = pipeline->modes().lastTransition();
      res.transitions.push_back({i, t.from, t.to, std::string(t.reason.data())});
    }
  }
  res.mode_changes = static_cast<int>(pipeline->modes().transitionCount() - transitions_start);
  summariseScene(scene, th, res);
  if (timing) res.wall_s = static_cast<double>(exec::monotonicNowNs() - wall_start) * 1e-9;
  return res;
}

}  // namespace visnav::campaign
