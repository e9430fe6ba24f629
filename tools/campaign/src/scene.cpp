#include "visnav/campaign/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "scene_parts.hpp"

namespace visnav::campaign {
namespace {

double wave(double amp, double period, int frame) {
  return amp == 0.0 ? 0.0 : amp * std::sin(2.0 * kPi * frame / period);
}

double logistic(double x) { return 1.0 / (1.0 + std::exp(-x)); }

/// Brightness of the most face-on front surface at `pose` (the level a gradient must cross).
double effectiveBrightness(const Scene& s, const Pose& pose) {
  double best_cos = -2.0;
  double brightness = s.target_brightness;
  for (const ModelSurface& surf : s.model.surfaces()) {
    const Vec3 n_c = pose.R_c_m * surf.normal_m;
    const Vec3 c_c = pose.transform(surf.centroid_m);
    const double facing = -n_c.dot(c_c.normalized());
    if (facing <= 0.0 || facing <= best_cos) continue;
    best_cos = facing;
    brightness = s.target_brightness;
    if (s.render.shading.enabled) {
      const double lambert = std::max(0.0, -n_c.dot(s.render.shading.sun_dir_c.normalized()));
      brightness *= s.render.shading.ambient + (1.0 - s.render.shading.ambient) * lambert;
    }
  }
  return brightness;
}

}  // namespace

namespace detail {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

Mat3 baseAttitude(double yaw_deg, double tilt_deg, double tilt_dir_deg) {
  // Face-on (model +z towards the camera, Rx(180)), turned about the boresight, then tilted about an axis
  // in the image plane.
  const Vec3 tilt_axis(std::cos(tilt_dir_deg * kRadPerDeg), std::sin(tilt_dir_deg * kRadPerDeg), 0.0);
  return expSo3(tilt_axis * (tilt_deg * kRadPerDeg)) * expSo3(Vec3::UnitZ() * (yaw_deg * kRadPerDeg)) *
         expSo3(Vec3::UnitX() * kPi);
}

CameraIntrinsics makeCamera(int w, int h, double f, double cx, double cy, double k1, double k2) {
  CameraIntrinsics k;
  k.width_px = w;
  k.height_px = h;
  k.fx_px = f;
  k.fy_px = f;
  k.cx_px = cx;
  k.cy_px = cy;
  k.distortion.k1 = k1;
  k.distortion.k2 = k2;
  return k;
}

int capFrames(int drawn, int max_frames) { return max_frames > 0 ? std::min(drawn, max_frames) : drawn; }

void applyGradient(Scene& s, const Pose& pose, double contrast_plus, double contrast_minus, double angle_rad,
                   double softness_rel) {
  const Silhouette sil = s.silhouette(pose);
  const double r = 0.7 * sil.radius_px;
  const GradientSolution g =
      solveGradient(effectiveBrightness(s, pose), contrast_plus, contrast_minus, sil.centre_px, r, angle_rad,
                    softness_rel * r, std::max(s.camera.width_px, s.camera.height_px));
  s.render.background = g.background;
  s.render.limb = g.limb;
  s.gradient_contrast_plus = g.contrast_plus;
  s.gradient_contrast_minus = g.contrast_minus;
}

/// Symmetries and gamma: what every scene derives from its model and camera.
void finishScene(Scene& s) {
  s.symmetries = modelSymmetries(s.model);
  s.gamma = s.camera.fx_px * std::sqrt(faceOnArea(s.model));
}

}  // namespace detail

using detail::fmt;

const char* toString(Family family) {
  switch (family) {
    case Family::kPlate: return "plate";
    case Family::kOctagon: return "octagon";
    case Family::kBox: return "box";
    case Family::kSmallsat: return "smallsat";
    case Family::kCao: return "cao";
  }
  return "?";
}

bool parseFamily(const std::string& text, Family& out) {
  for (int f = 0; f < kFamilyCount; ++f) {
    if (text == toString(static_cast<Family>(f))) {
      out = static_cast<Family>(f);
      return true;
    }
  }
  return false;
}

const char* toString(BackgroundKind kind) {
  switch (kind) {
    case BackgroundKind::kSpace: return "space";
    case BackgroundKind::kGradient: return "gradient";
    case BackgroundKind::kLimb: return "limb";
    case BackgroundKind::kBlobs: return "blobs";
    case BackgroundKind::kDrifting: return "drifting";
  }
  return "?";
}

double faceOnArea(const PolygonModel& model) {
  double area = 0.0;
  for (const ModelSurface& s : model.surfaces()) {
    if (s.normal_m.z() <= 1e-9) continue;
    double a2 = 0.0;
    const auto& idx = s.vertex_indices;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const Vec3& p = model.vertices()[static_cast<std::size_t>(idx[k])];
      const Vec3& q = model.vertices()[static_cast<std::size_t>(idx[(k + 1) % idx.size()])];
      a2 += p.x() * q.y() - q.x() * p.y();
    }
    area += 0.5 * std::fabs(a2);
  }
  return area;
}

