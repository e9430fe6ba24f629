// The seeded draw of one random scene (family, seed): one Pcg32 stream per aspect.
#include <algorithm>
#include <cmath>

#include "scene_parts.hpp"
#include "visnav/core/rng.hpp"

namespace visnav::campaign {
namespace {

using detail::baseAttitude;
using detail::fmt;
using detail::makeCamera;

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

LoadError drawScene(Family family, std::uint64_t seed, const ModelLibrary& models, int max_frames,
                    Scene& out) {
  Scene s;
  s.family = family;
  s.seed = seed;
  s.name = std::string(toString(family)) + "/" + std::to_string(seed);
  const std::uint64_t base = detail::splitmix64(seed ^ fnv1a(toString(family)));
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
  s.frames = detail::capFrames(s.frames_drawn, max_frames);
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
    case BackgroundKind::kGradient:
      detail::applyGradient(s, s.truth(s.approach ? s.frames - 1 : 0), c_plus, c_minus, g_angle, g_soft);
      break;
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
  detail::finishScene(s);
  out = std::move(s);
  return LoadError::success();
}

}  // namespace visnav::campaign
