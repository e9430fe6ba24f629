// The named cases: the field reports of the robustness issue, each rebuilt as a fixed scene.
#include <cmath>

#include "scene_parts.hpp"

namespace visnav::campaign {
namespace {

using detail::baseAttitude;
using detail::makeCamera;

/// Where and how a case's target moves: held at one distance, base attitude, tumble, lateral waves.
struct Hold {
  double distance_m = 10.0;
  double yaw_deg = 0.0;
  double tilt_deg = 0.0;
  double tilt_dir_deg = 0.0;
  Vec3 tumble_axis_m = Vec3::UnitZ();
  double tumble_deg_per_frame = 0.0;
  double lateral_x_amp_m = 0.0;
  double lateral_x_period_frames = 100.0;
  double lateral_y_amp_m = 0.0;
  double lateral_y_period_frames = 100.0;
};

void setHold(Scene& s, const Hold& h) {
  s.d_start_m = s.d_end_m = h.distance_m;
  s.yaw_deg = h.yaw_deg;
  s.tilt_deg = h.tilt_deg;
  s.tilt_dir_deg = h.tilt_dir_deg;
  s.R_base = baseAttitude(h.yaw_deg, h.tilt_deg, h.tilt_dir_deg);
  s.tumble_axis_m = h.tumble_axis_m.normalized();
  s.tumble_deg_per_frame = h.tumble_deg_per_frame;
  s.lateral_x_amp_m = h.lateral_x_amp_m;
  s.lateral_x_period_frames = h.lateral_x_period_frames;
  s.lateral_y_amp_m = h.lateral_y_amp_m;
  s.lateral_y_period_frames = h.lateral_y_period_frames;
}

/// The 1.6 x 1.2 x 1.0 m box of config/models/box_1600x1200x1000.toml.
void setReportBox(Scene& s) {
  s.family = Family::kBox;
  s.model = makeBox(0.8, 0.6, 0.5);
  s.model_text = "box half 0.800x0.600x0.500 m";
}

}  // namespace

const std::vector<std::string>& caseNames() {
  static const std::vector<std::string> names = {"tumbling_box", "eclipse_box", "slew_box",
                                                 "low_contrast_octagon", "approach_smallsat"};
  return names;
}

LoadError makeCase(const std::string& name, const ModelLibrary& models, int max_frames, Scene& out) {
  Scene s;
  s.name = name;
  s.is_case = true;
  s.render.blur_size_px = 5;
  s.render.background = 0.1;
  const Vec3 sun = Vec3(0.3, 0.2, 1.0).normalized();
  if (name == "tumbling_box") {
    // Field report 1: a box tumbling at 3 deg/s about a tilted axis, faces entering at grazing angles.
    setReportBox(s);
    s.seed = 101;
    s.camera = makeCamera(640, 480, 1000.0, 320.0, 240.0, 0.0);
    s.frames_drawn = 150;
    // Tilt 32 deg: two or three faces in view.
    setHold(s, {8.0, 20.0, 32.0, 60.0, Vec3(0.4, 1.0, 0.6), 0.6, 0.15, 140.0, 0.1, 180.0});
    s.target_brightness = 0.75;
    s.render.noise_sigma = 0.1;
    s.render.blur_sigma_px = 0.8;
    s.render.shading = {true, 0.2, sun};
  } else if (name == "eclipse_box" || name == "slew_box") {
    // Field report 2: a box at 10 m; a 5 s eclipse in the middle, or an 8 deg slew (~60 px) at frame 40.
    const bool slew = name == "slew_box";
    setReportBox(s);
    s.seed = slew ? 103 : 102;
    // The slew report's camera: 8 deg = 60 px means f = 60 / tan(8 deg) = 427 px.
    s.camera = slew ? makeCamera(640, 480, 427.0, 320.0, 240.0, 0.0)
                    : makeCamera(640, 480, 1000.0, 320.0, 240.0, 0.0);
    s.frames_drawn = 120;
    setHold(s, {10.0, 30.0, 28.0, 120.0, Vec3(0.3, 0.9, 0.3), 0.2, 0.1, 150.0, 0.05, 200.0});
    s.target_brightness = 0.75;
    s.render.background = 0.05;
    s.render.noise_sigma = 0.05;
    s.render.blur_sigma_px = 0.6;
    s.render.shading = {true, 0.3, sun};
    if (slew) {
      s.events.slew = true;
      s.events.slew_frame = 40;
      s.events.slew_deg = 8.0;
      s.events.slew_axis_c = Vec3::UnitY();  // the target jumps sideways in the image
    } else {
      s.events.eclipse = true;
      s.events.eclipse_first = 48;  // frames 48..72: centred on frame 60 of 120
      s.events.eclipse_frames = 25;
    }
  } else if (name == "low_contrast_octagon") {
    // Field report 3: an octagonal plate, brightness 0.25, on a gradient whose level crosses it (contrast
    // +0.2 -> 0 -> -0.3 along the outline), drifting bright blobs, noise 0.1.
    s.family = Family::kOctagon;
    s.seed = 104;
    s.model = makeRegularOctagonPlate(1.0);
    s.model_text = "regular octagon r 1.000 m";
    s.camera = makeCamera(1024, 768, 1200.0, 512.0, 384.0, -0.03);
    s.frames_drawn = 150;
    setHold(s, {10.0, 10.0, 15.0, 30.0, Vec3(0.2, 0.3, 1.0), 0.1, 0.3, 160.0, 0.2, 200.0});
    s.target_brightness = 0.25;
    s.render.noise_sigma = 0.1;
    s.render.blur_sigma_px = 0.7;
    s.background = BackgroundKind::kGradient;
    s.drifting_blobs = true;
  } else if (name == "approach_smallsat") {
    // Field report 5: the satellite with panels from 750 m to 5 m, no pose given (far range, acquisition).
    s.family = Family::kSmallsat;
    s.seed = 105;
    s.model = models.smallsat;
    s.model_text = "smallsat " + models.smallsat_path;
    s.camera = makeCamera(640, 480, 1000.0, 320.0, 240.0, -0.05, 0.01);  // vga_6mm_distorted
    s.frames_drawn = 200;
    setHold(s, {750.0, 0.0, 10.0, 0.0, Vec3::UnitZ(), 0.0, 0.2, 120.0, 0.1, 160.0});
    s.approach = true;
    s.d_end_m = 5.0;
    s.target_brightness = 0.75;
    s.render.noise_sigma = 0.05;
    s.render.blur_sigma_px = 0.5;
  } else {
    std::string list;
    for (const std::string& n : caseNames()) list += (list.empty() ? "" : ", ") + n;
    return LoadError::failure("unknown case '" + name + "' (cases: " + list + ", all)");
  }
  if (s.model.surfaces().empty()) return LoadError::failure(name + ": the model is not loaded");
  s.frames = detail::capFrames(s.frames_drawn, max_frames);
  s.render.target_brightness = s.target_brightness;
  s.noise_seed = detail::splitmix64(s.seed);
  // Field report 3's contrast: +0.2 -> 0 -> -0.3 along the outline.
  if (s.background == BackgroundKind::kGradient)
    detail::applyGradient(s, s.truth(0), 0.2, 0.3, 30.0 * kRadPerDeg, 0.3);
  if (s.drifting_blobs) {
    const double w = s.camera.width_px;
    const double h = s.camera.height_px;
    const double peaks[3] = {0.45, 0.4, 0.5};
    const double sigmas[3] = {30.0, 45.0, 25.0};
    const Vec2 from[3] = {{0.1 * w, 0.2 * h}, {0.9 * w, 0.8 * h}, {0.3 * w, 0.95 * h}};
    const Vec2 to[3] = {{0.8 * w, 0.6 * h}, {0.2 * w, 0.3 * h}, {0.6 * w, 0.05 * h}};
    for (int g = 0; g < 3; ++g) {
      synthetic::Glint glint;
      glint.first_frame = 0;
      glint.last_frame = s.frames - 1;
      glint.start_px = from[g];
      glint.end_px = to[g];
      glint.sigma_px = sigmas[g];
      glint.peak = peaks[g];
      s.render.glints.push_back(glint);
    }
  }
  detail::finishScene(s);
  out = std::move(s);
  return LoadError::success();
}

}  // namespace visnav::campaign
