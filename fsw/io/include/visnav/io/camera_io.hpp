// Init-time loaders and writers for cameras. Formats: docs in fsw/io/README.md.
#pragma once

#include <string>

#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"

namespace visnav::io {

/// visnav's own TOML camera format: either SI (focal_length_m + pixel_pitch_m) or pixel (fx_px, fy_px).
LoadError loadCameraToml(const std::string& path, CameraIntrinsics& out);
/// OpenCV FileStorage YAML calibration (image_width, image_height, camera_matrix, distortion_coefficients
/// with 4, 5, 8, 12 or 14 entries; only the first 5 Brown-Conrady terms may be non-zero). Adds 0.5 px to the
/// principal point (OpenCV's pixel centres are integers, ours are at +0.5: CONVENTIONS.md).
LoadError loadCameraOpenCvYaml(const std::string& path, CameraIntrinsics& out);
/// Dispatch on the extension (.toml, .yaml/.yml).
LoadError loadCamera(const std::string& path, CameraIntrinsics& out);
/// Writes the TOML format in pixel units; a round trip reproduces the intrinsics exactly.
LoadError writeCameraToml(const std::string& path, const CameraIntrinsics& camera);

}  // namespace visnav::io