GradientSolution solveGradient(double target, double contrast_plus, double contrast_minus,
                               const Vec2& centre_px, double outline_radius_px, double angle_rad,
                               double softness_px, double image_size_px) {
  // Background along the ramp direction at signed depth x (x = d_c at the target centre):
  // v(x) = bg + D logistic(x / s). Contrast is target - v: +c_plus at x = d_c - r, 0 at d_c, -c_minus at
  // d_c + r. The ratio c_minus / c_plus fixes d_c (monotonic: bisection), then D and bg follow.
  const double r = std::max(1.0, outline_radius_px);
  const double s = std::max(1.0, softness_px);
  const double want = contrast_minus / std::max(1e-9, contrast_plus);
  auto ratio = [&](double dc) {
    const double a0 = logistic(dc / s);
    return (logistic((dc + r) / s) - a0) / std::max(1e-300, a0 - logistic((dc - r) / s));
  };
  double lo = -20.0 * s;  // ratio large (upper side steep)
  double hi = 20.0 * s;   // ratio small
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (ratio(mid) > want)
      lo = mid;
    else
      hi = mid;
  }
  const double dc = 0.5 * (lo + hi);
  const double a0 = logistic(dc / s);
  const double am = logistic((dc - r) / s);
  const double ap = logistic((dc + r) / s);
  double D = contrast_plus / std::max(1e-12, a0 - am);
  D = std::min(D, target / std::max(1e-12, a0));                // bg >= 0
  D = std::min(D, (1.0 - target) / std::max(1e-12, 1.0 - a0));  // bg + D <= 1
  GradientSolution out;
  out.background = std::clamp(target - D * a0, 0.0, 1.0);
  out.contrast_plus = D * (a0 - am);
  out.contrast_minus = D * (ap - a0);
  // A disc so large that its boundary is a straight line over the image; its inside level is flat.
  const double radius = 50.0 * std::max(1.0, image_size_px);
  const Vec2 u(std::cos(angle_rad), std::sin(angle_rad));  // towards the bright side
  const Vec2 centre = centre_px + u * (radius - dc);
  out.limb.enabled = true;
  out.limb.center_x_px = centre.x();
  out.limb.center_y_px = centre.y();
  out.limb.radius_px = radius;
  out.limb.brightness_limb = std::clamp(out.background + D, 0.0, 1.0);
  out.limb.brightness_centre = out.limb.brightness_limb;
  out.limb.softness_px = s;
  return out;
}

double Scene::distance(int frame) const {
  const double s = frames > 1 ? static_cast<double>(frame) / (frames - 1) : 0.0;
  if (approach) return d_start_m * std::pow(d_end_m / d_start_m, s);
  return d_start_m + (d_end_m - d_start_m) * s;
}

Pose Scene::truth(int frame) const {
  Pose p;
  p.t_c_m = Vec3(wave(lateral_x_amp_m, lateral_x_period_frames, frame),
                 wave(lateral_y_amp_m, lateral_y_period_frames, frame), distance(frame));
  p.R_c_m = R_base * expSo3(tumble_axis_m * (tumble_deg_per_frame * kRadPerDeg * frame));
  if (events.slew && frame >= events.slew_frame) {
    // The line of sight jumps: the camera turns, so the truth turns with it (left-multiplied).
    const Mat3 R_s = expSo3(events.slew_axis_c * (events.slew_deg * kRadPerDeg));
    p.R_c_m = R_s * p.R_c_m;
    p.t_c_m = R_s * p.t_c_m;
  }
  return p;
}

