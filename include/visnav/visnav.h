/* visnav C ABI (libvisnav): the flight pipeline of visnavd and visnav-replay (modes, far range, acquisition,
 * near range, Kalman filter, FDIR) behind a stable C interface, for simulation loops (Octave/MATLAB MEX,
 * Simulink S-functions, Python ctypes, C). fsw/capi/README.md describes it; conventions (frames, quaternion
 * order, covariance layout) are those of fsw/geometry/CONVENTIONS.md.
 *
 * Rules:
 *  - Every function returns a visnav_status code; error text goes to the caller's buffer (visnav_create) or
 *    is kept in the handle (visnav_last_error). No C++ exception crosses this interface.
 *  - visnav_create() allocates everything (and reads the files); visnav_step() allocates nothing, does no
 *    I/O and is bounded: it may run inside a hard real-time step.
 *  - Same inputs, same outputs, bit for bit (no clock is read unless visnav_set_timing() turns it on).
 *  - One handle is one pipeline; handles are independent; a handle is not thread-safe.
 *  - ABI: the soname is libvisnav.so.VISNAV_ABI_VERSION; any change to a struct or a signature increments
 *    it. visnav_abi_version() tells the loaded library's number, to be checked against VISNAV_ABI_VERSION.
 */
#ifndef VISNAV_VISNAV_H
#define VISNAV_VISNAV_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VISNAV_ABI_VERSION 2

#if defined(__GNUC__)
#define VISNAV_API __attribute__((visibility("default")))
#else
#define VISNAV_API
#endif

/** Opaque pipeline handle. */
typedef struct visnav_handle visnav_handle;

/** Return codes. */
typedef enum visnav_status {
  VISNAV_OK = 0,
  VISNAV_ERROR_INVALID_ARGUMENT =
      1,                          /**< null handle or output, bad size, depth or stride, non-finite input */
  VISNAV_ERROR_LOAD = 2,          /**< a config, camera or model file is missing or invalid */
  VISNAV_ERROR_OUT_OF_MEMORY = 3, /**< visnav_create could not allocate the pipeline */
  VISNAV_ERROR_INTERNAL = 4,      /**< an unexpected C++ exception was caught at the boundary */
  VISNAV_ERROR_REJECTED = 5       /**< visnav_command: the command was refused (reason in the ack) */
} visnav_status;

/** Navigation mode (fsw/navigation/README.md). */
typedef enum visnav_mode {
  VISNAV_MODE_STANDBY = 0,
  VISNAV_MODE_FAR_RANGE = 1,
  VISNAV_MODE_ACQUISITION = 2,
  VISNAV_MODE_NEAR_RANGE = 3
} visnav_mode;

/** Near-range verdict of this frame as delivered: LOST also when the tracker measured a pose the pipeline did
 *  not deliver (pose_valid 0: disputed by the filter, or less certain than [navigation]
 *  max_valid_attitude_sigma_deg / max_valid_position_sigma_rel); VISNAV_TRACK_INIT outside near range. */
typedef enum visnav_track_status {
  VISNAV_TRACK_INIT = 0,
  VISNAV_TRACK_TRACKING = 1,
  VISNAV_TRACK_DEGRADED = 2,
  VISNAV_TRACK_LOST = 3
} visnav_track_status;

/** Ground-style mode commands (visnav-command). */
typedef enum visnav_command_kind {
  VISNAV_COMMAND_FORCE_FAR_RANGE = 0,
  VISNAV_COMMAND_REACQUIRE = 1,
  VISNAV_COMMAND_STANDBY = 2,
  VISNAV_COMMAND_RESUME = 3
} visnav_command_kind;

/** One cycle's answer. Plain data, filled completely by every successful visnav_step. */
typedef struct visnav_solution {
  uint64_t cycle_number;    /**< visnav_step calls so far, from 1 */
  uint64_t frame_number;    /**< sequence number of the frame processed (frames counted from 0) */
  int64_t exposure_time_ns; /**< as passed in */
  int32_t frame_received;   /**< 1: this step processed an image; 0: no image (the filter coasted) */
  int32_t mode;             /**< visnav_mode */
  int32_t track_status;     /**< visnav_track_status */
  uint32_t track_flags;     /**< near-range TrackFlag bits (fsw/nearrange), 0 outside near range */
  uint32_t fault_bits;      /**< FDIR fault bits of this frame (visnav_fault_name) */
  int32_t pose_valid;       /**< 1: the 6-DOF pose below is reported (near range, acquisition's first) */
  int32_t symmetric_twins;  /**< with pose_valid: other attitudes the image cannot tell from it at this range
                                 (the model's symmetries, near twins under [acquisition]
                                 near_twin_min_separation_px); 0: unique. The pose is the twin continuous with
                                 the track (ABI 2) */
  int32_t twin_by_continuity; /**< 1 (with pose_valid): this pose's track began with an acquisition that
                                   chose among such near twins by continuity with the track lost before
                                   (ABI 2) */
  double quality;             /**< [0, 1] */
  /* 6-DOF pose T_c_m: model (target) frame -> camera frame, through the Kalman filter. */
  double position_m[3];  /**< t_c_m: target origin in the camera frame [m] */
  double quaternion[4];  /**< q_c_m as w, x, y, z with w >= 0 */
  double ypr_rad[3];     /**< yaw, pitch, roll of R_c_m (DIN 9300: R = Rz Ry Rx) [rad] */
  double covariance[36]; /**< 6x6 row-major over (omega [rad], dt [m]), left perturbation */
  /* Far range (valid in far range and acquisition; see far_valid). */
  int32_t far_valid;
  int32_t far_cluster_pixels; /**< n of eq. 16 */
  int32_t far_cluster_count;
  int32_t reserved0;
  double far_direction_c[3]; /**< unit line of sight to the target, camera frame */
  double far_azimuth_rad;    /**< atan2(x, z) */
  double far_elevation_rad;  /**< atan2(-y, hypot(x, z)) */
  double far_distance_m;     /**< eq. 16 */
  double far_circularity;    /**< eq. 15 */
  double far_quality;        /**< [0, 1] */
  /* Near-range details of this frame (zeros outside near range). */
  int32_t tracked_surfaces;
  int32_t lines_total;
  int32_t lines_used;
  int32_t edge_points;
  int32_t inlier_points;
  int32_t texture_points;
  int32_t vertices;
  int32_t lm_iterations;
  uint64_t tracked_surface_mask;
  double rms_px;
  /* Kalman filter. */
  int32_t nis_valid;        /**< 1: this frame had a 6-DOF filter update; nis is what its gate judged */
  int32_t filter_valid;     /**< 1: the filter is initialised (velocities below meaningful) */
  double nis;               /**< normalised innovation squared of the 6-DOF update */
  double velocity_c_m_s[3]; /**< d t_c_m / dt, camera frame [m/s] */
  double angular_velocity_c_rad_s[3]; /**< relative angular rate, camera frame [rad/s] */
  /* Timing [us]: zeros unless visnav_set_timing(handle, 1). */
  double t_project_us;
  double t_scan_us;
  double t_ransac_us;
  double t_pose_us;
  double t_process_us;
} visnav_solution;

