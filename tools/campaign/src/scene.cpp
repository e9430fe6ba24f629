#include "visnav/campaign/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "visnav/core/rng.hpp"

namespace visnav::campaign {
namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

std::uint64_t fnv1a(const char* s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (; *s != '\0'; ++s) h = (h ^ static_cast<unsigned char>(*s)) * 0x100000001b3ULL;
  return h;
}

// One Pcg32 stream per aspect of a scene, so a new draw in one aspect never shifts another.
constexpr std::uint64_t kStreamModel = 0x6d6f64656cULL;       // "model"
constexpr std::uint64_t kStreamCamera = 0x63616d657261ULL;    // "camera"
constexpr std::uint64_t kStreamImage = 0x696d616765ULL;       // "image"
constexpr std::uint64_t kStreamMotion = 0x6d6f74696f6eULL;    // "motion"
constexpr std::uint64_t kStreamEvents = 0x6576656e7473ULL;    // "events"
constexpr std::uint64_t kStreamBackground = 0x6261636b67ULL;  // "backg"
constexpr std::uint64_t kStreamNoise = 0x6e6f697365ULL;       // "noise"
constexpr int kMaxGlints = 5;

class Draw {
 public:
  Draw(std::uint64_t base, std::uint64_t stream) : m_rng(base, stream) {}
  double uniform() { return m_rng.uniform(); }
  double uni(double lo, double hi) { return lo + (hi - lo) * m_rng.uniform(); }
  int integer(int lo, int hi) {
    return lo + static_cast<int>(m_rng.below(static_cast<std::uint32_t>(hi - lo + 1)));
  }
  bool chance(double p) { return m_rng.uniform() < p; }
  std::uint64_t u64() {
    const std::uint64_t hi = m_rng.next();
    const std::uint64_t lo = m_rng.next();
    return (hi << 32U) | lo;
  }

