#include "scenario.hpp"

#include <cmath>
#include <filesystem>

#include "visnav/replay/toml_reader.hpp"

namespace visnav::synth {
namespace {

double wave(double amp, double period_frames, int frame) {
  return amp == 0.0 ? 0.0 : amp * std::sin(2.0 * kPi * frame / period_frames);
}

}  // namespace

int Trajectory::frameCount() const {
  if (step_rel > 0.0) {
    const double factor = d_end_m >= d_start_m ? 1.0 + step_rel : 1.0 - step_rel;
    return static_cast<int>(std::floor(std::log(d_end_m / d_start_m) / std::log(factor) + 1e-6)) + 1;
  }
  // The tolerance absorbs 20 / 0.01 = 1999.9999999999998 style round-off.
  return static_cast<int>(std::floor(std::abs(d_end_m - d_start_m) / step_m + 1e-6)) + 1;
}

Pose Trajectory::pose(int frame) const {
  const double dir = d_end_m >= d_start_m ? 1.0 : -1.0;
  const double distance =
      step_rel > 0.0 ? d_start_m * std::pow(1.0 + dir * step_rel, frame) : d_start_m + dir * step_m * frame;
  const YawPitchRoll ypr{(base_yaw_deg + wave(yaw_amp_deg, yaw_period_frames, frame)) * kRadPerDeg,
                         (base_pitch_deg + wave(pitch_amp_deg, pitch_period_frames, frame)) * kRadPerDeg,
                         (base_roll_deg + wave(roll_amp_deg, roll_period_frames, frame)) * kRadPerDeg};
  Vec3 t(wave(lateral_x_amp_m, lateral_x_period_frames, frame),
         wave(lateral_y_amp_m, lateral_y_period_frames, frame), distance);
  if (lateral_x_amp_deg != 0.0)
    t.x() += distance * std::tan(wave(lateral_x_amp_deg, lateral_x_period_frames, frame) * kRadPerDeg);
  if (lateral_y_amp_deg != 0.0)
    t.y() += distance * std::tan(wave(lateral_y_amp_deg, lateral_y_period_frames, frame) * kRadPerDeg);
  Pose p = Pose::fromYpr(ypr, t);
  if (!tumble_rate_deg_per_frame.isZero()) {
    p.R_c_m = p.R_c_m * expSo3(tumble_rate_deg_per_frame * (kRadPerDeg * frame));
  }
  return p;
}

std::int64_t Trajectory::timestampNs(int frame) const { return std::llround(frame * 1e9 / rate_hz); }

LoadError loadScenario(const std::string& path, Scenario& out) {
  replay::TomlReader r;
  LoadError e = r.open(path);
  if (!e.ok) return e;
  Scenario s;
  s.path = path;
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  std::string camera;
  std::string model;
  std::int64_t seed = 1;
  std::int64_t max_code = 255;
  r.getString("name", s.name, true);
  r.getString("camera", camera, true);
  r.getString("model", model, true);
  r.getInt("seed", seed);
  r.checkRange("seed", static_cast<double>(seed), 0.0, 9.2e18);
  r.getInt("bit_depth", s.bit_depth);
  if (r.good() && s.bit_depth != 8 && s.bit_depth != 16) r.fail("bit_depth", "must be 8 or 16");
  max_code = s.bit_depth == 8 ? 255 : 65535;
  r.getInt("max_code", max_code);
  r.checkRange("max_code", static_cast<double>(max_code), 1.0, s.bit_depth == 8 ? 255.0 : 65535.0);

  Trajectory& t = s.trajectory;
  r.getDouble("trajectory.d_start_m", t.d_start_m, true);
  r.getDouble("trajectory.d_end_m", t.d_end_m, true);
  const bool geometric = r.has("trajectory.step_rel");
  r.getDouble("trajectory.step_rel", t.step_rel);
  r.getDouble("trajectory.step_m", t.step_m, !geometric);
  if (geometric) r.checkRange("trajectory.step_rel", t.step_rel, 1e-6, 0.5);
  r.getDouble("trajectory.rate_hz", t.rate_hz, true);
  r.checkRange("trajectory.d_start_m", t.d_start_m, 0.1, 1e5);
  r.checkRange("trajectory.d_end_m", t.d_end_m, 0.1, 1e5);
  r.checkRange("trajectory.step_m", t.step_m, 1e-6, 1e5);
  r.checkRange("trajectory.rate_hz", t.rate_hz, 1e-3, 1e4);
  r.getDouble("trajectory.base_yaw_deg", t.base_yaw_deg);
  r.getDouble("trajectory.base_pitch_deg", t.base_pitch_deg);
  r.getDouble("trajectory.base_roll_deg", t.base_roll_deg);
  const struct {
    const char* amp;
    const char* period;
    double* amp_value;
    double* period_value;
  } waves[] = {{"lateral_x_amp_m", "lateral_x_period_frames", &t.lateral_x_amp_m, &t.lateral_x_period_frames},
               {"lateral_y_amp_m", "lateral_y_period_frames", &t.lateral_y_amp_m, &t.lateral_y_period_frames},
               {"yaw_amp_deg", "yaw_period_frames", &t.yaw_amp_deg, &t.yaw_period_frames},
               {"pitch_amp_deg", "pitch_period_frames", &t.pitch_amp_deg, &t.pitch_period_frames},
               {"roll_amp_deg", "roll_period_frames", &t.roll_amp_deg, &t.roll_period_frames}};
  for (const auto& w : waves) {
    r.getDouble(std::string("trajectory.") + w.amp, *w.amp_value);
    r.getDouble(std::string("trajectory.") + w.period, *w.period_value);
    if (r.good() && !(*w.period_value > 0.0)) r.fail(std::string("trajectory.") + w.period, "must be > 0");
  }
  r.getVector("trajectory.tumble_rate_deg_per_frame", t.tumble_rate_deg_per_frame.data(), 3);
  r.getDouble("trajectory.lateral_x_amp_deg", t.lateral_x_amp_deg);
  r.getDouble("trajectory.lateral_y_amp_deg", t.lateral_y_amp_deg);
  r.checkRange("trajectory.lateral_x_amp_deg", t.lateral_x_amp_deg, -80.0, 80.0);
  r.checkRange("trajectory.lateral_y_amp_deg", t.lateral_y_amp_deg, -80.0, 80.0);

  synthetic::RenderOptions& o = s.render;
  r.getDouble("render.background", o.background);
  r.checkRange("render.background", o.background, 0.0, 1.0);
  r.getDouble("render.target_brightness", o.target_brightness);
  r.checkRange("render.target_brightness", o.target_brightness, -1.0, 1.0);
  r.getArray("render.surface_albedo", o.surface_albedo, 1000);
  r.getDouble("render.noise_sigma", o.noise_sigma);
  r.checkRange("render.noise_sigma", o.noise_sigma, 0.0, 1.0);
  r.getInt("render.blur_size_px", o.blur_size_px);
  r.getDouble("render.blur_sigma_px", o.blur_sigma_px);
  r.getDouble("render.max_segment_px", o.max_segment_px);
  r.checkRange("render.max_segment_px", o.max_segment_px, 0.01, 100.0);

  r.getBool("render.shading.enabled", o.shading.enabled);
  r.getDouble("render.shading.ambient", o.shading.ambient);
  r.checkRange("render.shading.ambient", o.shading.ambient, 0.0, 1.0);
  r.getVector("render.shading.sun_dir_c", o.shading.sun_dir_c.data(), 3);
  if (r.good() && !(o.shading.sun_dir_c.norm() > 1e-9))
    r.fail("render.shading.sun_dir_c", "must be non-zero");

  double centre[2] = {o.limb.center_x_px, o.limb.center_y_px};
  r.getBool("render.limb.enabled", o.limb.enabled);
  r.getVector("render.limb.center_px", centre, 2);
  o.limb.center_x_px = centre[0];
  o.limb.center_y_px = centre[1];
  r.getDouble("render.limb.radius_px", o.limb.radius_px);
  r.checkRange("render.limb.radius_px", o.limb.radius_px, 1.0, 1e6);
  r.getDouble("render.limb.brightness_limb", o.limb.brightness_limb);
  r.getDouble("render.limb.brightness_centre", o.limb.brightness_centre);
  r.getDouble("render.limb.softness_px", o.limb.softness_px);
  r.checkRange("render.limb.softness_px", o.limb.softness_px, 0.01, 1e5);

  std::int64_t blob_seed = seed;
  r.getInt("render.blobs.count", o.blobs.count);
  r.checkRange("render.blobs.count", o.blobs.count, 0.0, 10000.0);
  r.getInt("render.blobs.seed", blob_seed);
  r.checkRange("render.blobs.seed", static_cast<double>(blob_seed), 0.0, 9.2e18);
  r.getDouble("render.blobs.radius_min_px", o.blobs.radius_min_px);
  r.getDouble("render.blobs.radius_max_px", o.blobs.radius_max_px);
  r.getDouble("render.blobs.brightness_min", o.blobs.brightness_min);
  r.getDouble("render.blobs.brightness_max", o.blobs.brightness_max);
  readDynamicClutter(r, o);
  e = r.finish();
  if (!e.ok) return e;

  s.seed = static_cast<std::uint64_t>(seed);
  s.max_code = static_cast<std::uint16_t>(max_code);
  o.blobs.seed = static_cast<std::uint64_t>(blob_seed);
  s.camera_path = (base / camera).lexically_normal().string();
  s.model_path = (base / model).lexically_normal().string();
  out = std::move(s);
  return LoadError::success();
}

}  // namespace visnav::synth
