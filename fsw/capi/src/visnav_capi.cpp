// libvisnav: the C ABI of include/visnav/visnav.h over nav::NavigationPipeline (fsw/capi/README.md).
// Loading goes through the same functions visnav-replay and visnavd use (app::loadVisnavConfig,
// io::loadCamera, io::loadModel, app::loadConfiguredFiles); every entry point catches everything at the
// boundary.
#include <cmath>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "visnav/app/visnav_config.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/version.hpp"
#include "visnav/visnav.h"

struct visnav_handle {
  visnav::nav::NavigationPipeline pipeline;
  std::uint64_t next_frame = 0;  ///< sequence number the next stepped image gets
  std::int32_t width = 0;        ///< the camera's image size
  std::int32_t height = 0;
  char last_error[256] = {};
};

namespace {

using visnav::nav::NavMode;

void copyText(const char* text, char* out, std::size_t capacity) {
  if (out == nullptr || capacity == 0) return;
  std::snprintf(out, capacity, "%s", text);
}

int fail(visnav_handle* handle, int code, const char* text) {
  if (handle != nullptr) copyText(text, handle->last_error, sizeof(handle->last_error));
  return code;
}

int trackStatus(const visnav::nav::NavSolution& sol, const visnav::NearRangeResult& near) {
  if (sol.mode != NavMode::kNearRange) return VISNAV_TRACK_INIT;
  // A pose the pipeline did not deliver (the filter disputed it, or it is less certain than the limits of
  // [navigation]) is lost to the user, whatever the tracker's verdict; as in telemetry (sample_mapping.cpp).
  if (!sol.pose_valid) return VISNAV_TRACK_LOST;
  switch (near.status) {
    case visnav::TrackStatus::kTracking: return VISNAV_TRACK_TRACKING;
    case visnav::TrackStatus::kDegraded: return VISNAV_TRACK_DEGRADED;
    case visnav::TrackStatus::kLost: return VISNAV_TRACK_LOST;
  }
  return VISNAV_TRACK_LOST;
}

// NavSolution (and what the pipeline kept of this frame) -> the plain C struct. Allocation-free.
void fill(const visnav_handle& h, const visnav::nav::NavSolution& sol, visnav_solution& out) {
  out = visnav_solution{};  // every field zero (value-initialised)
  const visnav::nav::NavigationPipeline& p = h.pipeline;
  out.cycle_number = sol.cycle_number;
  out.frame_number = sol.frame_number;
  out.exposure_time_ns = sol.exposure_time_ns;
  out.frame_received = sol.frame_received ? 1 : 0;
  out.mode = static_cast<std::int32_t>(sol.mode);
  const bool near = sol.mode == NavMode::kNearRange;
  const visnav::NearRangeResult empty{};
  const visnav::NearRangeResult& r = near ? p.lastNearRange() : empty;
  out.track_status = trackStatus(sol, r);
  out.track_flags = r.flags;
  out.fault_bits = sol.fault_bits;
  out.quality = sol.quality;
  out.pose_valid = sol.pose_valid ? 1 : 0;
  out.symmetric_twins = sol.symmetric_twins;
  out.twin_by_continuity = sol.twin_by_continuity ? 1 : 0;
  if (sol.pose_valid) {
    Eigen::Quaterniond q = sol.pose.quaternion();
    if (q.w() < 0.0) q.coeffs() *= -1.0;  // CONVENTIONS.md: w >= 0
    const visnav::YawPitchRoll ypr = sol.pose.ypr();
    for (int i = 0; i < 3; ++i) out.position_m[i] = sol.pose.t_c_m[i];
    out.quaternion[0] = q.w();
    out.quaternion[1] = q.x();
    out.quaternion[2] = q.y();
    out.quaternion[3] = q.z();
    out.ypr_rad[0] = ypr.yaw_rad;
    out.ypr_rad[1] = ypr.pitch_rad;
    out.ypr_rad[2] = ypr.roll_rad;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) out.covariance[i * 6 + j] = sol.covariance(i, j);
  }
  const visnav::FarRangeSolution& far = sol.far;
  out.far_valid = far.valid ? 1 : 0;
  out.far_cluster_pixels = far.cluster_pixels;
  out.far_cluster_count = far.cluster_count;
  for (int i = 0; i < 3; ++i) out.far_direction_c[i] = far.direction_c[i];
  out.far_azimuth_rad = far.azimuth_rad;
  out.far_elevation_rad = far.elevation_rad;
  out.far_distance_m = far.distance_m;
  out.far_circularity = far.circularity;
  out.far_quality = far.quality;
  out.tracked_surfaces = r.tracked_surfaces;
  out.lines_total = r.lines_total;
  out.lines_used = r.lines_used;
  out.edge_points = r.edge_points;
  out.inlier_points = r.inlier_points;
  out.texture_points = r.texture_points;
  out.vertices = r.vertices;
  out.lm_iterations = r.lm_iterations;
  out.tracked_surface_mask = r.tracked_surface_mask;
  out.rms_px = r.rms_px;
  const visnav::nav::FilterUpdate& update = p.lastPoseUpdate();
  out.nis_valid = update.status == visnav::Status::kOk && update.dof == 6 ? 1 : 0;
  out.nis = out.nis_valid != 0 ? update.nis : 0.0;
  const visnav::nav::PoseFilter& filter = p.filter();
  out.filter_valid = filter.initialised() ? 1 : 0;
  if (filter.initialised()) {
    for (int i = 0; i < 3; ++i) {
      out.velocity_c_m_s[i] = filter.velocity()[i];
      out.angular_velocity_c_rad_s[i] = filter.angularVelocity()[i];
    }
  }
  out.t_project_us = r.timing.project_us;
  out.t_scan_us = r.timing.scan_us;
  out.t_ransac_us = r.timing.ransac_us;
  out.t_pose_us = r.timing.pose_us;
  out.t_process_us = sol.timing.process_us;
}

