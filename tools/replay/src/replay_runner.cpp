#include "visnav/replay_tool/replay_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <vector>

#include "visnav/app/visnav_config.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/config_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/replay/sequence.hpp"
#include "visnav/replay_tool/overlay.hpp"

namespace visnav::replay_tool {
namespace {

void writeHeader(std::FILE* f) {
  std::fputs(
      "frame,timestamp_ns,status,flags,mode,quality,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg", f);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) std::fprintf(f, ",cov_%d_%d", i, j);
  std::fputs(
      ",tracked_surfaces,surface_mask,lines_total,lines_used,edge_points,inlier_points,texture_points,"
      "vertices,rms_px,lm_iterations,t_project_us,t_scan_us,t_ransac_us,t_pose_us,t_total_us,"
      "fault_bits,far_valid,far_azimuth_deg,far_elevation_deg,far_distance_m,far_cluster_px,far_circularity,"
      "far_clusters,nis,symmetric_twins,twin_by_continuity\n",
      f);
}

/// Status column: the near-range verdict in near range, "lost" when the pipeline did not deliver the pose (a
/// coasted frame, a disputed or too uncertain measurement: as telemetry says), "init" while the 6-DOF track
/// does not exist yet (standby, far range, acquisition).
const char* statusText(const nav::NavSolution& sol, const NearRangeResult& near) {
  if (sol.mode != nav::NavMode::kNearRange) return "init";
  if (!sol.pose_valid) return toString(TrackStatus::kLost);
  return toString(near.status);
}

void writeRow(std::FILE* f, std::int64_t frame, std::int64_t timestamp_ns, const nav::NavSolution& sol,
              const NearRangeResult& near_in, const nav::FilterUpdate& pose_update) {
  // Near-range details only for frames the tracker ran on.
  const NearRangeResult near = sol.mode == nav::NavMode::kNearRange ? near_in : NearRangeResult{};
  std::fprintf(f, "%lld,%lld,%s,%u,%s,%.6f", static_cast<long long>(frame),
               static_cast<long long>(timestamp_ns), statusText(sol, near), near.flags,
               nav::toString(sol.mode), sol.quality);
  if (sol.pose_valid) {
    Eigen::Quaterniond q = sol.pose.quaternion();
    if (q.w() < 0.0) q.coeffs() *= -1.0;  // CONVENTIONS.md: w >= 0
    const YawPitchRoll ypr = sol.pose.ypr();
    const Vec3& t = sol.pose.t_c_m;
    std::fprintf(f, ",%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g", t.x(), t.y(), t.z(),
                 q.w(), q.x(), q.y(), q.z(), ypr.yaw_rad * kDegPerRad, ypr.pitch_rad * kDegPerRad,
                 ypr.roll_rad * kDegPerRad);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.6g", sol.covariance(i, j));
  } else {
    for (int i = 0; i < 10 + 36; ++i) std::fputc(',', f);  // no 6-DOF pose: empty fields
  }
  std::fprintf(f, ",%d,%llu,%d,%d,%d,%d,%d,%d,%.6f,%d,%.2f,%.2f,%.2f,%.2f,%.2f", near.tracked_surfaces,
               static_cast<unsigned long long>(near.tracked_surface_mask), near.lines_total, near.lines_used,
               near.edge_points, near.inlier_points, near.texture_points, near.vertices, near.rms_px,
               near.lm_iterations, near.timing.project_us, near.timing.scan_us, near.timing.ransac_us,
               near.timing.pose_us, sol.timing.process_us);
  const nav::FarRangeSolution& far = sol.far;
  std::fprintf(f, ",%u,%d,%.9g,%.9g,%.9g,%d,%.6f,%d,", sol.fault_bits, far.valid ? 1 : 0,
               far.azimuth_rad * kDegPerRad, far.elevation_rad * kDegPerRad, far.distance_m,
               far.cluster_pixels, far.circularity, far.cluster_count);
  // The filter's NIS for this frame's 6-DOF update (empty when there was none): what its gate judged.
  if (pose_update.status == Status::kOk && pose_update.dof == 6) std::fprintf(f, "%.6g", pose_update.nis);
  std::fprintf(f, ",%d,%d\n", sol.symmetric_twins, sol.twin_by_continuity ? 1 : 0);
}

void drawProgress(int done, int total, const ReplaySummary& s) {
  constexpr int kWidth = 40;
  const int filled = total > 0 ? done * kWidth / total : kWidth;
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\r[%s] %d/%d  tracking %d degraded %d lost %d", bar, done, total, s.tracking,
               s.degraded, s.lost);
  if (done == total) std::fputc('\n', stderr);
}

}  // namespace

bool parsePoseArgument(const std::string& text, Pose& out) {
  std::istringstream in(text);
  double v[6];
  char comma = 0;
  for (int i = 0; i < 6; ++i) {
    if (!(in >> v[i])) return false;
    if (i < 5 && (!(in >> comma) || comma != ',')) return false;
  }
  std::string rest;
  if (in >> rest) return false;
  for (double x : v)
    if (!std::isfinite(x)) return false;
  out = Pose::fromYpr({v[3] * kRadPerDeg, v[4] * kRadPerDeg, v[5] * kRadPerDeg}, Vec3(v[0], v[1], v[2]));
  return true;
}

