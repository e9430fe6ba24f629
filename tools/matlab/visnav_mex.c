/* visnav_mex: the Octave/MATLAB gateway to libvisnav (include/visnav/visnav.h). Built with
 * `mkoctfile --mex` on Octave (the same mex.h API MATLAB's `mex` compiles). Visnav.m wraps it; README.md
 * describes the calls:
 *   h   = visnav_mex('create', config, camera, model)       % '' for the built-in config / the config's files
 *   sol = visnav_mex('step', h, image, exposure_time_ns)     % image: height x width uint8 or uint16 (bit
 * depth sol = visnav_mex('step', h, image, t_ns, bit_depth)      %  8 / 16 unless given), [] for no frame ack
 * = visnav_mex('command', h, kind, command_id)         % kind: 'force_far_range' 'reacquire' 'standby'
 *         visnav_mex('start_near_range', h, position_m, quaternion_wxyz)   % 'resume' (or 0..3)
 *         visnav_mex('timing', h, on)
 *         visnav_mex('destroy', h)
 *   v   = visnav_mex('version')
 * Handles are checked against a table of the live ones (a stale or made-up handle is an error, not a crash)
 * and freed when the MEX is cleared. MATLAB images are column-major; each handle owns one row-major frame
 * buffer sized at create, so a step copies the image into it and libvisnav's step allocates nothing (the
 * returned struct is an Octave/MATLAB array and is allocated by them, as every MEX output is).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mex.h"
#include "visnav/visnav.h"

#define VISNAV_MEX_MAX_HANDLES 64

typedef struct mex_handle {
  visnav_handle* handle;
  uint16_t* buffer; /* width * height pixels, row-major, 16-bit words (8-bit frames use the bytes) */
  int32_t width;
  int32_t height;
} mex_handle;

static mex_handle g_handles[VISNAV_MEX_MAX_HANDLES];
static int g_registered = 0;

static void destroyAll(void) {
  int i;
  for (i = 0; i < VISNAV_MEX_MAX_HANDLES; ++i) {
    if (g_handles[i].handle != NULL) {
      visnav_destroy(g_handles[i].handle);
      free(g_handles[i].buffer);
      memset(&g_handles[i], 0, sizeof(g_handles[i]));
    }
  }
}

/* Handle ids given to Octave are slot + 1 (0 is never valid). */
static mex_handle* lookup(const mxArray* id_array) {
  double id;
  int slot;
  if (!mxIsNumeric(id_array) || mxGetNumberOfElements(id_array) != 1)
    mexErrMsgIdAndTxt("visnav:handle", "visnav_mex: the handle must be the scalar 'create' returned");
  id = mxGetScalar(id_array);
  slot = (int)id - 1;
  if (id != (double)(slot + 1) || slot < 0 || slot >= VISNAV_MEX_MAX_HANDLES ||
      g_handles[slot].handle == NULL)
    mexErrMsgIdAndTxt("visnav:handle", "visnav_mex: %g is not a live visnav handle", id);
  return &g_handles[slot];
}

static void textArg(const mxArray* a, char* out, size_t size, const char* what) {
  if (mxIsEmpty(a)) {
    out[0] = '\0';
    return;
  }
  if (!mxIsChar(a) || mxGetString(a, out, (mwSize)size) != 0)
    mexErrMsgIdAndTxt("visnav:argument", "visnav_mex: %s must be a path (char, < %u characters)", what,
                      (unsigned)size);
}

static double scalarArg(const mxArray* a, const char* what) {
  if (!mxIsNumeric(a) || mxGetNumberOfElements(a) != 1 || mxIsComplex(a))
    mexErrMsgIdAndTxt("visnav:argument", "visnav_mex: %s must be a real scalar", what);
  return mxGetScalar(a);
}

/* int64 exactly when given as int64 (nanoseconds beyond 2^53 stay exact), else from the double. */
static int64_t timeArg(const mxArray* a) {
  if (mxIsInt64(a) && mxGetNumberOfElements(a) == 1) return *(const int64_t*)mxGetData(a);
  return (int64_t)scalarArg(a, "exposure_time_ns");
}

