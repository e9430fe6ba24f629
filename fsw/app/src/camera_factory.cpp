#include "visnav/app/camera_factory.hpp"

#include <string>

#include "visnav/libcamera/libcamera_camera.hpp"
#include "visnav/replay/replay_camera.hpp"
#include "visnav/synthetic/scenario_camera.hpp"
#include "visnav/v4l2/v4l2_camera.hpp"

namespace visnav::app {
namespace {

constexpr int kPlaybackRing =
    2;  // one frame in use, one spare: each frame is released before the next acquire

}  // namespace

std::unique_ptr<camera::CameraSource> makeCamera(const VisnavConfig& config, camera::Pacing pacing) {
  const bool loop = config.daemon.playback_loop;
  switch (config.camera.driverKind()) {
    case camera::CameraDriver::kV4l2: return std::make_unique<camera::V4l2Camera>(config.camera);
    case camera::CameraDriver::kLibcamera: return std::make_unique<camera::LibcameraCamera>(config.camera);
    case camera::CameraDriver::kReplay:
      return std::make_unique<replay::ReplayCamera>(
          replay::ReplayCameraOptions{config.camera.device, pacing, loop, kPlaybackRing});
    case camera::CameraDriver::kSynthetic:
      return std::make_unique<synthetic::ScenarioCamera>(
          synthetic::ScenarioCameraOptions{config.camera.device, pacing, loop, kPlaybackRing});
  }
  return nullptr;
}

LoadError openCamera(const VisnavConfig& config, bool simulated_clock, OpenedCamera& out) {
  out = OpenedCamera{};
  const camera::Pacing pacing = simulated_clock || config.daemon.pacing() == PlaybackPacing::kAsFastAsPossible
                                    ? camera::Pacing::kAsFastAsPossible
                                    : camera::Pacing::kRecordedRate;
  out.source = makeCamera(config, pacing);
  if (!out.source) return LoadError::failure("[camera] driver: no such driver");
  const camera::CameraDriver driver = config.camera.driverKind();
  out.playback = driver == camera::CameraDriver::kReplay || driver == camera::CameraDriver::kSynthetic;
  if (!out.playback) return LoadError::success();  // a live camera starts streaming in startLiveCamera()
  if (LoadError e = out.source->open(); !e.ok)
    return LoadError::failure(std::string("camera ") + out.source->name() + " '" + config.camera.device +
                              "': " + e.message);
  if (driver == camera::CameraDriver::kReplay) {
    const auto& sequence = static_cast<const replay::ReplayCamera&>(*out.source).sequence();
    out.have_intrinsics = out.have_model = true;
    out.intrinsics = sequence.camera;
    out.model = sequence.model;
    out.frame_count = static_cast<int>(sequence.frames.size());
    out.first_timestamp_ns = sequence.frames.empty() ? 0 : sequence.frames.front().timestamp_ns;
    out.rate_hz = sequence.rate_hz;
  } else if (config.camera.driverKind() == camera::CameraDriver::kSynthetic) {
    const auto& scenario_camera = static_cast<const synthetic::ScenarioCamera&>(*out.source);
    const synthetic::SyntheticCameraConfig& setup = scenario_camera.config();
    out.have_intrinsics = out.have_model = true;
    out.intrinsics = setup.camera;
    out.model = setup.model;
    out.frame_count = setup.trajectory != nullptr ? setup.trajectory->frameCount() : 0;
    out.first_timestamp_ns = out.frame_count > 0 ? setup.trajectory->timestampNs(0) : 0;
    if (out.frame_count > 1)
      out.rate_hz =
          static_cast<double>(out.frame_count - 1) * 1e9 /
          static_cast<double>(setup.trajectory->timestampNs(out.frame_count - 1) - out.first_timestamp_ns);
  }
  return LoadError::success();
}

LoadError startLiveCamera(const VisnavConfig& config, OpenedCamera& camera) {
  if (camera.playback || !camera.source) return LoadError::success();
  if (LoadError e = camera.source->open(); !e.ok)
    return LoadError::failure(std::string("camera ") + camera.source->name() + " '" + config.camera.device +
                              "': " + e.message);
  return LoadError::success();
}

}  // namespace visnav::app
