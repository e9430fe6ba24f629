#include "visnav/app/visnav_config.hpp"

#include <utility>

#include "visnav/io/camera_io.hpp"
#include "visnav/io/config_io.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::app {
namespace {

bool usesLiveCamera(const camera::CameraParams& params) {
  return params.driverKind() == camera::CameraDriver::kV4l2 ||
         params.driverKind() == camera::CameraDriver::kLibcamera;
}

}  // namespace

const char* runProblem(const VisnavConfig& c) {
  if (usesLiveCamera(c.camera) && c.files.camera.empty())
    return "[files] camera must name the calibration of the live camera (driver v4l2 or libcamera)";
  if (usesLiveCamera(c.camera) && c.files.model.empty())
    return "[files] model must name the target model when the camera is live (driver v4l2 or libcamera)";
  if (c.camera.driverKind() == camera::CameraDriver::kSynthetic && c.camera.device.empty())
    return "[camera] device must name the scenario file when driver = \"synthetic\"";
  return nullptr;
}

std::string resolveAgainstConfig(const std::string& config_path, const std::string& path) {
  if (path.empty() || path.front() == '/') return path;
  const std::size_t slash = config_path.rfind('/');
  if (slash == std::string::npos) return path;
  return config_path.substr(0, slash + 1) + path;
}

LoadError loadVisnavConfig(const std::string& path, VisnavConfig& out) {
  VisnavConfig c;
  c.path = path;
  io::ConfigFile file;
  LoadError e = file.open(path);
  if (e.ok) e = file.apply(c.pipeline.navigation);
  if (e.ok) e = file.apply(c.pipeline.nearrange);
  if (e.ok) e = file.apply(c.pipeline.farrange);
  if (e.ok) e = file.apply(c.pipeline.acquisition);
  if (e.ok) e = file.apply(c.pipeline.filter);
  if (e.ok) e = file.apply(c.executive);
  if (e.ok) e = file.apply(c.camera);
  if (e.ok) {
    e = telemetry::applyTelemetryConfig(file, c.telemetry);
    if (!e.ok && e.message.rfind(path, 0) != 0) e.message = path + ": " + e.message;  // the partition's error
  }
  if (e.ok) e = file.apply(c.files);
  if (e.ok) e = file.apply(c.daemon);
  if (e.ok) e = file.checkNoUnknownKeys();
  if (!e.ok) return e;
  c.files.camera = resolveAgainstConfig(path, c.files.camera);
  c.files.model = resolveAgainstConfig(path, c.files.model);
  if (c.camera.driverKind() == camera::CameraDriver::kReplay ||
      c.camera.driverKind() == camera::CameraDriver::kSynthetic)
    c.camera.device = resolveAgainstConfig(path, c.camera.device);
  out = std::move(c);
  return LoadError::success();
}

LoadError loadConfiguredFiles(const VisnavConfig& config, CameraIntrinsics& intrinsics, bool& have_camera,
                              PolygonModel& model, bool& have_model) {
  have_camera = !config.files.camera.empty();
  have_model = !config.files.model.empty();
  if (have_camera)
    if (LoadError e = io::loadCamera(config.files.camera, intrinsics); !e.ok) return e;
  if (have_model)
    if (LoadError e = io::loadModel(config.files.model, model); !e.ok) return e;
  if (have_camera && usesLiveCamera(config.camera) &&
      (intrinsics.width_px != config.camera.width_px || intrinsics.height_px != config.camera.height_px))
    return LoadError::failure(
        config.path + ": [camera] width_px x height_px = " + std::to_string(config.camera.width_px) + "x" +
        std::to_string(config.camera.height_px) + " but the calibration " + config.files.camera + " is " +
        std::to_string(intrinsics.width_px) + "x" + std::to_string(intrinsics.height_px));
  return LoadError::success();
}

}  // namespace visnav::app
