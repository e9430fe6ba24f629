// One Monte Carlo scene of visnav-campaign: target model, camera, rendering, trajectory and events, drawn
// from the scene seed alone (tools/campaign/README.md lists every draw and its range). A scene is fully
// determined by (family, scene seed, frame cap): drawScene() twice gives bit-identical scenes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/campaign/symmetry.hpp"
#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::campaign {

enum class Family : int { kPlate = 0, kOctagon, kBox, kSmallsat, kCao };
constexpr int kFamilyCount = 5;
const char* toString(Family family);
bool parseFamily(const std::string& text, Family& out);

enum class BackgroundKind : int { kSpace = 0, kGradient, kLimb, kBlobs, kDrifting };
const char* toString(BackgroundKind kind);

/// The file models of the families that do not build their own (loaded once per campaign).
struct ModelLibrary {
  PolygonModel smallsat;
  std::string smallsat_path;
  PolygonModel cao;  ///< the "cao" family's model (--model)
  std::string cao_path;
};

/// Area [m^2] of the model seen face-on along -z (surfaces with n_z > 0, projected onto the x-y plane).
double faceOnArea(const PolygonModel& model);

/// Projection of the target centre and radius at a frame (for placing backgrounds and checking fits).
struct Silhouette {
  bool in_front = false;
  Vec2 centre_px = Vec2::Zero();
  double radius_px = 0.0;  ///< f R / z of the bounding sphere
};

/// A background whose level crosses the target brightness inside the target outline: a huge soft disc
/// (LimbClutter) whose brightness ramps from `background` to `limb`. Solved so that along `direction` the
/// background is target - contrast_plus at the outline's near side, the target brightness at its centre and
/// target + contrast_minus at its far side (contrast +c_plus -> 0 -> -c_minus), within [0, 1].
struct GradientSolution {
  double background = 0.0;
  synthetic::LimbClutter limb;
  double contrast_plus = 0.0;  ///< achieved (reduced when a level would leave [0, 1])
  double contrast_minus = 0.0;
};
GradientSolution solveGradient(double target_brightness, double contrast_plus, double contrast_minus,
                               const Vec2& centre_px, double outline_radius_px, double angle_rad,
                               double softness_px, double image_size_px);

struct SceneEvents {
  bool eclipse = false;
  int eclipse_first = 0;  ///< first frame without the target
  int eclipse_frames = 0;
  bool slew = false;
  int slew_frame = 0;                ///< first frame with the new line of sight
  Vec3 slew_axis_c = Vec3::UnitX();  ///< camera-frame axis of the jump
  double slew_deg = 0.0;
};

struct Scene {
  std::string name;  ///< "box/1234" (family/seed) or the case name
  Family family = Family::kPlate;
  bool is_case = false;
  std::uint64_t seed = 0;  ///< scene seed (random scenes; cases have a fixed one)
  bool approach = false;   ///< 750 m -> d_end, started in far range; else near range from the first truth
  std::string model_text;  ///< "plate 2.13x1.55 m", ...
  PolygonModel model;
  std::vector<Symmetry> symmetries;
  CameraIntrinsics camera;
  synthetic::RenderOptions render;
  BackgroundKind background = BackgroundKind::kSpace;
  bool drifting_blobs = false;
  double target_brightness = 0.8;
  double gradient_contrast_plus = 0.0;  ///< gradient background: achieved contrasts
  double gradient_contrast_minus = 0.0;
  std::uint64_t noise_seed = 1;  ///< per-frame noise seed = Renderer::frameSeed(noise_seed, frame)
  // Trajectory (5 Hz). Distance: near scenes linear from d_start to d_end, approach scenes geometric.
  int frames = 0;
  int frames_drawn = 0;  ///< before --max-frames
  double rate_hz = 5.0;
  double d_start_m = 10.0;
  double d_end_m = 10.0;
  double yaw_deg = 0.0;   ///< about the boresight
  double tilt_deg = 0.0;  ///< off face-on, about an image-plane axis at tilt_dir_deg
  double tilt_dir_deg = 0.0;
  Mat3 R_base = Mat3::Identity();  ///< R_c_m at frame 0 (before tumble)
  Vec3 tumble_axis_m = Vec3::UnitZ();
  double tumble_deg_per_frame = 0.0;
  double lateral_x_amp_m = 0.0;
  double lateral_x_period_frames = 100.0;
  double lateral_y_amp_m = 0.0;
  double lateral_y_period_frames = 100.0;
  SceneEvents events;
  double gamma = 3000.0;  ///< far-range eq. 16 gamma a user would calibrate: f sqrt(face-on area)

  double distance(int frame) const;
  Pose truth(int frame) const;
  bool eclipsed(int frame) const;
  std::int64_t timestampNs(int frame) const;
  Silhouette silhouette(const Pose& T_c_m) const;
};

/// Scene seed of the index-th scene of a campaign: campaign seed + index, so `--runs 1 --seed X` reruns the
/// scene printed with seed X.
inline std::uint64_t sceneSeed(std::uint64_t campaign_seed, int index) {
  return campaign_seed + static_cast<std::uint64_t>(index);
}

/// Draws the scene of (family, seed). `max_frames` > 0 caps its length (an approach then closes faster,
/// events are placed inside the shorter scene); the random draws themselves do not depend on it.
LoadError drawScene(Family family, std::uint64_t seed, const ModelLibrary& models, int max_frames,
                    Scene& out);

/// The named field-report cases ("tumbling_box", "eclipse_box", "slew_box", "low_contrast_octagon",
/// "approach_smallsat").
const std::vector<std::string>& caseNames();
LoadError makeCase(const std::string& name, const ModelLibrary& models, int max_frames, Scene& out);

/// The drawn parameters as (key, value) for the JSON and CSV outputs; numbers are formatted with %.6g.
struct SceneParam {
  std::string key;
  std::string value;
  bool is_number = true;
};
std::vector<SceneParam> sceneParameters(const Scene& scene);

}  // namespace visnav::campaign