bool empty(const char* text) { return text == nullptr || text[0] == '\0'; }

// The loading half of visnav_create (allocates, reads files): the same loaders as visnav-replay --config.
visnav::LoadError build(const char* config_path, const char* camera_path, const char* model_path,
                        visnav_handle& handle) {
  visnav::nav::PipelineParams params;
  visnav::CameraIntrinsics intrinsics;
  visnav::PolygonModel model;
  bool have_camera = false;
  bool have_model = false;
  if (!empty(config_path)) {
    visnav::app::VisnavConfig config;
    if (visnav::LoadError e = visnav::app::loadVisnavConfig(config_path, config); !e.ok) return e;
    params = config.pipeline;
    if (empty(camera_path) || empty(model_path)) {
      if (visnav::LoadError e =
              visnav::app::loadConfiguredFiles(config, intrinsics, have_camera, model, have_model);
          !e.ok)
        return e;
    }
  }
  if (!empty(camera_path)) {
    if (visnav::LoadError e = visnav::io::loadCamera(camera_path, intrinsics); !e.ok) return e;
    have_camera = true;
  }
  if (!empty(model_path)) {
    if (visnav::LoadError e = visnav::io::loadModel(model_path, model); !e.ok) return e;
    have_model = true;
  }
  if (!have_camera) return visnav::LoadError::failure("no camera: pass camera_path or set [files] camera");
  if (!have_model) return visnav::LoadError::failure("no model: pass model_path or set [files] model");
  handle.width = intrinsics.width_px;
  handle.height = intrinsics.height_px;
  return handle.pipeline.init(visnav::PinholeCamera(intrinsics), model, params);
}

}  // namespace