bool Scene::eclipsed(int frame) const {
  return events.eclipse && frame >= events.eclipse_first &&
         frame < events.eclipse_first + events.eclipse_frames;
}

std::int64_t Scene::timestampNs(int frame) const { return std::llround(frame * 1e9 / rate_hz); }

Silhouette Scene::silhouette(const Pose& T_c_m) const {
  Silhouette s;
  const double z = T_c_m.t_c_m.z();
  if (!(z > 1e-6)) return s;
  Vec2 px;
  if (!PinholeCamera(camera).project(T_c_m.t_c_m, px)) return s;
  s.in_front = true;
  s.centre_px = px;
  s.radius_px = camera.fx_px * model.boundingRadius() / z;
  return s;
}

std::vector<SceneParam> sceneParameters(const Scene& s) {
  std::vector<SceneParam> p;
  auto num = [&](const char* key, double v) { p.push_back({key, fmt("%.6g", v), true}); };
  auto text = [&](const char* key, const std::string& v) { p.push_back({key, v, false}); };
  const CameraIntrinsics& k = s.camera;
  const synthetic::RenderOptions& r = s.render;
  text("model", s.model_text);
  num("bounding_radius_m", s.model.boundingRadius());
  std::string syms;
  for (const Symmetry& sym : s.symmetries) syms += (syms.empty() ? "" : " ") + sym.name;
  text("symmetries", syms);
  num("width_px", k.width_px);
  num("height_px", k.height_px);
  num("f_px", k.fx_px);
  num("cx_px", k.cx_px);
  num("cy_px", k.cy_px);
  num("k1", k.distortion.k1);
  num("k2", k.distortion.k2);
  num("noise_sigma", r.noise_sigma);
  num("blur_sigma_px", r.blur_sigma_px);
  num("blur_size_px", r.blur_size_px);
  num("target_brightness", s.target_brightness);
  num("background", r.background);
  text("background_kind", toString(s.background));
  num("drifting_blobs", s.drifting_blobs ? 1 : 0);
  num("gradient_contrast_plus", s.gradient_contrast_plus);
  num("gradient_contrast_minus", s.gradient_contrast_minus);
  num("shading", r.shading.enabled ? 1 : 0);
  num("ambient", r.shading.enabled ? r.shading.ambient : 0.0);
  const Vec3 sun = r.shading.sun_dir_c.normalized();
  num("sun_x", sun.x());
  num("sun_y", sun.y());
  num("sun_z", sun.z());
  num("approach", s.approach ? 1 : 0);
  num("frames", s.frames);
  num("frames_drawn", s.frames_drawn);
  num("d_start_m", s.d_start_m);
  num("d_end_m", s.d_end_m);
  num("yaw_deg", s.yaw_deg);
  num("tilt_deg", s.tilt_deg);
  num("tilt_dir_deg", s.tilt_dir_deg);
  num("tumble_deg_per_frame", s.tumble_deg_per_frame);
  num("tumble_axis_x", s.tumble_axis_m.x());
  num("tumble_axis_y", s.tumble_axis_m.y());
  num("tumble_axis_z", s.tumble_axis_m.z());
  num("lateral_x_amp_m", s.lateral_x_amp_m);
  num("lateral_x_period_frames", s.lateral_x_period_frames);
  num("lateral_y_amp_m", s.lateral_y_amp_m);
  num("lateral_y_period_frames", s.lateral_y_period_frames);
  num("eclipse_first", s.events.eclipse ? s.events.eclipse_first : -1);
  num("eclipse_frames", s.events.eclipse ? s.events.eclipse_frames : 0);
  num("slew_frame", s.events.slew ? s.events.slew_frame : -1);
  num("slew_deg", s.events.slew ? s.events.slew_deg : 0.0);
  num("slew_axis_x", s.events.slew ? s.events.slew_axis_c.x() : 0.0);
  num("slew_axis_y", s.events.slew ? s.events.slew_axis_c.y() : 0.0);
  num("gamma", s.gamma);
  char seed[32];
  std::snprintf(seed, sizeof(seed), "%llu", static_cast<unsigned long long>(s.noise_seed));
  text("noise_seed", seed);
  return p;
}

}  // namespace visnav::campaign
