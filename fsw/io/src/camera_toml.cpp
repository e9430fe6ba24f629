// visnav's own TOML camera format (documented field by field in fsw/io/README.md).
#include <cmath>
#include <string>

#include "io_util.hpp"
#include "visnav/io/camera_io.hpp"

namespace visnav::io {
namespace {

using detail::TomlChecker;

constexpr std::int64_t kMaxImageSidePx = IntrinsicsLimits::kMaxImageSidePx;

bool imageSide(TomlChecker& check, const toml::table& cam, const char* key, int& out) {
  std::int64_t v = 0;
  if (!check.integer(cam, "[camera]", key, true, v)) return false;
  if (v <= 0 || v > kMaxImageSidePx)
    return check.fail(*cam.get(key), std::string("[camera] ") + key + " = " + std::to_string(v) +
                                         " out of range [1, " + std::to_string(kMaxImageSidePx) + "]");
  out = static_cast<int>(v);
  return true;
}

bool positive(TomlChecker& check, const toml::table& table, const std::string& name, const char* key,
              double& out) {
  if (!check.number(table, name, key, true, out)) return false;
  if (!(out > 0.0))
    return check.fail(*table.get(key),
                      name + " " + key + " = " + detail::formatDouble(out) + " out of range (must be > 0)");
  return true;
}

// Exactly one of the two focal length forms; returns fx, fy in pixels.
bool focalLength(TomlChecker& check, const toml::table& cam, double& fx_px, double& fy_px) {
  const bool si = cam.contains("focal_length_m") || cam.contains("pixel_pitch_m") ||
                  cam.contains("pixel_pitch_x_m") || cam.contains("pixel_pitch_y_m");
  const bool px = cam.contains("fx_px") || cam.contains("fy_px");
  if (si && px)
    return check.fail(cam, "[camera]: give either focal_length_m + pixel_pitch_m or fx_px + fy_px, not both");
  if (!si && !px)
    return check.fail(cam, "[camera]: missing key: give focal_length_m + pixel_pitch_m or fx_px + fy_px");
  if (px)
    return positive(check, cam, "[camera]", "fx_px", fx_px) &&
           positive(check, cam, "[camera]", "fy_px", fy_px);

  double f_m = 0.0;
  double gx_m = 0.0;
  double gy_m = 0.0;
  if (!positive(check, cam, "[camera]", "focal_length_m", f_m)) return false;
  const bool square = cam.contains("pixel_pitch_m");
  if (square && (cam.contains("pixel_pitch_x_m") || cam.contains("pixel_pitch_y_m")))
    return check.fail(cam,
                      "[camera]: give either pixel_pitch_m or pixel_pitch_x_m + pixel_pitch_y_m, not both");
  if (square) {
    if (!positive(check, cam, "[camera]", "pixel_pitch_m", gx_m)) return false;
    gy_m = gx_m;
  } else if (!positive(check, cam, "[camera]", "pixel_pitch_x_m", gx_m) ||
             !positive(check, cam, "[camera]", "pixel_pitch_y_m", gy_m)) {
    return false;
  }
  fx_px = f_m / gx_m;
  fy_px = f_m / gy_m;
  if (!std::isfinite(fx_px) || !std::isfinite(fy_px))
    return check.fail(cam, "[camera]: focal_length_m / pixel pitch is not finite");
  return true;
}

bool readDistortion(TomlChecker& check, const toml::table& cam, Distortion& d) {
  const toml::table* dist = nullptr;
  if (!check.table(cam, "[camera]", "distortion", false, dist)) return false;
  if (dist == nullptr) return true;
  const std::string name = "[camera.distortion]";
  return check.onlyKeys(*dist, name, {"k1", "k2", "k3", "p1", "p2"}) &&
         check.number(*dist, name, "k1", false, d.k1) && check.number(*dist, name, "k2", false, d.k2) &&
         check.number(*dist, name, "k3", false, d.k3) && check.number(*dist, name, "p1", false, d.p1) &&
         check.number(*dist, name, "p2", false, d.p2);
}

}  // namespace

LoadError loadCameraToml(const std::string& path, CameraIntrinsics& out) {
  toml::table root;
  if (LoadError e = detail::parseTomlFile(path, root); !e.ok) return e;
  TomlChecker check(path);
  const toml::table* cam = nullptr;
  CameraIntrinsics k;
  bool has_cx = false;
  bool has_cy = false;
  const bool ok =
      check.onlyKeys(root, "top level", {"camera"}) && check.table(root, "top level", "camera", true, cam) &&
      check.onlyKeys(*cam, "[camera]",
                     {"width_px", "height_px", "focal_length_m", "pixel_pitch_m", "pixel_pitch_x_m",
                      "pixel_pitch_y_m", "fx_px", "fy_px", "skew", "cx_px", "cy_px", "distortion"}) &&
      imageSide(check, *cam, "width_px", k.width_px) && imageSide(check, *cam, "height_px", k.height_px) &&
      focalLength(check, *cam, k.fx_px, k.fy_px) && check.number(*cam, "[camera]", "skew", false, k.skew) &&
      check.number(*cam, "[camera]", "cx_px", false, k.cx_px, &has_cx) &&
      check.number(*cam, "[camera]", "cy_px", false, k.cy_px, &has_cy) &&
      readDistortion(check, *cam, k.distortion);
  if (!ok) return check.error();
  // Default principal point: the image centre, which with pixel centres at +0.5 is exactly (w/2, h/2).
  if (!has_cx) k.cx_px = 0.5 * k.width_px;
  if (!has_cy) k.cy_px = 0.5 * k.height_px;
  std::string problem;
  if (!checkIntrinsics(k, problem)) {
    check.fail(*cam, "[camera]: " + problem);
    return check.error();
  }
  out = k;
  return LoadError::success();
}

LoadError loadCamera(const std::string& path, CameraIntrinsics& out) {
  const std::string ext = detail::extensionOf(path);
  if (ext == ".toml") return loadCameraToml(path, out);
  if (ext == ".yaml" || ext == ".yml") return loadCameraOpenCvYaml(path, out);
  return LoadError::failure(path + ": unknown camera file extension '" + ext +
                            "' (expected .toml, .yaml, .yml)");
}

LoadError writeCameraToml(const std::string& path, const CameraIntrinsics& camera) {
  std::string problem;
  if (!checkIntrinsics(camera, problem)) return LoadError::failure(path + ": refusing to write: " + problem);
  const auto f = [](double v) { return detail::formatDouble(v); };
  const Distortion& d = camera.distortion;
  std::string text = "# visnav camera, format: fsw/io/README.md. Written by writeCameraToml.\n[camera]\n";
  text += "width_px = " + std::to_string(camera.width_px) + "\n";
  text += "height_px = " + std::to_string(camera.height_px) + "\n";
  text += "fx_px = " + f(camera.fx_px) + "\n";
  text += "fy_px = " + f(camera.fy_px) + "\n";
  text += "skew = " + f(camera.skew) + "\n";
  text += "cx_px = " + f(camera.cx_px) + "\n";
  text += "cy_px = " + f(camera.cy_px) + "\n\n[camera.distortion]\n";
  text += "k1 = " + f(d.k1) + "\nk2 = " + f(d.k2) + "\nk3 = " + f(d.k3) + "\n";
  text += "p1 = " + f(d.p1) + "\np2 = " + f(d.p2) + "\n";
  return detail::writeTextFile(path, text);
}

}  // namespace visnav::io