extern "C" {

const char* visnav_version(void) { return visnav::kVersion; }

int visnav_abi_version(void) { return VISNAV_ABI_VERSION; }

const char* visnav_status_text(int status) {
  switch (status) {
    case VISNAV_OK: return "ok";
    case VISNAV_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case VISNAV_ERROR_LOAD: return "load error";
    case VISNAV_ERROR_OUT_OF_MEMORY: return "out of memory";
    case VISNAV_ERROR_INTERNAL: return "internal error";
    case VISNAV_ERROR_REJECTED: return "rejected";
    default: return "unknown";
  }
}

const char* visnav_mode_name(int mode) {
  if (mode < VISNAV_MODE_STANDBY || mode > VISNAV_MODE_NEAR_RANGE) return "unknown";
  return visnav::nav::toString(static_cast<NavMode>(mode));
}

const char* visnav_track_status_name(int track_status) {
  switch (track_status) {
    case VISNAV_TRACK_INIT: return "init";
    case VISNAV_TRACK_TRACKING: return "tracking";
    case VISNAV_TRACK_DEGRADED: return "degraded";
    case VISNAV_TRACK_LOST: return "lost";
    default: return "unknown";
  }
}

const char* visnav_fault_name(int bit_index) { return visnav::faultName(bit_index); }

int visnav_create(const char* config_path, const char* camera_path, const char* model_path,
                  visnav_handle** out_handle, char* err, std::size_t errlen) {
  copyText("", err, errlen);
  if (out_handle == nullptr) {
    copyText("visnav_create: out_handle is NULL", err, errlen);
    return VISNAV_ERROR_INVALID_ARGUMENT;
  }
  *out_handle = nullptr;
  try {
    visnav_handle* handle = new (std::nothrow) visnav_handle;
    if (handle == nullptr) {
      copyText("visnav_create: cannot allocate the pipeline", err, errlen);
      return VISNAV_ERROR_OUT_OF_MEMORY;
    }
    const visnav::LoadError e = build(config_path, camera_path, model_path, *handle);
    if (!e.ok) {
      copyText(e.message.c_str(), err, errlen);
      delete handle;
      return VISNAV_ERROR_LOAD;
    }
    *out_handle = handle;
    return VISNAV_OK;
  } catch (const std::bad_alloc&) {
    copyText("visnav_create: out of memory", err, errlen);
    return VISNAV_ERROR_OUT_OF_MEMORY;
  } catch (const std::exception& ex) {
    copyText((std::string("visnav_create: ") + ex.what()).c_str(), err, errlen);
    return VISNAV_ERROR_INTERNAL;
  } catch (...) {
    copyText("visnav_create: unknown exception", err, errlen);
    return VISNAV_ERROR_INTERNAL;
  }
}

int visnav_step(visnav_handle* handle, const void* image, std::int32_t width, std::int32_t height,
                std::int64_t stride_bytes, std::int32_t bit_depth, std::int64_t exposure_time_ns,
                visnav_solution* out) {
  if (handle == nullptr) return VISNAV_ERROR_INVALID_ARGUMENT;
  if (out == nullptr) return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_step: solution is NULL");
  try {
    visnav::Frame frame;
    const visnav::Frame* frame_ptr = nullptr;
    if (image != nullptr) {
      if (width <= 0 || height <= 0 || width > 65535 || height > 65535)
        return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_step: width and height must be 1..65535");
      if (bit_depth < 8 || bit_depth > 16)
        return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_step: bit_depth must be 8..16");
      const std::int64_t bytes_per_pixel = bit_depth > 8 ? 2 : 1;
      const std::int64_t stride = stride_bytes == 0 ? width * bytes_per_pixel : stride_bytes;
      if (stride < width * bytes_per_pixel || (bytes_per_pixel == 2 && stride % 2 != 0))
        return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT,
                    "visnav_step: stride_bytes is smaller than a row (or odd for 16-bit pixels)");
      if (bit_depth == 8) {
        frame.image = visnav::MonoImage::from8(
            visnav::ImageView8(static_cast<const std::uint8_t*>(image), width, height, stride));
      } else {
        frame.image = visnav::MonoImage::from16(
            visnav::ImageView16(static_cast<const std::uint16_t*>(image), width, height, stride),
            static_cast<std::uint16_t>((1U << static_cast<unsigned>(bit_depth)) - 1U));
      }
      frame.exposure_time_ns = exposure_time_ns;
      frame.sequence = handle->next_frame++;
      frame_ptr = &frame;
    }
    visnav::nav::NavSolution solution;
    // Simulated time, as in visnav-replay: the frame is processed at its exposure time.
    handle->pipeline.process(frame_ptr, exposure_time_ns, solution);
    fill(*handle, solution, *out);
    handle->last_error[0] = '\0';
    return VISNAV_OK;
  } catch (...) {  // nothing in the step throws; this is the boundary's guarantee, not a code path
    return fail(handle, VISNAV_ERROR_INTERNAL, "visnav_step: unexpected exception");
  }
}

