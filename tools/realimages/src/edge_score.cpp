#include "visnav/realimages/edge_score.hpp"

#include <algorithm>
#include <cmath>

namespace visnav::realimages {

double FrameEdgeScore::median_abs_offset_px() const {
  if (abs_offsets.empty()) return NAN;
  std::vector<double> sorted = abs_offsets;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

void Gradient::compute(const std::uint8_t* pixels, int w, int h, std::ptrdiff_t stride_bytes) {
  width = w;
  height = h;
  gx.assign(static_cast<std::size_t>(w) * h, 0.0F);
  gy.assign(static_cast<std::size_t>(w) * h, 0.0F);
  auto at = [&](int x, int y) { return static_cast<float>(pixels[stride_bytes * y + x]); };
  for (int y = 1; y + 1 < h; ++y) {
    for (int x = 1; x + 1 < w; ++x) {
      const float dx = (at(x + 1, y - 1) + 2.0F * at(x + 1, y) + at(x + 1, y + 1)) -
                       (at(x - 1, y - 1) + 2.0F * at(x - 1, y) + at(x - 1, y + 1));
      const float dy = (at(x - 1, y + 1) + 2.0F * at(x, y + 1) + at(x + 1, y + 1)) -
                       (at(x - 1, y - 1) + 2.0F * at(x, y - 1) + at(x + 1, y - 1));
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      gx[i] = dx / 8.0F;
      gy[i] = dy / 8.0F;
    }
  }
}

namespace {

/// |gradient . n| at a pixel-grid point (x, y) in CONVENTIONS.md pixels (centres at +0.5), bilinear.
double normalDerivative(const Gradient& g, double x, double y, const Vec2& n) {
  const double fx = x - 0.5, fy = y - 0.5;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  const double ax = fx - x0, ay = fy - y0;
  double sx = 0.0, sy = 0.0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const double wgt = (i ? ax : 1.0 - ax) * (j ? ay : 1.0 - ay);
      const std::size_t k = static_cast<std::size_t>(y0 + j) * g.width + (x0 + i);
      sx += wgt * g.gx[k];
      sy += wgt * g.gy[k];
    }
  }
  return std::abs(sx * n.x() + sy * n.y());
}

bool frontFacing(const ModelSurface& s, const Pose& pose) {
  const Vec3 n = pose.R_c_m * s.normal_m;
  const Vec3 q = pose.transform(s.centroid_m);
  return n.dot(q) < 0.0;  // n . (q / |q|) < 0
}

}  // namespace

FrameEdgeScore scoreFrame(const Gradient& gradient, const PinholeCamera& camera, const PolygonModel& model,
                          const Pose& pose, const EdgeScoreOptions& options) {
  FrameEdgeScore out;
  const int N = options.search_half_px;
  std::vector<char> front(model.surfaces().size());
  for (std::size_t s = 0; s < front.size(); ++s) front[s] = frontFacing(model.surfaces()[s], pose) ? 1 : 0;
  std::vector<double> profile(2 * N + 1);
  for (const ModelEdge& e : model.edges()) {
    const bool visible = front[e.surface_left] || (e.surface_right >= 0 && front[e.surface_right]);
    if (!visible) continue;
    const Vec3 a = pose.transform(model.vertices()[e.v0]);
    const Vec3 b = pose.transform(model.vertices()[e.v1]);
    Vec2 pa, pb;
    if (!camera.project(a, pa) || !camera.project(b, pb)) continue;  // behind the camera: not scored
    const double length = (pb - pa).norm();
    if (length < 2.0 * options.end_margin_px + options.sample_step_px) continue;
    const int count =
        static_cast<int>(std::floor((length - 2.0 * options.end_margin_px) / options.sample_step_px));
    for (int k = 0; k <= count; ++k) {
      // Parameter along the 3-D edge for an even spacing of the image chord (exact without distortion).
      const double t = (options.end_margin_px + k * options.sample_step_px) / length;
      const Vec3 p = a + t * (b - a);
      const double dt = 0.5 / length;
      Vec2 c, c0, c1;
      if (!camera.project(p, c) || !camera.project(a + (t - dt) * (b - a), c0) ||
          !camera.project(a + (t + dt) * (b - a), c1))
        continue;
      Vec2 dir = c1 - c0;
      if (dir.norm() < 1e-9) continue;
      dir.normalize();
      const Vec2 n(-dir.y(), dir.x());
      const Vec2 lo = c - N * n, hi = c + N * n;
      // The whole search segment inside the image, clear of the bilinear stencil and the Sobel border.
      if (std::min({lo.x(), hi.x(), lo.y(), hi.y()}) < 2.0 ||
          std::max(lo.x(), hi.x()) > gradient.width - 2.0 || std::max(lo.y(), hi.y()) > gradient.height - 2.0)
        continue;
      ++out.samples;
      int best = 0;
      for (int i = -N; i <= N; ++i) {
        profile[i + N] = normalDerivative(gradient, c.x() + i * n.x(), c.y() + i * n.y(), n);
        if (profile[i + N] > profile[best]) best = i + N;
      }
      if (profile[best] < options.min_gradient) continue;
      ++out.with_edge;
      double offset = best - N;
      if (best > 0 && best < 2 * N) {  // parabola through the maximum and its neighbours
        const double l = profile[best - 1], m = profile[best], r = profile[best + 1];
        const double den = l - 2.0 * m + r;
        if (den < 0.0) offset += std::clamp(0.5 * (l - r) / den, -0.5, 0.5);
      }
      out.abs_offsets.push_back(std::abs(offset));
      if (std::abs(offset) <= options.within_px) ++out.within;
    }
  }
  return out;
}

}  // namespace visnav::realimages
