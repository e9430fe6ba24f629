#include "visnav/campaign/runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "trace_parts.hpp"
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

// --dump-frames: one 8-bit binary PGM per frame.
bool dumpFrame(const std::string& dir, const Scene& scene, int index, const std::uint8_t* pixels, int w,
               int h) {
  std::string name = scene.name;
  std::replace(name.begin(), name.end(), '/', '-');
  char suffix[24];  // "-%04d.pgm" of any int: at most 17 bytes
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
      f.far_direction_error_deg = detail::farDirectionErrorDeg(pipeline->lastFarRange(), truth);
      f.far_off_target =
          f.in_view && f.far_direction_error_deg >
                           detail::targetAngularRadiusDeg(scene, truth) + th.far_on_target_margin_deg;
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
    if (trace)
      res.trace += detail::traceFrame(
          {f, *pipeline, u, oracle.get(), o, oracle_sigma, truth, scene, camera, params.navigation});
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