static void setNumber(mxArray* s, const char* field, double value) {
  mxSetField(s, 0, field, mxCreateDoubleScalar(value));
}

static void setVector(mxArray* s, const char* field, const double* values, mwSize rows, mwSize cols,
                      int transpose) {
  mxArray* a = mxCreateDoubleMatrix(rows, cols, mxREAL);
  double* d = mxGetPr(a);
  mwSize r, c;
  for (r = 0; r < rows; ++r)
    for (c = 0; c < cols; ++c) d[c * rows + r] = transpose ? values[r * cols + c] : values[c * rows + r];
  mxSetField(s, 0, field, a);
}

static void setUint64(mxArray* s, const char* field, uint64_t value) {
  mxArray* a = mxCreateNumericMatrix(1, 1, mxUINT64_CLASS, mxREAL);
  *(uint64_t*)mxGetData(a) = value;
  mxSetField(s, 0, field, a);
}

static void setInt64(mxArray* s, const char* field, int64_t value) {
  mxArray* a = mxCreateNumericMatrix(1, 1, mxINT64_CLASS, mxREAL);
  *(int64_t*)mxGetData(a) = value;
  mxSetField(s, 0, field, a);
}

static const char* const kSolutionFields[] = {"cycle_number",
                                              "frame_number",
                                              "exposure_time_ns",
                                              "frame_received",
                                              "mode",
                                              "mode_name",
                                              "track_status",
                                              "track_status_name",
                                              "track_flags",
                                              "fault_bits",
                                              "fault_names",
                                              "pose_valid",
                                              "quality",
                                              "position_m",
                                              "quaternion",
                                              "ypr_rad",
                                              "covariance",
                                              "far_valid",
                                              "far_direction_c",
                                              "far_azimuth_rad",
                                              "far_elevation_rad",
                                              "far_distance_m",
                                              "far_cluster_pixels",
                                              "far_circularity",
                                              "far_cluster_count",
                                              "far_quality",
                                              "tracked_surfaces",
                                              "tracked_surface_mask",
                                              "lines_total",
                                              "lines_used",
                                              "edge_points",
                                              "inlier_points",
                                              "texture_points",
                                              "vertices",
                                              "rms_px",
                                              "lm_iterations",
                                              "nis_valid",
                                              "nis",
                                              "filter_valid",
                                              "velocity_c_m_s",
                                              "angular_velocity_c_rad_s",
                                              "t_project_us",
                                              "t_scan_us",
                                              "t_ransac_us",
                                              "t_pose_us",
                                              "t_process_us",
                                              "symmetric_twins",
                                              "twin_by_continuity"};