/** Answer to visnav_command. */
typedef struct visnav_command_ack {
  uint32_t command_id;
  int32_t kind;     /**< visnav_command_kind echoed */
  int32_t accepted; /**< 1 accepted, 0 refused */
  char reason[64];  /**< NUL-terminated: "ok" or why refused */
} visnav_command_ack;

/** Library version text ("0.1.0"), static storage. */
VISNAV_API const char* visnav_version(void);
/** ABI number of the loaded library (compare with VISNAV_ABI_VERSION of the header compiled against). */
VISNAV_API int visnav_abi_version(void);
/** Short text of a visnav_status ("ok", "invalid argument", ...), static storage. */
VISNAV_API const char* visnav_status_text(int status);
/** "standby", "far_range", "acquisition", "near_range"; "unknown" otherwise. */
VISNAV_API const char* visnav_mode_name(int mode);
/** "init", "tracking", "degraded", "lost"; "unknown" otherwise. */
VISNAV_API const char* visnav_track_status_name(int track_status);
/** Name of fault bit index 0..31 ("inlier_ratio", ...; "unknown" for unused bits). */
VISNAV_API const char* visnav_fault_name(int bit_index);

/**
 * Loads the configuration (visnavd's whole-config TOML: every table checked; NULL or "" for the built-in
 * defaults), the camera (.toml or OpenCV .yaml) and the target model (.toml or ViSP .cao), and builds the
 * pipeline with all its memory. camera_path / model_path NULL or "": taken from the config's [files] table.
 * On success *out_handle is set; on failure it is NULL and err (if not NULL) holds up to errlen-1
 * characters of the reason, NUL-terminated.
 */
VISNAV_API int visnav_create(const char* config_path, const char* camera_path, const char* model_path,
                             visnav_handle** out_handle, char* err, size_t errlen);

/**
 * One cycle on one image: `image` points to `height` rows of `width` pixels, `stride_bytes` apart (0: tightly
 * packed); bit_depth 8 is one byte per pixel, 9..16 are native-endian uint16 with codes 0 .. 2^bit_depth - 1.
 * exposure_time_ns is the frame's time (monotonic, increasing); the frame is processed at that time. A frame
 * of another size than the camera's is not processed: the solution carries the bad_frame fault, as in
 * visnavd. image NULL: a cycle without a frame (the filter coasts; size and depth ignored). Frames are
 * numbered 0, 1, 2, ... in the order they are stepped (the number seeds the tracker's RANSAC, as the frame
 * index of a sequence does in visnav-replay). Allocates nothing. On error `out` is left as it was and
 * visnav_last_error() tells why.
 */
VISNAV_API int visnav_step(visnav_handle* handle, const void* image, int32_t width, int32_t height,
                           int64_t stride_bytes, int32_t bit_depth, int64_t exposure_time_ns,
                           visnav_solution* out);

/** A mode command (visnav_command_kind), validated and acknowledged like visnavd's ground commands.
 * Returns VISNAV_OK when accepted, VISNAV_ERROR_REJECTED when refused (ack->reason says why). ack may be
 * NULL. */
VISNAV_API int visnav_command(visnav_handle* handle, int kind, uint32_t command_id, visnav_command_ack* ack);

/** Enters near range from a known pose T_c_m (position [m], quaternion w, x, y, z), bypassing far range and
 * acquisition, as visnav-replay --initial-pose does. */
VISNAV_API int visnav_start_near_range(visnav_handle* handle, const double position_m[3],
                                       const double quaternion_wxyz[4]);

/** 1: per-stage timings from CLOCK_MONOTONIC (not deterministic); 0 (default): timings are zero. */
VISNAV_API int visnav_set_timing(visnav_handle* handle, int enabled);

/** The camera's image size in pixels (what visnav_step expects). */
VISNAV_API int visnav_image_size(const visnav_handle* handle, int32_t* width, int32_t* height);

/** Reason of the handle's last failed call ("" after success), valid until the next call on the handle. */
VISNAV_API const char* visnav_last_error(const visnav_handle* handle);

/** Frees the handle (NULL is ignored). */
VISNAV_API void visnav_destroy(visnav_handle* handle);

#ifdef __cplusplus
}
#endif

#endif /* VISNAV_VISNAV_H */
