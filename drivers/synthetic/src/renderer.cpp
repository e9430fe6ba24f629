#include "visnav/synthetic/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace visnav::synthetic {
namespace {

constexpr double kNearPlaneM = 1e-3;                     // surfaces are clipped at z >= 1 mm
constexpr std::uint64_t kNoiseStream = 0x6e6f697365ULL;  // "noise": PCG stream of the pixel noise
constexpr std::uint64_t kBlobStream = 0x626c6f6273ULL;   // "blobs": PCG stream of the clutter
constexpr double kInv2Pow32 = 1.0 / 4294967296.0;

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

bool inUnit(double v) { return v >= 0.0 && v <= 1.0; }

}  // namespace

std::uint64_t Renderer::frameSeed(std::uint64_t scenario_seed, std::uint64_t frame_index) {
  return splitmix64(splitmix64(scenario_seed) ^ (frame_index * 0xd1b54a32d192ed03ULL));
}

LoadError Renderer::init(const PinholeCamera& camera, const PolygonModel& model,
                         const RenderOptions& options) {
  const RenderOptions& o = options;
  auto bad = [](const std::string& what) { return LoadError::failure("render options: " + what); };
  if (camera.width() <= 0 || camera.height() <= 0) return bad("camera has no image size");
  if (model.surfaces().empty()) return bad("model has no surfaces");
  if (!inUnit(o.background)) return bad("background must be in [0, 1]");
  if (!(o.target_brightness <= 1.0)) return bad("target_brightness must be <= 1 (< 0: use albedo)");
  if (!o.surface_albedo.empty() && o.surface_albedo.size() != model.surfaces().size()) {
    return bad("surface_albedo needs one entry per model surface (" +
               std::to_string(model.surfaces().size()) + ")");
  }
  for (const double a : o.surface_albedo) {
    if (!inUnit(a)) return bad("surface_albedo entries must be in [0, 1]");
  }
  if (!inUnit(o.shading.ambient)) return bad("shading ambient must be in [0, 1]");
  if (!(o.shading.sun_dir_c.norm() > 1e-12)) return bad("sun direction must be non-zero");
  if (o.limb.enabled && !(o.limb.radius_px > 0.0 && o.limb.softness_px > 0.0)) {
    return bad("limb radius and softness must be > 0");
  }
  if (o.blobs.count < 0 || o.blobs.count > 100000) return bad("blob count must be in [0, 100000]");
  if (o.blobs.count > 0 && !(o.blobs.radius_min_px > 0.0 && o.blobs.radius_max_px >= o.blobs.radius_min_px)) {
    return bad("blob radii need 0 < min <= max");
  }
  if (!(o.noise_sigma >= 0.0)) return bad("noise sigma must be >= 0");
  if (o.blur_size_px < 1 || o.blur_size_px > kMaxKernel || o.blur_size_px % 2 == 0) {
    return bad("blur size must be odd, 1.." + std::to_string(kMaxKernel));
  }
  if (!(o.max_segment_px > 0.0) || o.max_segments_per_edge < 1) return bad("edge subdivision must be > 0");
  for (const MovingBar& b : o.bars) {
    if (b.last_frame < b.first_frame || !(b.length_px > 0.0 && b.width_px > 0.0))
      return bad("bars need first_frame <= last_frame and positive length and width");
  }
  for (const Glint& g : o.glints) {
    if (g.last_frame < g.first_frame || !(g.sigma_px > 0.0))
      return bad("glints need first <= last, sigma > 0");
  }

  m_camera = camera;
  m_model = model;
  m_options = options;
  m_options.shading.sun_dir_c.normalize();
  const auto n = static_cast<std::size_t>(camera.width()) * static_cast<std::size_t>(camera.height());
  m_raster.init(camera.width(), camera.height());
  // Clipping a convex polygon at one plane adds at most one vertex.
  const auto clip_capacity = static_cast<std::size_t>(model.maxSurfaceVertices()) + 2U;
  m_clip_a.reserve(clip_capacity);
  m_clip_b.reserve(clip_capacity);
  m_background.assign(n, 0.0);
  m_coverage.assign(n, 0.0);
  m_weighted.assign(n, 0.0);
  m_radiance.assign(n, 0.0);
  m_image.assign(n, 0.0);
  m_tmp.assign(n, 0.0);

  m_kernel_size = o.blur_sigma_px > 0.0 ? o.blur_size_px : 1;
  const int half = m_kernel_size / 2;
  double sum = 0.0;
  for (int i = 0; i < m_kernel_size; ++i) {
    const double x = i - half;
    m_kernel[i] = m_kernel_size == 1 ? 1.0 : std::exp(-0.5 * x * x / (o.blur_sigma_px * o.blur_sigma_px));
    sum += m_kernel[i];
  }
  for (int i = 0; i < m_kernel_size; ++i) m_kernel[i] /= sum;
  buildBackground();
  m_frame_background.assign(o.bars.empty() && o.glints.empty() ? 0U : n, 0.0);
  findParts();
  m_union_coverage.assign(m_part_centroid.size() > 1 ? n : 0U, 0.0);
  return LoadError::success();
}