static mxArray* solutionStruct(const visnav_solution* s) {
  const int n = (int)(sizeof(kSolutionFields) / sizeof(kSolutionFields[0]));
  mxArray* out = mxCreateStructMatrix(1, 1, n, (const char**)kSolutionFields);
  char names[512];
  size_t used = 0;
  int bit;
  names[0] = '\0';
  for (bit = 0; bit < 32; ++bit) {
    if ((s->fault_bits & (1U << bit)) != 0U) {
      int w =
          snprintf(names + used, sizeof(names) - used, "%s%s", used > 0 ? "," : "", visnav_fault_name(bit));
      if (w > 0 && (size_t)w < sizeof(names) - used) used += (size_t)w;
    }
  }
  setUint64(out, "cycle_number", s->cycle_number);
  setUint64(out, "frame_number", s->frame_number);
  setInt64(out, "exposure_time_ns", s->exposure_time_ns);
  setNumber(out, "frame_received", s->frame_received);
  setNumber(out, "mode", s->mode);
  mxSetField(out, 0, "mode_name", mxCreateString(visnav_mode_name(s->mode)));
  setNumber(out, "track_status", s->track_status);
  mxSetField(out, 0, "track_status_name", mxCreateString(visnav_track_status_name(s->track_status)));
  setNumber(out, "track_flags", s->track_flags);
  setNumber(out, "fault_bits", s->fault_bits);
  mxSetField(out, 0, "fault_names", mxCreateString(names));
  setNumber(out, "pose_valid", s->pose_valid);
  setNumber(out, "symmetric_twins", s->symmetric_twins);
  setNumber(out, "twin_by_continuity", s->twin_by_continuity);
  setNumber(out, "quality", s->quality);
  setVector(out, "position_m", s->position_m, 3, 1, 0);
  setVector(out, "quaternion", s->quaternion, 4, 1, 0);
  setVector(out, "ypr_rad", s->ypr_rad, 3, 1, 0);
  setVector(out, "covariance", s->covariance, 6, 6, 1);
  setNumber(out, "far_valid", s->far_valid);
  setVector(out, "far_direction_c", s->far_direction_c, 3, 1, 0);
  setNumber(out, "far_azimuth_rad", s->far_azimuth_rad);
  setNumber(out, "far_elevation_rad", s->far_elevation_rad);
  setNumber(out, "far_distance_m", s->far_distance_m);
  setNumber(out, "far_cluster_pixels", s->far_cluster_pixels);
  setNumber(out, "far_circularity", s->far_circularity);
  setNumber(out, "far_cluster_count", s->far_cluster_count);
  setNumber(out, "far_quality", s->far_quality);
  setNumber(out, "tracked_surfaces", s->tracked_surfaces);
  setUint64(out, "tracked_surface_mask", s->tracked_surface_mask);
  setNumber(out, "lines_total", s->lines_total);
  setNumber(out, "lines_used", s->lines_used);
  setNumber(out, "edge_points", s->edge_points);
  setNumber(out, "inlier_points", s->inlier_points);
  setNumber(out, "texture_points", s->texture_points);
  setNumber(out, "vertices", s->vertices);
  setNumber(out, "rms_px", s->rms_px);
  setNumber(out, "lm_iterations", s->lm_iterations);
  setNumber(out, "nis_valid", s->nis_valid);
  setNumber(out, "nis", s->nis);
  setNumber(out, "filter_valid", s->filter_valid);
  setVector(out, "velocity_c_m_s", s->velocity_c_m_s, 3, 1, 0);
  setVector(out, "angular_velocity_c_rad_s", s->angular_velocity_c_rad_s, 3, 1, 0);
  setNumber(out, "t_project_us", s->t_project_us);
  setNumber(out, "t_scan_us", s->t_scan_us);
  setNumber(out, "t_ransac_us", s->t_ransac_us);
  setNumber(out, "t_pose_us", s->t_pose_us);
  setNumber(out, "t_process_us", s->t_process_us);
  return out;
}

static void doCreate(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  char config[4096], camera[4096], model[4096], err[512];
  visnav_handle* handle = NULL;
  int slot, rc;
  int32_t width = 0, height = 0;
  if (nrhs != 4 || nlhs > 1)
    mexErrMsgIdAndTxt("visnav:usage", "usage: h = visnav_mex('create', config, camera, model)");
  if (visnav_abi_version() != VISNAV_ABI_VERSION)
    mexErrMsgIdAndTxt("visnav:abi", "visnav_mex: built for ABI %d but libvisnav has ABI %d",
                      VISNAV_ABI_VERSION, visnav_abi_version());
  textArg(prhs[1], config, sizeof(config), "config");
  textArg(prhs[2], camera, sizeof(camera), "camera");
  textArg(prhs[3], model, sizeof(model), "model");
  for (slot = 0; slot < VISNAV_MEX_MAX_HANDLES && g_handles[slot].handle != NULL; ++slot) {
  }
  if (slot == VISNAV_MEX_MAX_HANDLES)
    mexErrMsgIdAndTxt("visnav:handles", "visnav_mex: %d handles live; destroy one first",
                      VISNAV_MEX_MAX_HANDLES);
  rc = visnav_create(config, camera, model, &handle, err, sizeof(err));
  if (rc != VISNAV_OK)
    mexErrMsgIdAndTxt("visnav:create", "visnav_create: %s: %s", visnav_status_text(rc), err);
  visnav_image_size(handle, &width, &height);
  g_handles[slot].buffer = (uint16_t*)malloc((size_t)width * (size_t)height * sizeof(uint16_t));
  if (g_handles[slot].buffer == NULL) {
    visnav_destroy(handle);
    mexErrMsgIdAndTxt("visnav:create", "visnav_mex: cannot allocate the %dx%d frame buffer", width, height);
  }
  g_handles[slot].handle = handle;
  g_handles[slot].width = width;
  g_handles[slot].height = height;
  if (!g_registered) {
    mexAtExit(destroyAll);
    g_registered = 1;
  }
  plhs[0] = mxCreateDoubleScalar((double)(slot + 1));
}