LoadError runReplay(const ReplayOptions& options, ReplaySummary& summary) {
  summary = ReplaySummary{};
  replay::Sequence sequence;
  if (LoadError e = replay::loadSequence(options.sequence_dir, sequence); !e.ok) return e;
  CameraIntrinsics intrinsics = sequence.camera;
  if (!options.camera_path.empty())
    if (LoadError e = io::loadCamera(options.camera_path, intrinsics); !e.ok) return e;
  PolygonModel model = sequence.model;
  if (!options.model_path.empty())
    if (LoadError e = io::loadModel(options.model_path, model); !e.ok) return e;
  nav::PipelineParams params;
  if (!options.config_path.empty()) {
    // visnavd's whole-config loader (fsw/app): every table is checked (a typo anywhere is an error), the
    // pipeline tables are used, the others ([camera], [executive], [telemetry], ...) are ignored here.
    app::VisnavConfig config;
    if (LoadError e = app::loadVisnavConfig(options.config_path, config); !e.ok) return e;
    params = config.pipeline;
  }
  if (options.override_residual) params.nearrange.pose_residual = static_cast<int>(options.residual);

  nav::NavigationPipeline pipeline;
  if (LoadError e = pipeline.init(PinholeCamera(intrinsics), model, params); !e.ok) return e;
  if (options.timing) pipeline.setClock(&exec::monotonicNowNs);
  using Start = ReplayOptions::Start;
  if (options.start == Start::kInitialPose) {
    pipeline.startNearRange(options.initial_pose, 0);
  } else if (options.start == Start::kFirstTruth) {
    if (sequence.truth.empty())
      return LoadError::failure(options.sequence_dir + ": sequence has no truth.csv to start from");
    pipeline.startNearRange(sequence.truth.front().pose, 0);
  }

  const std::size_t bytes_per_pixel = sequence.bit_depth > 8 ? 2U : 1U;
  const std::size_t capacity =
      static_cast<std::size_t>(intrinsics.width_px) * intrinsics.height_px * bytes_per_pixel;
  std::unique_ptr<std::uint8_t[]> buffer(new std::uint8_t[capacity]);
  std::FILE* csv = std::fopen(options.output_csv.c_str(), "w");
  if (csv == nullptr) return LoadError::failure(options.output_csv + ": cannot open for writing");
  writeHeader(csv);

  int total = static_cast<int>(sequence.frames.size());
  if (options.max_frames >= 0) total = std::min(total, options.max_frames);
  std::vector<double> times;
  times.reserve(static_cast<std::size_t>(total));
  const bool tty = options.progress && isatty(STDERR_FILENO) != 0;
  LoadError failure;
  for (int i = 0; i < total; ++i) {
    const replay::FrameEntry& entry = sequence.frames[static_cast<std::size_t>(i)];
    int w = 0, h = 0, maxval = 0;
    if (LoadError e = replay::readPgm(entry.file, buffer.get(), capacity, w, h, maxval, sequence.max_code);
        !e.ok) {
      failure = e;
      break;
    }
    if (w != intrinsics.width_px || h != intrinsics.height_px) {
      failure = LoadError::failure(entry.file + ": frame is " + std::to_string(w) + "x" + std::to_string(h) +
                                   " but the camera is " + std::to_string(intrinsics.width_px) + "x" +
                                   std::to_string(intrinsics.height_px));
      break;
    }
    Frame frame;
    frame.image = maxval > 255 ? MonoImage::from16(
                                     ImageView16(reinterpret_cast<const std::uint16_t*>(buffer.get()), w, h),
                                     static_cast<std::uint16_t>(maxval))
                               : MonoImage::from8(ImageView8(buffer.get(), w, h));
    frame.exposure_time_ns = entry.timestamp_ns;
    frame.sequence = static_cast<std::uint64_t>(entry.frame);
    const std::uint64_t transitions_before = pipeline.modes().transitionCount();
    nav::NavSolution solution;
    // Simulated clock: the frame is processed at its exposure time.
    pipeline.process(&frame, entry.timestamp_ns, solution);
    const NearRangeResult& result = pipeline.lastNearRange();
    writeRow(csv, entry.frame, entry.timestamp_ns, solution, result, pipeline.lastPoseUpdate());
    if (pipeline.modes().transitionCount() != transitions_before) {
      const nav::ModeTransition& t = pipeline.modes().lastTransition();
      ++summary.transitions;
      if (options.progress) {
        std::fprintf(stderr, "%sframe %lld: %s -> %s (%s)\n", tty ? "\r" : "",
                     static_cast<long long>(entry.frame), nav::toString(t.from), nav::toString(t.to),
                     t.reason.data());
      }
    }
    ++summary.frames;
    const bool near = solution.mode == nav::NavMode::kNearRange;
    summary.tracking += near && result.status == TrackStatus::kTracking ? 1 : 0;
    summary.degraded += near && result.status == TrackStatus::kDegraded ? 1 : 0;
    summary.lost += near && result.status == TrackStatus::kLost ? 1 : 0;
    summary.valid_poses += solution.pose_valid ? 1 : 0;
    summary.far_range += solution.mode == nav::NavMode::kFarRange ? 1 : 0;
    summary.acquisition += solution.mode == nav::NavMode::kAcquisition ? 1 : 0;
    times.push_back(solution.timing.process_us);
    if (near && !options.overlay_dir.empty() && options.overlay_every > 0 && i % options.overlay_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "/overlay_%06lld.png", static_cast<long long>(entry.frame));
      if (LoadError e =
              writeOverlayPng(options.overlay_dir + name, frame.image, pipeline.nearRange(), result);
          !e.ok) {
        failure = e;
        break;
      }
    }
    if (tty && (i % 10 == 0 || i + 1 == total)) drawProgress(i + 1, total, summary);
  }
  if (std::fclose(csv) != 0 && failure.ok)
    failure = LoadError::failure(options.output_csv + ": write failed");
  if (!times.empty()) {
    std::sort(times.begin(), times.end());
    summary.median_total_us = times[times.size() / 2];
    summary.p95_total_us = times[std::min(times.size() - 1, times.size() * 95 / 100)];
  }
  return failure;
}

}  // namespace visnav::replay_tool