void Renderer::buildBackground() {
  const int w = width();
  const int h = height();
  const LimbClutter& limb = m_options.limb;
  const double bg = m_options.background;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double value = bg;
      if (limb.enabled) {
        const double depth =
            limb.radius_px - std::hypot(u + 0.5 - limb.center_x_px, v + 0.5 - limb.center_y_px);
        const double inside = limb.brightness_limb + (limb.brightness_centre - limb.brightness_limb) *
                                                         std::clamp(depth / limb.radius_px, 0.0, 1.0);
        const double s = 1.0 / (1.0 + std::exp(-depth / limb.softness_px));
        value = bg + (inside - bg) * s;
      }
      m_background[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)] =
          value;
    }
  }
  const BlobClutter& blobs = m_options.blobs;
  Pcg32 rng(blobs.seed, kBlobStream);
  for (int b = 0; b < blobs.count; ++b) {
    const double cx = rng.uniform() * w;
    const double cy = rng.uniform() * h;
    const double sigma = blobs.radius_min_px + rng.uniform() * (blobs.radius_max_px - blobs.radius_min_px);
    const double peak = blobs.brightness_min + rng.uniform() * (blobs.brightness_max - blobs.brightness_min);
    const int u0 = std::max(0, static_cast<int>(std::floor(cx - 4.0 * sigma)));
    const int u1 = std::min(w - 1, static_cast<int>(std::ceil(cx + 4.0 * sigma)));
    const int v0 = std::max(0, static_cast<int>(std::floor(cy - 4.0 * sigma)));
    const int v1 = std::min(h - 1, static_cast<int>(std::ceil(cy + 4.0 * sigma)));
    for (int v = v0; v <= v1; ++v) {
      for (int u = u0; u <= u1; ++u) {
        const double dx = u + 0.5 - cx;
        const double dy = v + 0.5 - cy;
        m_background[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) +
                     static_cast<std::size_t>(u)] +=
            peak * std::exp(-0.5 * (dx * dx + dy * dy) / (sigma * sigma));
      }
    }
  }
}

double Renderer::surfaceBrightness(int surface, const Vec3& normal_c) const {
  const RenderOptions& o = m_options;
  double albedo = o.target_brightness;
  if (!o.surface_albedo.empty()) {
    albedo = o.surface_albedo[static_cast<std::size_t>(surface)];
  } else if (albedo < 0.0) {
    albedo = m_model.surfaces()[static_cast<std::size_t>(surface)].albedo;
  }
  if (!o.shading.enabled) return albedo;
  const double lambert = std::max(0.0, -normal_c.dot(o.shading.sun_dir_c));
  return albedo * (o.shading.ambient + (1.0 - o.shading.ambient) * lambert);
}

void Renderer::rasterizeSurface(const ModelSurface& surface, const Pose& T_c_m, double brightness) {
  m_clip_a.clear();
  for (const int idx : surface.vertex_indices) {
    m_clip_a.push(T_c_m.transform(m_model.vertices()[static_cast<std::size_t>(idx)]));
  }
  // Sutherland-Hodgman against the near plane z = kNearPlaneM (only matters when the target is very close).
  m_clip_b.clear();
  const std::size_t n_in = m_clip_a.size();
  for (std::size_t k = 0; k < n_in; ++k) {
    const Vec3& a = m_clip_a[k];
    const Vec3& b = m_clip_a[(k + 1) % n_in];
    const bool a_in = a.z() >= kNearPlaneM;
    const bool b_in = b.z() >= kNearPlaneM;
    if (a_in) m_clip_b.push(a);
    if (a_in != b_in) m_clip_b.push(a + (b - a) * ((kNearPlaneM - a.z()) / (b.z() - a.z())));
  }
  const std::size_t n = m_clip_b.size();
  if (n < 3) return;

  // Orientation in the image decides the accumulation sign (shoelace on the undistorted projection).
  double area2 = 0.0;
  Vec2 prev;
  m_camera.projectIdeal(m_clip_b[n - 1], prev);
  for (std::size_t k = 0; k < n; ++k) {
    Vec2 p;
    m_camera.projectIdeal(m_clip_b[k], p);
    area2 += prev.x() * p.y() - p.x() * prev.y();
    prev = p;
  }
  if (area2 == 0.0) return;
  const double sign = area2 < 0.0 ? 1.0 : -1.0;

  // Straight 3-D edges become curves under distortion: follow them with short chords.
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3& a = m_clip_b[k];
    const Vec3& b = m_clip_b[(k + 1) % n];
    Vec2 pa;
    Vec2 pb;
    m_camera.project(a, pa);
    m_camera.project(b, pb);
    const double chord = (pb - pa).norm();
    const int segments = static_cast<int>(std::clamp(std::ceil(chord / m_options.max_segment_px), 1.0,
                                                     static_cast<double>(m_options.max_segments_per_edge)));
    Vec2 p_prev = pa;
    for (int j = 1; j <= segments; ++j) {
      Vec2 p = pb;
      if (j < segments) m_camera.project(a + (b - a) * (static_cast<double>(j) / segments), p);
      m_raster.addSegment(p_prev, p, sign, brightness);
      p_prev = p;
    }
  }
}