static void doStep(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  mex_handle* m;
  const mxArray* image;
  int64_t t_ns;
  int bit_depth, rc;
  visnav_solution sol;
  if ((nrhs != 4 && nrhs != 5) || nlhs > 1)
    mexErrMsgIdAndTxt("visnav:usage",
                      "usage: sol = visnav_mex('step', h, image, exposure_time_ns [, bit_depth])");
  m = lookup(prhs[1]);
  image = prhs[2];
  t_ns = timeArg(prhs[3]);
  if (mxIsEmpty(image)) {
    rc = visnav_step(m->handle, NULL, 0, 0, 0, 0, t_ns, &sol);
  } else {
    const mwSize rows = mxGetM(image), cols = mxGetN(image);
    const int is8 = mxIsUint8(image), is16 = mxIsUint16(image);
    mwSize r, c;
    if ((!is8 && !is16) || mxIsComplex(image) || mxGetNumberOfDimensions(image) != 2)
      mexErrMsgIdAndTxt("visnav:argument", "visnav_mex: the image must be a 2-D uint8 or uint16 matrix");
    bit_depth = nrhs == 5 ? (int)scalarArg(prhs[4], "bit_depth") : (is8 ? 8 : 16);
    if ((is8 && bit_depth != 8) || (is16 && (bit_depth < 9 || bit_depth > 16)))
      mexErrMsgIdAndTxt("visnav:argument", "visnav_mex: bit_depth %d does not fit a %s image", bit_depth,
                        is8 ? "uint8" : "uint16");
    if ((int32_t)rows != m->height || (int32_t)cols != m->width) {
      /* A width x height matrix (the image transposed, e.g. image.') is in memory exactly the row-major
         frame: used in place, no copy. Any other size goes on as it is and the pipeline reports bad_frame. */
      rc = visnav_step(m->handle, mxGetData(image), (int32_t)rows, (int32_t)cols, 0, bit_depth, t_ns, &sol);
    } else if (is8) {
      const uint8_t* src = (const uint8_t*)mxGetData(image);
      uint8_t* dst = (uint8_t*)m->buffer;
      for (c = 0; c < cols; ++c)
        for (r = 0; r < rows; ++r) dst[r * cols + c] = src[c * rows + r];
      rc = visnav_step(m->handle, dst, m->width, m->height, 0, 8, t_ns, &sol);
    } else {
      const uint16_t* src = (const uint16_t*)mxGetData(image);
      for (c = 0; c < cols; ++c)
        for (r = 0; r < rows; ++r) m->buffer[r * cols + c] = src[c * rows + r];
      rc = visnav_step(m->handle, m->buffer, m->width, m->height, 0, bit_depth, t_ns, &sol);
    }
  }
  if (rc != VISNAV_OK)
    mexErrMsgIdAndTxt("visnav:step", "visnav_step: %s: %s", visnav_status_text(rc),
                      visnav_last_error(m->handle));
  plhs[0] = solutionStruct(&sol);
}

static int commandKind(const mxArray* a) {
  static const char* const names[] = {"force_far_range", "reacquire", "standby", "resume"};
  char text[32];
  int k;
  if (!mxIsChar(a)) return (int)scalarArg(a, "kind");
  if (mxGetString(a, text, sizeof(text)) != 0) return -1;
  for (k = 0; k < 4; ++k)
    if (strcmp(text, names[k]) == 0) return k;
  return -1;
}