int visnav_command(visnav_handle* handle, int kind, std::uint32_t command_id, visnav_command_ack* ack) {
  if (handle == nullptr) return VISNAV_ERROR_INVALID_ARGUMENT;
  if (kind < VISNAV_COMMAND_FORCE_FAR_RANGE || kind > VISNAV_COMMAND_RESUME)
    return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_command: unknown command kind");
  try {
    visnav::nav::CommandAck a;
    const std::uint64_t frame = handle->next_frame > 0 ? handle->next_frame - 1 : 0;
    const bool accepted =
        handle->pipeline.command(static_cast<visnav::nav::ModeCommandKind>(kind), command_id, frame, a);
    if (ack != nullptr) {
      ack->command_id = a.command_id;
      ack->kind = static_cast<std::int32_t>(a.kind);
      ack->accepted = accepted ? 1 : 0;
      copyText(a.reason.data(), ack->reason, sizeof(ack->reason));
    }
    if (!accepted) return fail(handle, VISNAV_ERROR_REJECTED, a.reason.data());
    handle->last_error[0] = '\0';
    return VISNAV_OK;
  } catch (...) {
    return fail(handle, VISNAV_ERROR_INTERNAL, "visnav_command: unexpected exception");
  }
}

int visnav_start_near_range(visnav_handle* handle, const double position_m[3],
                            const double quaternion_wxyz[4]) {
  if (handle == nullptr) return VISNAV_ERROR_INVALID_ARGUMENT;
  if (position_m == nullptr || quaternion_wxyz == nullptr)
    return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_start_near_range: NULL pose");
  double norm2 = 0.0;
  for (int i = 0; i < 4; ++i) norm2 += quaternion_wxyz[i] * quaternion_wxyz[i];
  bool finite = std::isfinite(norm2);
  for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(position_m[i]);
  if (!finite || norm2 < 1e-12)
    return fail(handle, VISNAV_ERROR_INVALID_ARGUMENT, "visnav_start_near_range: non-finite or zero pose");
  try {
    visnav::Pose pose;
    const Eigen::Quaterniond q(quaternion_wxyz[0], quaternion_wxyz[1], quaternion_wxyz[2],
                               quaternion_wxyz[3]);
    pose.R_c_m = q.normalized().toRotationMatrix();
    pose.t_c_m = visnav::Vec3(position_m[0], position_m[1], position_m[2]);
    handle->pipeline.startNearRange(pose, handle->next_frame);
    handle->last_error[0] = '\0';
    return VISNAV_OK;
  } catch (...) {
    return fail(handle, VISNAV_ERROR_INTERNAL, "visnav_start_near_range: unexpected exception");
  }
}

int visnav_set_timing(visnav_handle* handle, int enabled) {
  if (handle == nullptr) return VISNAV_ERROR_INVALID_ARGUMENT;
  handle->pipeline.setClock(enabled != 0 ? &visnav::exec::monotonicNowNs : nullptr);
  handle->last_error[0] = '\0';
  return VISNAV_OK;
}

int visnav_image_size(const visnav_handle* handle, std::int32_t* width, std::int32_t* height) {
  if (handle == nullptr || width == nullptr || height == nullptr) return VISNAV_ERROR_INVALID_ARGUMENT;
  *width = handle->width;
  *height = handle->height;
  return VISNAV_OK;
}

const char* visnav_last_error(const visnav_handle* handle) {
  return handle != nullptr ? handle->last_error : "visnav: NULL handle";
}

void visnav_destroy(visnav_handle* handle) { delete handle; }

}  // extern "C"
