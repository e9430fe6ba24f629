// [camera] driver -> the CameraSource that implements it:
//   v4l2       V4l2Camera on [camera] device (/dev/videoN)
//   libcamera  LibcameraCamera, camera id [camera] device (empty: the first camera)
//   replay     ReplayCamera on the sequence directory [camera] device
//   synthetic  ScenarioCamera rendering the visnav-synth scenario file [camera] device
// The playback cameras (replay, synthetic) bring their own intrinsics, model and timeline; they are paced at
// the recorded rate or play as fast as asked ([daemon] playback_pacing; always as fast as possible on the
// simulated clock) and may loop ([daemon] playback_loop). Init time only.
#pragma once

#include <cstdint>
#include <memory>

#include "visnav/app/visnav_config.hpp"
#include "visnav/camera/camera_source.hpp"
#include "visnav/camera/playback.hpp"

namespace visnav::app {

struct OpenedCamera {
  std::unique_ptr<camera::CameraSource> source;
  bool playback = false;         ///< replay or synthetic: a finite, recorded timeline
  bool have_intrinsics = false;  ///< playback: the sequence's / scenario's camera
  CameraIntrinsics intrinsics;
  bool have_model = false;
  PolygonModel model;
  std::int64_t first_timestamp_ns = 0;  ///< playback: recorded time of frame 0 (epoch of a simulated clock)
  int frame_count = 0;                  ///< playback: frames in one pass (0 for live cameras)
  double rate_hz = 0.0;                 ///< playback: recorded frame rate
};

/// Creates (not opened) the source for config.camera.driver.
std::unique_ptr<camera::CameraSource> makeCamera(const VisnavConfig& config, camera::Pacing pacing);

/// Creates the camera. A playback source is opened here: it fills intrinsics, model and timeline from its
/// file. A live one (v4l2, libcamera) is only created: its stream starts in startLiveCamera(), the last step
/// of start-up, so it does not run ahead of the first cycle (frames queued during the rest of start-up would
/// be stale or dropped). `simulated_clock` forces as-fast-as-possible playback (recorded timestamps, which
/// the simulated clock follows). Errors name the device and the problem.
LoadError openCamera(const VisnavConfig& config, bool simulated_clock, OpenedCamera& out);
/// Opens a live camera created by openCamera() (nothing for playback sources).
LoadError startLiveCamera(const VisnavConfig& config, OpenedCamera& camera);

}  // namespace visnav::app