static void doCommand(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  static const char* const fields[] = {"accepted", "command_id", "kind", "reason"};
  mex_handle* m;
  visnav_command_ack ack;
  int kind, rc;
  uint32_t id;
  mxArray* out;
  if (nrhs != 4 || nlhs > 1)
    mexErrMsgIdAndTxt("visnav:usage", "usage: ack = visnav_mex('command', h, kind, command_id)");
  m = lookup(prhs[1]);
  kind = commandKind(prhs[2]);
  id = (uint32_t)scalarArg(prhs[3], "command_id");
  memset(&ack, 0, sizeof(ack));
  rc = visnav_command(m->handle, kind, id, &ack);
  if (rc != VISNAV_OK && rc != VISNAV_ERROR_REJECTED)
    mexErrMsgIdAndTxt("visnav:command", "visnav_command: %s: %s", visnav_status_text(rc),
                      visnav_last_error(m->handle));
  out = mxCreateStructMatrix(1, 1, 4, (const char**)fields);
  setNumber(out, "accepted", ack.accepted);
  setNumber(out, "command_id", ack.command_id);
  setNumber(out, "kind", ack.kind);
  mxSetField(out, 0, "reason", mxCreateString(ack.reason));
  plhs[0] = out;
}

static void doStartNearRange(int nrhs, const mxArray* prhs[]) {
  mex_handle* m;
  int rc;
  if (nrhs != 4 || !mxIsDouble(prhs[2]) || !mxIsDouble(prhs[3]) || mxGetNumberOfElements(prhs[2]) != 3 ||
      mxGetNumberOfElements(prhs[3]) != 4)
    mexErrMsgIdAndTxt("visnav:usage",
                      "usage: visnav_mex('start_near_range', h, position_m(3), quaternion_wxyz(4))");
  m = lookup(prhs[1]);
  rc = visnav_start_near_range(m->handle, mxGetPr(prhs[2]), mxGetPr(prhs[3]));
  if (rc != VISNAV_OK)
    mexErrMsgIdAndTxt("visnav:start", "visnav_start_near_range: %s", visnav_last_error(m->handle));
}

static void doDestroy(int nrhs, const mxArray* prhs[]) {
  mex_handle* m;
  if (nrhs != 2) mexErrMsgIdAndTxt("visnav:usage", "usage: visnav_mex('destroy', h)");
  m = lookup(prhs[1]);
  visnav_destroy(m->handle);
  free(m->buffer);
  memset(m, 0, sizeof(*m));
}

void mexFunction(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  char verb[32];
  if (nrhs < 1 || !mxIsChar(prhs[0]) || mxGetString(prhs[0], verb, sizeof(verb)) != 0)
    mexErrMsgIdAndTxt(
        "visnav:usage",
        "usage: visnav_mex('create'|'step'|'command'|'start_near_range'|'timing'|'destroy'|'version', ...)");
  if (strcmp(verb, "create") == 0) {
    doCreate(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(verb, "step") == 0) {
    doStep(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(verb, "command") == 0) {
    doCommand(nlhs, plhs, nrhs, prhs);
  } else if (strcmp(verb, "start_near_range") == 0) {
    doStartNearRange(nrhs, prhs);
  } else if (strcmp(verb, "timing") == 0) {
    if (nrhs != 3) mexErrMsgIdAndTxt("visnav:usage", "usage: visnav_mex('timing', h, on)");
    visnav_set_timing(lookup(prhs[1])->handle, scalarArg(prhs[2], "on") != 0.0);
  } else if (strcmp(verb, "destroy") == 0) {
    doDestroy(nrhs, prhs);
  } else if (strcmp(verb, "version") == 0) {
    static const char* const fields[] = {"version", "abi", "header_abi"};
    mxArray* out = mxCreateStructMatrix(1, 1, 3, (const char**)fields);
    mxSetField(out, 0, "version", mxCreateString(visnav_version()));
    setNumber(out, "abi", visnav_abi_version());
    setNumber(out, "header_abi", VISNAV_ABI_VERSION);
    plhs[0] = out;
  } else {
    mexErrMsgIdAndTxt("visnav:usage", "visnav_mex: unknown call '%s'", verb);
  }
}
