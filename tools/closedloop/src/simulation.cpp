#include "visnav/closedloop/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "visnav/closedloop/chaser.hpp"
#include "visnav/closedloop/guidance.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/synthetic/renderer.hpp"
#include "visnav/visnav.h"

namespace visnav::closedloop {
namespace {

constexpr double kCollisionRange = 1.5;  ///< m: the plate's half diagonal; closer is a crash

struct VisnavHandle {
  visnav_handle* h = nullptr;
  ~VisnavHandle() { visnav_destroy(h); }
};

/// Where the run starts: the target's spin axis is world z, its face normal tilted nutation_deg from it
/// (about world y); the chaser on a direction start_offset_deg off the axis (about world x), at rest,
/// pointing at the target up to start_pointing_deg.
void initialState(const ScenarioParams& p, TargetMotion& target, ChaserState& chaser) {
  target.R_w_m0 = expSo3(Vec3::UnitY() * p.nutation_deg * kRadPerDeg);
  target.omega_w = Vec3::UnitZ() * p.tumble_rate_deg_s * kRadPerDeg;
  const Vec3 u = expSo3(Vec3::UnitX() * p.start_offset_deg * kRadPerDeg) * Vec3::UnitZ();
  chaser.p_w = u * p.start_range_m;
  chaser.R_w_c = expSo3(Vec3(1.0, 1.0, 0.0).normalized() * p.start_pointing_deg * kRadPerDeg) *
                 lookAt(chaser.p_w, Vec3::UnitX());
}

}  // namespace

LoadError runClosedLoop(const ScenarioParams& p, bool use_visnav, RunResult& out) {
  out = RunResult{};
  out.label = use_visnav ? "visnav" : "truth";
  CameraIntrinsics intrinsics;
  if (LoadError e = io::loadCamera(p.camera_path, intrinsics); !e.ok) return e;
  PolygonModel model;
  if (LoadError e = io::loadModel(p.model_path, model); !e.ok) return e;
  const PinholeCamera camera(intrinsics);
  auto renderer = std::make_unique<synthetic::Renderer>();
  std::vector<std::uint8_t> image;
  VisnavHandle nav;
  if (use_visnav) {
    if (LoadError e = renderer->init(camera, model, synthetic::RenderOptions{}); !e.ok) return e;
    image.assign(static_cast<std::size_t>(camera.width()) * camera.height(), 0);
    char err[512];
    if (visnav_create(p.config_path.c_str(), p.camera_path.c_str(), p.model_path.c_str(), &nav.h, err,
                      sizeof(err)) != VISNAV_OK)
      return LoadError::failure(std::string("visnav_create: ") + err);
  }
  TargetMotion target;
  ChaserState initial;
  initialState(p, target, initial);
  ChaserLimits limits;
  limits.accel_max_m_s2 = p.accel_max_m_s2;
  limits.rate_max_rad_s = p.rate_max_deg_s * kRadPerDeg;
  limits.angular_accel_max_rad_s2 = p.angular_accel_max_deg_s2 * kRadPerDeg;
  Chaser chaser(limits, initial);
  VisnavEstimator estimator;
  Guidance guidance(p);
  const double dt = 1.0 / p.frame_rate_hz;
  const Vec3 hold_m(0.0, 0.0, p.hold_distance_m);
  const int max_frames = static_cast<int>(std::ceil(p.max_time_s * p.frame_rate_hz));
  out.frames.reserve(static_cast<std::size_t>(max_frames) + 1);
  Vec3 applied_accel = Vec3::Zero();
  double streak_start = -1.0;
  double streak_dv = 0.0;
  out.ended = "time limit";
  for (int k = 0; k <= max_frames; ++k) {
    const double t = k * dt;
    const ChaserState& s = chaser.state();
    const Mat3 R_w_m = target.attitude(t);
    const Pose truth = relativePose(s, R_w_m);
    FrameLog log;
    log.t_s = t;
    log.range_m = s.p_w.norm();
    log.position_error_m = (s.p_w - R_w_m * hold_m).norm();
    log.attitude_error_deg = attitudeErrorModSymmetry(truth.R_c_m, holdRelativeAttitude()) * kDegPerRad;
    log.delta_v_m_s = s.delta_v_m_s;
    log.mode = -1;
    if (log.range_m < kCollisionRange) {
      out.frames.push_back(log);
      out.ended = "collision";
      break;
    }
    RelativeEstimate est;
    bool near_ok = false;
    if (use_visnav) {
      renderer->setFrameIndex(k);
      renderer->render(truth, synthetic::Renderer::frameSeed(p.seed, static_cast<std::uint64_t>(k)),
                       image.data(), camera.width());
      visnav_solution sol;
      const std::int64_t t_ns =
          static_cast<std::int64_t>(k) * static_cast<std::int64_t>(std::llround(dt * 1e9));
      if (visnav_step(nav.h, image.data(), camera.width(), camera.height(), 0, 8, t_ns, &sol) != VISNAV_OK)
        return LoadError::failure(std::string("visnav_step: ") + visnav_last_error(nav.h));
      estimator.update(sol, s.R_w_c, applied_accel, dt);
      est = estimator.estimate();
      near_ok = estimator.nearFramesInARow() >= p.near_frames_to_switch;
      log.mode = sol.mode;
      log.track_status = sol.track_status;
      if (est.position_valid) log.estimate_error_m = (est.p_w - s.p_w).norm();
    } else {  // the reference: the guidance sees the true relative state
      est.position_valid = true;
      est.p_w = s.p_w;
      est.v_w = s.v_w;
      est.attitude_valid = true;
      est.R_w_m = R_w_m;
      est.target_rate_w = target.omega_w;
      near_ok = log.range_m < 30.0;  // where visnav's acquisition hands over to near range
    }
    const Command cmd = guidance.command(est, near_ok, s.R_w_c, s.omega_w);
    log.phase = static_cast<int>(guidance.phase());
    out.frames.push_back(log);
    // Arrival: inside both gates without a break for the hold window.
    if (log.position_error_m < p.gate_position_m && log.attitude_error_deg < p.gate_attitude_deg) {
      if (streak_start < 0.0) {
        streak_start = t;
        streak_dv = s.delta_v_m_s;
      }
      if (t - streak_start >= p.hold_window_s) {
        out.arrived = true;
        out.ended = "held the hold point";
        break;
      }
    } else {
      streak_start = -1.0;
    }
    for (int i = 0; i < p.physics_substeps; ++i) chaser.step(cmd, dt / p.physics_substeps);
    const double n = cmd.accel_w.norm();
    applied_accel = n > p.accel_max_m_s2 ? Vec3(cmd.accel_w * (p.accel_max_m_s2 / n)) : cmd.accel_w;
  }
  const FrameLog& last = out.frames.back();
  out.final_position_error_m = last.position_error_m;
  out.final_attitude_error_deg = last.attitude_error_deg;
  out.total_delta_v_m_s = last.delta_v_m_s;
  out.estimator_rejections = static_cast<int>(estimator.rejected());
  if (out.arrived) {
    out.arrival_time_s = streak_start;
    out.arrival_delta_v_m_s = streak_dv;
    for (const FrameLog& f : out.frames) {
      if (f.t_s < streak_start) continue;
      out.hold_max_position_error_m = std::max(out.hold_max_position_error_m, f.position_error_m);
      out.hold_max_attitude_error_deg = std::max(out.hold_max_attitude_error_deg, f.attitude_error_deg);
    }
  }
  return LoadError::success();
}

}  // namespace visnav::closedloop
