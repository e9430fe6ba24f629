#include "visnav/replay_tool/replay_runner.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <sstream>
#include <vector>

#include "visnav/io/camera_io.hpp"
#include "visnav/io/config_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/nearrange/near_range_tracker.hpp"
#include "visnav/replay/sequence.hpp"
#include "visnav/replay_tool/overlay.hpp"

namespace visnav::replay_tool {
namespace {

std::int64_t monotonicNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

void writeHeader(std::FILE* f) {
  std::fputs(
      "frame,timestamp_ns,status,flags,mode,quality,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg", f);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) std::fprintf(f, ",cov_%d_%d", i, j);
  std::fputs(
      ",tracked_surfaces,surface_mask,lines_total,lines_used,edge_points,inlier_points,texture_points,"
      "vertices,rms_px,lm_iterations,t_project_us,t_scan_us,t_ransac_us,t_pose_us,t_total_us\n",
      f);
}

void writeRow(std::FILE* f, std::int64_t frame, std::int64_t timestamp_ns, const NearRangeResult& r) {
  Eigen::Quaterniond q = r.pose.quaternion();
  if (q.w() < 0.0) q.coeffs() *= -1.0;  // CONVENTIONS.md: w >= 0
  const YawPitchRoll ypr = r.pose.ypr();
  const Vec3& t = r.pose.t_c_m;
  std::fprintf(f, "%lld,%lld,%s,%u,near,%.6f,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g",
               static_cast<long long>(frame), static_cast<long long>(timestamp_ns), toString(r.status),
               r.flags, r.quality, t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z(), ypr.yaw_rad * kDegPerRad,
               ypr.pitch_rad * kDegPerRad, ypr.roll_rad * kDegPerRad);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) std::fprintf(f, ",%.6g", r.covariance(i, j));
  std::fprintf(f, ",%d,%llu,%d,%d,%d,%d,%d,%d,%.6f,%d,%.2f,%.2f,%.2f,%.2f,%.2f\n", r.tracked_surfaces,
               static_cast<unsigned long long>(r.tracked_surface_mask), r.lines_total, r.lines_used,
               r.edge_points, r.inlier_points, r.texture_points, r.vertices, r.rms_px, r.lm_iterations,
               r.timing.project_us, r.timing.scan_us, r.timing.ransac_us, r.timing.pose_us,
               r.timing.total_us);
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
  NearRangeParams params;
  if (!options.config_path.empty()) {
    io::ConfigFile config;
    if (LoadError e = config.open(options.config_path); !e.ok) return e;
    if (LoadError e = config.apply(params); !e.ok) return e;
    if (LoadError e = config.checkNoUnknownKeys(); !e.ok) return e;
  }
  if (options.override_residual) params.pose_residual = static_cast<int>(options.residual);

  Pose pose;
  if (options.have_initial_pose) {
    pose = options.initial_pose;
  } else if (!sequence.truth.empty()) {
    pose = sequence.truth.front().pose;
  } else {
    return LoadError::failure(options.sequence_dir +
                              ": sequence has no truth.csv; give the initial pose with --initial-pose");
  }

  NearRangeTracker tracker;
  if (LoadError e = tracker.init(PinholeCamera(intrinsics), model, params); !e.ok) return e;
  if (options.timing) tracker.setClock(&monotonicNs);

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
  bool have_previous = false;
  Vec3 previous_t = Vec3::Zero();
  for (int i = 0; i < total; ++i) {
    const replay::FrameEntry& entry = sequence.frames[static_cast<std::size_t>(i)];
    int w = 0, h = 0, maxval = 0;
    if (LoadError e = replay::readPgm(entry.file, buffer.get(), capacity, w, h, maxval); !e.ok) {
      failure = e;
      break;
    }
    if (w != intrinsics.width_px || h != intrinsics.height_px) {
      failure = LoadError::failure(entry.file + ": frame is " + std::to_string(w) + "x" + std::to_string(h) +
                                   " but the camera is " + std::to_string(intrinsics.width_px) + "x" +
                                   std::to_string(intrinsics.height_px));
      break;
    }
    const MonoImage image =
        maxval > 255
            ? MonoImage::from16(ImageView16(reinterpret_cast<const std::uint16_t*>(buffer.get()), w, h),
                                static_cast<std::uint16_t>(maxval))
            : MonoImage::from8(ImageView8(buffer.get(), w, h));
    NearRangeResult result;
    tracker.track(image, pose, static_cast<std::uint64_t>(entry.frame), result);
    // Stand-in for the navigation filter (issue 3): constant-velocity prediction of the translation from
    // the last two measured frames; the attitude is held (at 25 m its frame-to-frame noise would only be
    // amplified by extrapolation). After a lost frame the prediction is the last pose.
    const bool measured = result.status != TrackStatus::kLost;
    pose = result.pose;
    if (measured && have_previous) pose.t_c_m += result.pose.t_c_m - previous_t;
    have_previous = measured;
    previous_t = result.pose.t_c_m;
    writeRow(csv, entry.frame, entry.timestamp_ns, result);
    ++summary.frames;
    summary.tracking += result.status == TrackStatus::kTracking ? 1 : 0;
    summary.degraded += result.status == TrackStatus::kDegraded ? 1 : 0;
    summary.lost += result.status == TrackStatus::kLost ? 1 : 0;
    times.push_back(result.timing.total_us);
    if (!options.overlay_dir.empty() && options.overlay_every > 0 && i % options.overlay_every == 0) {
      char name[64];
      std::snprintf(name, sizeof(name), "/overlay_%06lld.png", static_cast<long long>(entry.frame));
      if (LoadError e = writeOverlayPng(options.overlay_dir + name, image, tracker, result); !e.ok) {
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
