// Synthetic camera images of a polygon target (paper sec. IV-A recipe by default): background, exact
// area-coverage polygons through the distorted camera, additive Gaussian noise, 5x5 Gaussian blur,
// quantisation. init() allocates every buffer; render() allocates nothing and is bit-identical for the same
// pose and frame seed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "visnav/core/bounded_buffer.hpp"
#include "visnav/core/rng.hpp"
#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"
#include "visnav/synthetic/coverage_raster.hpp"
#include "visnav/synthetic/dynamic_clutter.hpp"

namespace visnav::synthetic {

/// Lambertian sun shading: brightness = albedo * (ambient + (1 - ambient) * max(0, n . (-sun_dir))).
struct Shading {
  bool enabled = false;
  double ambient = 0.2;
  Vec3 sun_dir_c = Vec3(0.0, 0.0, 1.0);  ///< direction sunlight travels, camera frame (normalised at init)
};

/// A large bright disc ("Earth limb") with a soft boundary and a brightness gradient towards its centre.
/// value = outside + (inside(depth) - outside) * logistic(depth / softness), depth = radius - |p - centre|,
/// inside(depth) = limb + (centre - limb) * clamp(depth / radius, 0, 1).
struct LimbClutter {
  bool enabled = false;
  double center_x_px = 320.0;
  double center_y_px = 1500.0;
  double radius_px = 1200.0;
  double brightness_limb = 0.6;    ///< just inside the boundary
  double brightness_centre = 0.9;  ///< at the disc centre
  double softness_px = 20.0;       ///< logistic scale of the boundary (10-90 % over ~4.4 softness)
};

/// Gaussian blobs added to the background: position uniform over the image, sigma in
/// [radius_min, radius_max] px, peak brightness in [brightness_min, brightness_max] (negative darkens).
struct BlobClutter {
  int count = 0;
  std::uint64_t seed = 1;
  double radius_min_px = 10.0;
  double radius_max_px = 60.0;
  double brightness_min = -0.1;
  double brightness_max = 0.2;
};

struct RenderOptions {
  double background = 0.1;         ///< paper step 1 (also the limb's outside level)
  double target_brightness = 0.8;  ///< paper step 2: flat brightness when shading is off; < 0: surface albedo
  /// Per-surface albedo overriding both of the above (empty, or one entry per model surface, in [0, 1]).
  std::vector<double> surface_albedo;
  Shading shading;
  LimbClutter limb;
  BlobClutter blobs;
  std::vector<MovingBar> bars;  ///< per-frame clutter (dynamic_clutter.hpp), behind the target
  std::vector<Glint> glints;
  double noise_sigma = 0.1;     ///< paper step 3, additive, before the blur
  int blur_size_px = 5;         ///< paper step 4: odd kernel size; 1 disables the blur
  double blur_sigma_px = 0.5;   ///< <= 0 disables the blur
  double max_segment_px = 2.0;  ///< distorted edges are followed with chords at most this long
  int max_segments_per_edge = 8192;
};

class Renderer {
 public:
  /// Validates the options and allocates every buffer. The static background (level + clutter) is built
  /// here once.
  LoadError init(const PinholeCamera& camera, const PolygonModel& model, const RenderOptions& options);

  /// Trajectory frame index for the per-frame clutter (bars, glints); 0 until set.
  void setFrameIndex(std::int64_t frame) { m_frame = frame; }

  /// Noise-free radiance and coverage of the target at T_c_m (paper steps 1-2). Returns the faces drawn.
  int rasterize(const Pose& T_c_m);
  /// Full recipe into 8-bit (max code 255) or 16-bit (codes 0..max_code) rows; no allocation.
  void render(const Pose& T_c_m, std::uint64_t frame_seed, std::uint8_t* out, std::ptrdiff_t stride_bytes);
  void render(const Pose& T_c_m, std::uint64_t frame_seed, std::uint16_t* out, std::ptrdiff_t stride_bytes,
              std::uint16_t max_code);

  /// Deterministic per-frame seed from (scenario seed, frame index) (splitmix64 mixing).
  static std::uint64_t frameSeed(std::uint64_t scenario_seed, std::uint64_t frame_index);

  /// Row-major width x height buffers of the last call, for tests and tools.
  const double* coverage() const { return m_coverage.data(); }
  const double* radiance() const { return m_radiance.data(); }  ///< before noise and blur
  const double* image() const { return m_image.data(); }        ///< after noise and blur, before quantising
  const double* background() const { return m_background.data(); }
  /// Normalised 1-D blur kernel (size blurSize()).
  const double* blurKernel() const { return m_kernel; }
  int blurSize() const { return m_kernel_size; }
  int width() const { return m_camera.width(); }
  int height() const { return m_camera.height(); }

 private:
  static constexpr int kMaxKernel = 31;
  void buildBackground();
  double surfaceBrightness(int surface, const Vec3& normal_c) const;
  void rasterizeSurface(const ModelSurface& surface, const Pose& T_c_m, double brightness);
  void addNoiseAndBlur(std::uint64_t frame_seed);
  // Models made of several separate convex parts (surfaces connected through shared edges) are composited
  // part by part, far to near; one-part models take the single-pass path above unchanged.
  void findParts();
  int rasterizeParts(const Pose& T_c_m, const double* background);
  const double* frameBackground();  // m_background plus this frame's bars and glints

  PinholeCamera m_camera;
  PolygonModel m_model;
  RenderOptions m_options;
  CoverageRaster m_raster;
  BoundedBuffer<Vec3> m_clip_a;  // near-plane clipping of one surface (3-D, camera frame)
  BoundedBuffer<Vec3> m_clip_b;
  std::vector<double> m_background;
  std::vector<double> m_coverage;
  std::vector<double> m_weighted;
  std::vector<double> m_radiance;
  std::vector<double> m_image;
  std::vector<double> m_tmp;
  std::vector<int> m_surface_part;    // part index per surface
  std::vector<Vec3> m_part_centroid;  // model frame
  std::vector<int> m_part_order;      // far to near, per frame
  std::vector<double> m_frame_background;
  std::vector<double> m_union_coverage;
  std::int64_t m_frame = 0;
  double m_kernel[kMaxKernel] = {};
  int m_kernel_size = 1;
  Pcg32 m_rng;
};

}  // namespace visnav::synthetic