 private:
  Pcg32 m_rng;
};

double wave(double amp, double period, int frame) {
  return amp == 0.0 ? 0.0 : amp * std::sin(2.0 * kPi * frame / period);
}

Mat3 baseAttitude(double yaw_deg, double tilt_deg, double tilt_dir_deg) {
  // Face-on (model +z towards the camera, Rx(180)), turned about the boresight, then tilted about an axis
  // in the image plane.
  const Vec3 tilt_axis(std::cos(tilt_dir_deg * kRadPerDeg), std::sin(tilt_dir_deg * kRadPerDeg), 0.0);
  return expSo3(tilt_axis * (tilt_deg * kRadPerDeg)) * expSo3(Vec3::UnitZ() * (yaw_deg * kRadPerDeg)) *
         expSo3(Vec3::UnitX() * kPi);
}

template <typename... Args>
std::string fmt(const char* format, Args... args) {
  char buf[128];
  std::snprintf(buf, sizeof(buf), format, args...);
  return buf;
}

CameraIntrinsics makeCamera(int w, int h, double f, double cx, double cy, double k1, double k2 = 0.0) {
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

/// Symmetries and gamma: what every scene derives from its model and camera.
void finishScene(Scene& s) {
  s.symmetries = modelSymmetries(s.model);
  s.gamma = s.camera.fx_px * std::sqrt(faceOnArea(s.model));
}

int capFrames(int drawn, int max_frames) { return max_frames > 0 ? std::min(drawn, max_frames) : drawn; }

/// Fraction of frames from `first` on whose bounding circle lies inside the image.
double inViewFraction(const Scene& s, int first) {
  int inside = 0;
  int total = 0;
  for (int i = first; i < s.frames; ++i) {
    const Silhouette sil = s.silhouette(s.truth(i));
    ++total;
    if (sil.in_front && sil.centre_px.x() - sil.radius_px >= 0.0 &&
        sil.centre_px.y() - sil.radius_px >= 0.0 && sil.centre_px.x() + sil.radius_px <= s.camera.width_px &&
        sil.centre_px.y() + sil.radius_px <= s.camera.height_px)
      ++inside;
  }
  return total > 0 ? static_cast<double>(inside) / total : 0.0;
}

void addGlints(Scene& s, Draw& d, int count) {
  // Drifting bright blobs: wide Gaussian spots crossing the image linearly over the whole scene.
  const double w = s.camera.width_px;
  const double h = s.camera.height_px;
  for (int g = 0; g < kMaxGlints; ++g) {
    synthetic::Glint glint;
    glint.first_frame = 0;
    glint.last_frame = std::max(0, s.frames - 1);
    glint.start_px = Vec2(d.uniform() * w, d.uniform() * h);
    glint.end_px = Vec2(d.uniform() * w, d.uniform() * h);
    glint.sigma_px = d.uni(15.0, 60.0);
    glint.peak = d.uni(0.2, 0.6);
    if (g < count) s.render.glints.push_back(glint);  // always 5 draws: the stream stays aligned
  }
}

}  // namespace

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

PolygonModel makeOctagonPlate(double width_m, double height_m, double chamfer_m) {
  const double hx = 0.5 * width_m;
  const double hy = 0.5 * height_m;
  const double c = chamfer_m;
  // Counter-clockwise seen from +z (the plate's normal), as makeRectanglePlate.
  const std::vector<Vec3> v = {{hx - c, -hy, 0.0},  {hx, -hy + c, 0.0}, {hx, hy - c, 0.0},
                               {hx - c, hy, 0.0},   {-hx + c, hy, 0.0}, {-hx, hy - c, 0.0},
                               {-hx, -hy + c, 0.0}, {-hx + c, -hy, 0.0}};
  ModelSurface s;
  s.name = "plate";
  s.vertex_indices = {0, 1, 2, 3, 4, 5, 6, 7};
  PolygonModel m;
  PolygonModel::build(v, {s}, m);
  return m;
}

PolygonModel makeRegularOctagonPlate(double circumradius_m) {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k) {
    const double a = (22.5 + 45.0 * k) * kRadPerDeg;
    v.emplace_back(circumradius_m * std::cos(a), circumradius_m * std::sin(a), 0.0);
  }
  ModelSurface s;
  s.name = "plate";
  s.vertex_indices = {0, 1, 2, 3, 4, 5, 6, 7};
  PolygonModel m;
  PolygonModel::build(v, {s}, m);
  return m;
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

LoadError drawScene(Family family, std::uint64_t seed, const ModelLibrary& models, int max_frames,
                    Scene& out) {
  Scene s;
  s.family = family;
  s.seed = seed;
  s.name = std::string(toString(family)) + "/" + std::to_string(seed);
  const std::uint64_t base = splitmix64(seed ^ fnv1a(toString(family)));
  Draw dm(base, kStreamModel), dc(base, kStreamCamera), di(base, kStreamImage), dmo(base, kStreamMotion),
      de(base, kStreamEvents), db(base, kStreamBackground), dn(base, kStreamNoise);

  // Model.
  switch (family) {
    case Family::kPlate: {
      const double w = dm.uni(1.0, 3.0);
      const double h = dm.uni(1.0, 3.0);
      s.model = makeRectanglePlate(w, h);
      s.model_text = fmt("plate %.3fx%.3f m", w, h);
      break;
    }
    case Family::kOctagon: {
      const bool regular = dm.chance(0.3);
      const double rc = dm.uni(0.6, 1.5);
      const double w = dm.uni(1.0, 3.0);
      const double h = dm.uni(1.0, 3.0);
      const double cf = dm.uni(0.15, 0.35);
      if (regular) {
        s.model = makeRegularOctagonPlate(rc);
        s.model_text = fmt("regular octagon r %.3f m", rc);
      } else {
        s.model = makeOctagonPlate(w, h, cf * std::min(w, h));
        s.model_text = fmt("octagon %.3fx%.3f m chamfer %.3f m", w, h, cf * std::min(w, h));
      }
      break;
    }
    case Family::kBox: {
      const double hx = dm.uni(0.3, 1.0);
      const double hy = dm.uni(0.3, 1.0);
      const double hz = dm.uni(0.3, 1.0);
      s.model = makeBox(hx, hy, hz);
      s.model_text = fmt("box half %.3fx%.3fx%.3f m", hx, hy, hz);
      break;
    }
    case Family::kSmallsat:
      s.model = models.smallsat;
      s.model_text = "smallsat " + models.smallsat_path;
      break;
    case Family::kCao:
      s.model = models.cao;
      s.model_text = "cao " + models.cao_path;
      break;
  }
  if (s.model.surfaces().empty()) return LoadError::failure(s.name + ": the family's model is not loaded");

  // Camera.
  static const int kSizes[4][2] = {{640, 480}, {800, 600}, {1024, 768}, {1280, 1024}};
  const int size = dc.integer(0, 3);
  const double f = dc.uni(600.0, 1400.0);
  const double cx_off = dc.uni(-0.02, 0.02);
  const double cy_off = dc.uni(-0.02, 0.02);
  const bool no_distortion = dc.chance(0.3);
  const double k1 = dc.uni(-0.08, 0.02);
  const int W = kSizes[size][0];
  const int H = kSizes[size][1];
  s.camera = makeCamera(W, H, f, 0.5 * W * (1.0 + 2.0 * cx_off), 0.5 * H * (1.0 + 2.0 * cy_off),
                        no_distortion ? 0.0 : k1);

  // Image.
  s.render.noise_sigma = di.uni(0.02, 0.12);
  s.render.blur_sigma_px = di.uni(0.3, 1.2);
  s.render.blur_size_px = di.chance(0.5) ? 7 : 5;
  s.target_brightness = di.uni(0.25, 0.9);
  s.render.target_brightness = s.target_brightness;
  s.render.shading.enabled = di.chance(0.5);
  s.render.shading.ambient = di.uni(0.1, 0.6);
  // Sun behind the chaser (light travels along +z_c), up to 70 deg off the boresight.
  const double sun_theta = di.uni(0.0, 70.0) * kRadPerDeg;
  const double sun_phi = di.uni(0.0, 360.0) * kRadPerDeg;
  s.render.shading.sun_dir_c = Vec3(std::sin(sun_theta) * std::cos(sun_phi),
                                    std::sin(sun_theta) * std::sin(sun_phi), std::cos(sun_theta));

  // Motion.
  s.approach = dmo.chance(0.25);
  const int frames_near = dmo.integer(100, 200);
  const int frames_approach = dmo.integer(150, 250);
  const bool hold = dmo.chance(0.5);
  const double da = dmo.uniform();
  const double dd = dmo.uniform();
  const double d_end_approach = dmo.uni(5.0, 10.0);
  s.yaw_deg = dmo.uni(0.0, 360.0);
  s.tilt_deg = dmo.uni(0.0, 35.0);
  s.tilt_dir_deg = dmo.uni(0.0, 360.0);
  s.tumble_deg_per_frame = dmo.uni(0.0, 1.0);
  const double axis_z = dmo.uni(-1.0, 1.0);
  const double axis_phi = dmo.uni(0.0, 2.0 * kPi);
  const double lat_x = dmo.uni(0.0, 0.8);
  s.lateral_x_period_frames = dmo.uni(60.0, 300.0);
  const double lat_y = dmo.uni(0.0, 0.8);
  s.lateral_y_period_frames = dmo.uni(60.0, 300.0);

  const double axis_r = std::sqrt(std::max(0.0, 1.0 - axis_z * axis_z));
  s.tumble_axis_m = Vec3(axis_r * std::cos(axis_phi), axis_r * std::sin(axis_phi), axis_z);
  s.R_base = baseAttitude(s.yaw_deg, s.tilt_deg, s.tilt_dir_deg);
  s.frames_drawn = s.approach ? frames_approach : frames_near;
  s.frames = capFrames(s.frames_drawn, max_frames);
  // Near band: the bounding sphere at most 80 % of the short image side and at least 20 px across, within
  // 5..30 m (beyond 30 m only when the target cannot fit closer).
  const double R = s.model.boundingRadius();
  const double short_side = std::min(W, H);
  const double z_min = std::max(5.0, 2.0 * f * R / (0.8 * short_side));
  const double z_max = std::max(z_min, std::min(30.0, 2.0 * f * R / 20.0));
  double z_close = 0.0;
  if (s.approach) {
    s.d_start_m = 750.0;
    s.d_end_m = std::max(d_end_approach, z_min);
    z_close = s.d_end_m;
  } else {
    const double a = z_min + da * (z_max - z_min);
    const double b = z_min + dd * (z_max - z_min);
    s.d_start_m = hold ? a : std::max(a, b);
    s.d_end_m = hold ? a : std::min(a, b);
    z_close = s.d_end_m;
  }
  const double margin_m = std::max(0.0, (0.5 * short_side - 10.0) * z_close / f - R);
  s.lateral_x_amp_m = lat_x * margin_m;
  s.lateral_y_amp_m = lat_y * margin_m;

  // Events (eclipse, slew), inside [w0, w1]; approach scenes only once the target is close (< 25 m).
  const bool want_eclipse = de.chance(0.3);
  const int eclipse_len = de.integer(10, 50);
  const double eclipse_pos = de.uniform();
  const bool want_slew = de.chance(0.3);
  const double slew_deg = de.uni(3.0, 10.0);
  const double slew_pos = de.uniform();
  const double slew_dir = de.uniform();
  int w0 = 10;
  if (s.approach) {
    int close = s.frames / 2;
    for (int i = 0; i < s.frames; ++i)
      if (s.distance(i) <= 25.0) {
        close = i;
        break;
      }
    w0 = std::max(w0, close);
  }
  const int w1 = s.frames - 20;
  if (want_eclipse && w1 - w0 >= eclipse_len + 5) {
    s.events.eclipse = true;
    s.events.eclipse_frames = eclipse_len;
    s.events.eclipse_first = w0 + static_cast<int>(eclipse_pos * (w1 - w0 - eclipse_len));
  }
  if (want_slew) {
    auto allowed = [&](int i) {
      return !(s.events.eclipse && i >= s.events.eclipse_first - 10 &&
               i < s.events.eclipse_first + s.events.eclipse_frames + 10);
    };
    int count = 0;
    for (int i = w0; i <= w1; ++i) count += allowed(i) ? 1 : 0;
    if (count > 0) {
      int k = std::min(count - 1, static_cast<int>(slew_pos * count));
      for (int i = w0; i <= w1; ++i) {
        if (!allowed(i)) continue;
        if (k-- == 0) {
          s.events.slew_frame = i;
          break;
        }
      }
      s.events.slew = true;
      s.events.slew_deg = slew_deg;
      // Of eight directions, the one keeping the target in view longest (ties: the first).
      double best = -1.0;
      Vec3 best_axis = Vec3::UnitX();
      for (int d = 0; d < 8; ++d) {
        const double phi = 2.0 * kPi * (slew_dir + d / 8.0);
        s.events.slew_axis_c = Vec3(std::cos(phi), std::sin(phi), 0.0);
        const double score = inViewFraction(s, s.events.slew_frame);
        if (score > best) {
          best = score;
          best_axis = s.events.slew_axis_c;
        }
      }
      s.events.slew_axis_c = best_axis;
    }
  }

  // Background.
  s.background = static_cast<BackgroundKind>(db.integer(0, 4));
  const double level_frac = db.uniform();
  const double c_plus = db.uni(0.1, 0.3);
  const double c_minus = db.uni(0.1, 0.3);
  const double g_angle = db.uni(0.0, 2.0 * kPi);
  const double g_soft = db.uni(0.2, 0.5);  // softness / outline radius: levels reachable in [0, 1]
  const double limb_rf = db.uni(1.5, 4.0);
  const double limb_off = db.uni(-0.3, 0.3);
  const double limb_angle = db.uni(0.0, 2.0 * kPi);
  const double limb_b = db.uni(0.5, 0.8);
  const double limb_soft = db.uni(5.0, 40.0);
  const int blob_count = db.integer(10, 40);
  const std::uint64_t blob_seed = db.u64();
  const double blob_rmin = db.uni(10.0, 30.0);
  const double blob_rextra = db.uni(10.0, 50.0);
  const double blob_bmin = db.uni(0.05, 0.15);
  const double blob_bmax = db.uni(0.05, 0.2);
  const bool extra_drift = db.chance(0.25);
  const int glint_count = db.integer(2, kMaxGlints);
  // Flat level: some contrast is kept (the gradient kind is where contrast goes through zero).
  s.render.background = level_frac * std::min(0.3, 0.6 * s.target_brightness);
  switch (s.background) {
    case BackgroundKind::kSpace: break;
    case BackgroundKind::kGradient: {
      const int ref = s.approach ? s.frames - 1 : 0;
      const Pose pose = s.truth(ref);
      const Silhouette sil = s.silhouette(pose);
      const double r = 0.7 * sil.radius_px;
      const GradientSolution g = solveGradient(effectiveBrightness(s, pose), c_plus, c_minus, sil.centre_px,
                                               r, g_angle, g_soft * r, std::max(W, H));
      s.render.background = g.background;
      s.render.limb = g.limb;
      s.gradient_contrast_plus = g.contrast_plus;
      s.gradient_contrast_minus = g.contrast_minus;
      break;
    }
    case BackgroundKind::kLimb: {
      synthetic::LimbClutter& l = s.render.limb;
      l.enabled = true;
      l.radius_px = limb_rf * std::max(W, H);
      const Vec2 dir(std::cos(limb_angle), std::sin(limb_angle));
      const Vec2 c = Vec2(0.5 * W, 0.5 * H) + dir * (l.radius_px + limb_off * short_side);
      l.center_x_px = c.x();
      l.center_y_px = c.y();
      l.brightness_limb = limb_b;
      l.brightness_centre = std::min(1.0, limb_b + 0.1);
      l.softness_px = limb_soft;
      break;
    }
    case BackgroundKind::kBlobs: {
      synthetic::BlobClutter& b = s.render.blobs;
      b.count = blob_count;
      b.seed = blob_seed;
      b.radius_min_px = blob_rmin;
      b.radius_max_px = blob_rmin + blob_rextra;
      b.brightness_min = -blob_bmin;
      b.brightness_max = blob_bmax;
      break;
    }
    case BackgroundKind::kDrifting: break;
  }
  s.drifting_blobs = s.background == BackgroundKind::kDrifting || extra_drift;
  addGlints(s, db, s.drifting_blobs ? glint_count : 0);

  s.noise_seed = dn.u64();
  finishScene(s);
  out = std::move(s);
  return LoadError::success();
}

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
    s.family = Family::kBox;
    s.seed = 101;
    s.model = makeBox(0.8, 0.6, 0.5);
    s.model_text = "box half 0.800x0.600x0.500 m";
    s.camera = makeCamera(640, 480, 1000.0, 320.0, 240.0, 0.0);
    s.frames_drawn = 150;
    s.d_start_m = s.d_end_m = 8.0;
    s.yaw_deg = 20.0;
    s.tilt_deg = 32.0;  // two or three faces in view
    s.tilt_dir_deg = 60.0;
    s.R_base = baseAttitude(s.yaw_deg, s.tilt_deg, s.tilt_dir_deg);
    s.tumble_axis_m = Vec3(0.4, 1.0, 0.6).normalized();
    s.tumble_deg_per_frame = 0.6;
    s.lateral_x_amp_m = 0.15;
    s.lateral_x_period_frames = 140.0;
    s.lateral_y_amp_m = 0.1;
    s.lateral_y_period_frames = 180.0;
    s.target_brightness = 0.75;
    s.render.noise_sigma = 0.1;
    s.render.blur_sigma_px = 0.8;
    s.render.shading = {true, 0.2, sun};
  } else if (name == "eclipse_box" || name == "slew_box") {
    // Field report 2: a box at 10 m; a 5 s eclipse in the middle, or an 8 deg slew (~60 px) at frame 40.
    const bool slew = name == "slew_box";
    s.family = Family::kBox;
    s.seed = slew ? 103 : 102;
    s.model = makeBox(0.8, 0.6, 0.5);
    s.model_text = "box half 0.800x0.600x0.500 m";
    // The slew report's camera: 8 deg = 60 px means f = 60 / tan(8 deg) = 427 px.
    s.camera = slew ? makeCamera(640, 480, 427.0, 320.0, 240.0, 0.0)
                    : makeCamera(640, 480, 1000.0, 320.0, 240.0, 0.0);
    s.frames_drawn = 120;
    s.d_start_m = s.d_end_m = 10.0;
    s.yaw_deg = 30.0;
    s.tilt_deg = 28.0;
    s.tilt_dir_deg = 120.0;
    s.R_base = baseAttitude(s.yaw_deg, s.tilt_deg, s.tilt_dir_deg);
    s.tumble_axis_m = Vec3(0.3, 0.9, 0.3).normalized();
    s.tumble_deg_per_frame = 0.2;
    s.lateral_x_amp_m = 0.1;
    s.lateral_x_period_frames = 150.0;
    s.lateral_y_amp_m = 0.05;
    s.lateral_y_period_frames = 200.0;
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
    s.d_start_m = s.d_end_m = 10.0;
    s.yaw_deg = 10.0;
    s.tilt_deg = 15.0;
    s.tilt_dir_deg = 30.0;
    s.R_base = baseAttitude(s.yaw_deg, s.tilt_deg, s.tilt_dir_deg);
    s.tumble_axis_m = Vec3(0.2, 0.3, 1.0).normalized();
    s.tumble_deg_per_frame = 0.1;
    s.lateral_x_amp_m = 0.3;
    s.lateral_x_period_frames = 160.0;
    s.lateral_y_amp_m = 0.2;
    s.lateral_y_period_frames = 200.0;
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
    s.approach = true;
    s.frames_drawn = 200;
    s.d_start_m = 750.0;
    s.d_end_m = 5.0;
    s.tilt_deg = 10.0;
    s.R_base = baseAttitude(0.0, s.tilt_deg, 0.0);
    s.lateral_x_amp_m = 0.2;
    s.lateral_x_period_frames = 120.0;
    s.lateral_y_amp_m = 0.1;
    s.lateral_y_period_frames = 160.0;
    s.target_brightness = 0.75;
    s.render.noise_sigma = 0.05;
    s.render.blur_sigma_px = 0.5;
  } else {
    std::string list;
    for (const std::string& n : caseNames()) list += (list.empty() ? "" : ", ") + n;
    return LoadError::failure("unknown case '" + name + "' (cases: " + list + ", all)");
  }
  if (s.model.surfaces().empty()) return LoadError::failure(name + ": the model is not loaded");
  s.frames = capFrames(s.frames_drawn, max_frames);
  s.render.target_brightness = s.target_brightness;
  s.noise_seed = splitmix64(s.seed);
  if (s.background == BackgroundKind::kGradient) {
    const Pose pose = s.truth(0);
    const Silhouette sil = s.silhouette(pose);
    const double r = 0.7 * sil.radius_px;
    const GradientSolution g =
        solveGradient(effectiveBrightness(s, pose), 0.2, 0.3, sil.centre_px, r, 30.0 * kRadPerDeg, 0.3 * r,
                      std::max(s.camera.width_px, s.camera.height_px));
    s.render.background = g.background;
    s.render.limb = g.limb;
    s.gradient_contrast_plus = g.contrast_plus;
    s.gradient_contrast_minus = g.contrast_minus;
  }
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
  finishScene(s);
  out = std::move(s);
  return LoadError::success();
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