int Renderer::rasterize(const Pose& T_c_m) {
  const double* background = m_frame_background.empty() ? m_background.data() : frameBackground();
  if (m_part_centroid.size() > 1) return rasterizeParts(T_c_m, background);
  int drawn = 0;
  const auto& surfaces = m_model.surfaces();
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const Vec3 normal_c = T_c_m.R_c_m * surfaces[s].normal_m;
    const Vec3 centroid_c = T_c_m.transform(surfaces[s].centroid_m);
    if (normal_c.dot(centroid_c) >= 0.0) continue;  // back face (CONVENTIONS.md, eq. 8)
    rasterizeSurface(surfaces[s], T_c_m, surfaceBrightness(static_cast<int>(s), normal_c));
    ++drawn;
  }
  m_raster.resolve(m_coverage.data(), m_weighted.data());
  // Front faces of a convex body do not overlap, so coverages and weighted brightnesses simply add.
  for (std::size_t i = 0; i < m_radiance.size(); ++i) {
    m_radiance[i] = background[i] * (1.0 - m_coverage[i]) + m_weighted[i];
  }
  return drawn;
}

void Renderer::addNoiseAndBlur(std::uint64_t frame_seed) {
  const std::size_t n = m_radiance.size();
  const double sigma = m_options.noise_sigma;
  if (sigma > 0.0) {
    m_rng.reseed(frame_seed, kNoiseStream);
    for (std::size_t i = 0; i < n; i += 2) {
      // Box-Muller: u1 in (0, 1] keeps the logarithm finite.
      const double u1 = (static_cast<double>(m_rng.next()) + 1.0) * kInv2Pow32;
      const double u2 = static_cast<double>(m_rng.next()) * kInv2Pow32;
      const double r = sigma * std::sqrt(-2.0 * std::log(u1));
      const double phi = 2.0 * kPi * u2;
      m_image[i] = m_radiance[i] + r * std::cos(phi);
      if (i + 1 < n) m_image[i + 1] = m_radiance[i + 1] + r * std::sin(phi);
    }
  } else {
    std::copy(m_radiance.begin(), m_radiance.end(), m_image.begin());
  }
  if (m_kernel_size == 1) return;
  // Separable, normalised kernel; borders replicate the edge pixel.
  const int w = width();
  const int h = height();
  const int half = m_kernel_size / 2;
  const auto at = [w](int u, int v) {
    return static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u);
  };
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double acc = 0.0;
      for (int k = 0; k < m_kernel_size; ++k)
        acc += m_kernel[k] * m_image[at(std::clamp(u + k - half, 0, w - 1), v)];
      m_tmp[at(u, v)] = acc;
    }
  }
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      double acc = 0.0;
      for (int k = 0; k < m_kernel_size; ++k)
        acc += m_kernel[k] * m_tmp[at(u, std::clamp(v + k - half, 0, h - 1))];
      m_image[at(u, v)] = acc;
    }
  }
}

void Renderer::render(const Pose& T_c_m, std::uint64_t frame_seed, std::uint8_t* out,
                      std::ptrdiff_t stride_bytes) {
  rasterize(T_c_m);
  addNoiseAndBlur(frame_seed);
  const int w = width();
  for (int v = 0; v < height(); ++v) {
    std::uint8_t* row = out + stride_bytes * v;
    const double* src = m_image.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(w);
    for (int u = 0; u < w; ++u)
      row[u] = static_cast<std::uint8_t>(std::clamp(src[u], 0.0, 1.0) * 255.0 + 0.5);
  }
}

void Renderer::render(const Pose& T_c_m, std::uint64_t frame_seed, std::uint16_t* out,
                      std::ptrdiff_t stride_bytes, std::uint16_t max_code) {
  rasterize(T_c_m);
  addNoiseAndBlur(frame_seed);
  const int w = width();
  const double scale = max_code;
  for (int v = 0; v < height(); ++v) {
    auto* row = reinterpret_cast<std::uint16_t*>(reinterpret_cast<std::uint8_t*>(out) + stride_bytes * v);
    const double* src = m_image.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(w);
    for (int u = 0; u < w; ++u)
      row[u] = static_cast<std::uint16_t>(std::clamp(src[u], 0.0, 1.0) * scale + 0.5);
  }
}

}  // namespace visnav::synthetic
