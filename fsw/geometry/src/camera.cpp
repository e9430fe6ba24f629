#include "visnav/geometry/camera.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace visnav {

CameraIntrinsics CameraIntrinsics::fromSi(int width, int height, double focal_length_m,
                                          double pixel_pitch_x_m, double pixel_pitch_y_m, double skew,
                                          double cx_px, double cy_px) {
  CameraIntrinsics k;
  k.width_px = width;
  k.height_px = height;
  k.fx_px = focal_length_m / pixel_pitch_x_m;
  k.fy_px = focal_length_m / pixel_pitch_y_m;
  k.skew = skew;
  k.cx_px = cx_px;
  k.cy_px = cy_px;
  return k;
}

namespace {

std::string formatNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The radial part must not fold over inside the image: sampled from the centre outwards until it reaches
// the corners' (distorted) radius, its slope stays positive.
bool radialMonotonic(const Distortion& d, double r_max, std::string& problem) {
  constexpr int kStepsToCorner = 2048;  // samples per corner radius: dense for any polynomial of degree 7
  constexpr int kMaxSteps = 64 * 2048;  // undistorted radius up to 64 x the corner radius
  const double step = r_max / kStepsToCorner;
  for (int i = 1; i <= kMaxSteps; ++i) {
    const double r = i * step;
    const double r2 = r * r;
    const double slope = 1.0 + r2 * (3.0 * d.k1 + r2 * (5.0 * d.k2 + r2 * 7.0 * d.k3));
    if (!(slope > 0.0)) {
      problem = "distortion folds over inside the image (radial map stops increasing at normalised radius " +
                formatNumber(r) + ", the image corners need " + formatNumber(r_max) + ")";
      return false;
    }
    if (r * (1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3))) >= r_max) return true;
  }
  problem = "distortion compresses the image corners beyond 64 times their radius";
  return false;
}

}  // namespace

bool checkIntrinsics(const CameraIntrinsics& k, std::string& problem) {
  using L = IntrinsicsLimits;
  const Distortion& d = k.distortion;
  const auto within = [](double v, double lo, double hi) { return v >= lo && v <= hi; };  // false for NaN
  if (k.width_px <= 0 || k.height_px <= 0 || k.width_px > L::kMaxImageSidePx ||
      k.height_px > L::kMaxImageSidePx) {
    problem = "image size " + std::to_string(k.width_px) + "x" + std::to_string(k.height_px) +
              " out of range [1, " + std::to_string(L::kMaxImageSidePx) + "]";
  } else if (!within(k.fx_px, L::kMinFocalPx, L::kMaxFocalPx) ||
             !within(k.fy_px, L::kMinFocalPx, L::kMaxFocalPx)) {
    problem = "fx_px = " + formatNumber(k.fx_px) + ", fy_px = " + formatNumber(k.fy_px) + ": must be in [" +
              formatNumber(L::kMinFocalPx) + ", " + formatNumber(L::kMaxFocalPx) + "] px";
  } else if (!within(k.fx_px / k.fy_px, 1.0 / L::kMaxAspect, L::kMaxAspect)) {
    problem = "fx_px / fy_px = " + formatNumber(k.fx_px / k.fy_px) + " outside [" +
              formatNumber(1.0 / L::kMaxAspect) + ", " + formatNumber(L::kMaxAspect) + "]";
  } else if (!within(k.skew, -L::kMaxSkew, L::kMaxSkew)) {
    problem = "skew = " + formatNumber(k.skew) + " outside [-" + formatNumber(L::kMaxSkew) + ", " +
              formatNumber(L::kMaxSkew) + "]";
  } else if (!within(k.cx_px, -k.width_px, 2.0 * k.width_px) ||
             !within(k.cy_px, -k.height_px, 2.0 * k.height_px)) {
    problem = "principal point (" + formatNumber(k.cx_px) + ", " + formatNumber(k.cy_px) +
              ") outside [-width, 2 width] x [-height, 2 height]";
  } else if (!std::isfinite(d.k1) || !std::isfinite(d.k2) || !std::isfinite(d.k3) || !std::isfinite(d.p1) ||
             !std::isfinite(d.p2)) {
    problem = "distortion coefficient is not finite";
  } else {
    if (d.isZero()) return true;
    const PinholeCamera camera(k);
    const double w = k.width_px;
    const double h = k.height_px;
    double r_max = 0.0;
    for (const Vec2& corner : {Vec2(0.0, 0.0), Vec2(w, 0.0), Vec2(0.0, h), Vec2(w, h)})
      r_max = std::max(r_max, camera.idealPixelToNormalized(corner).norm());
    if (!radialMonotonic(d, r_max, problem)) return false;
    constexpr int kGrid = 17;
    for (int j = 0; j < kGrid; ++j) {
      for (int i = 0; i < kGrid; ++i) {
        const Vec2 px(w * i / (kGrid - 1), h * j / (kGrid - 1));
        const Vec2 back = camera.distortPixel(camera.undistortPixel(px));
        const double error = (back - px).norm();
        if (!(error <= L::kMaxUndistortErrorPx)) {
          problem = "distortion cannot be inverted at pixel (" + formatNumber(px.x()) + ", " +
                    formatNumber(px.y()) + "): " +
                    (std::isfinite(error) ? "the undistortion misses by " + formatNumber(error) + " px"
                                          : std::string("the undistortion diverges"));
          return false;
        }
      }
    }
    return true;
  }
  return false;
}

Vec2 PinholeCamera::normalizedToIdealPixel(const Vec2& xn) const {
  return {m_k.fx_px * xn.x() + m_k.skew * m_k.fx_px * xn.y() + m_k.cx_px, m_k.fy_px * xn.y() + m_k.cy_px};
}

Vec2 PinholeCamera::idealPixelToNormalized(const Vec2& px) const {
  const double yn = (px.y() - m_k.cy_px) / m_k.fy_px;
  const double xn = (px.x() - m_k.cx_px - m_k.skew * m_k.fx_px * yn) / m_k.fx_px;
  return {xn, yn};
}

Vec2 PinholeCamera::distortNormalized(const Vec2& xn) const {
  const Distortion& d = m_k.distortion;
  const double x = xn.x();
  const double y = xn.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  return {x * radial + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x),
          y * radial + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y};
}

Vec2 PinholeCamera::undistortNormalized(const Vec2& xd) const {
  if (m_k.distortion.isZero()) return xd;
  // Fixed-point iteration x <- x + (xd - distort(x)); converges for the mild distortion of navigation optics.
  Vec2 x = xd;
  constexpr int kMaxIterations = 20;
  for (int i = 0; i < kMaxIterations; ++i) {
    const Vec2 step = xd - distortNormalized(x);
    x += step;
    if (step.squaredNorm() < 1e-24) break;
  }
  return x;
}

bool PinholeCamera::projectIdeal(const Vec3& p_c, Vec2& px, Mat23* d_px_d_p) const {
  if (!(p_c.z() > 1e-9)) return false;
  const double inv_z = 1.0 / p_c.z();
  const Vec2 xn(p_c.x() * inv_z, p_c.y() * inv_z);
  px = normalizedToIdealPixel(xn);
  if (d_px_d_p != nullptr) {
    const double fx = m_k.fx_px;
    const double fy = m_k.fy_px;
    const double sfx = m_k.skew * fx;
    // d xn / d p
    Mat23 d_xn;
    d_xn << inv_z, 0.0, -xn.x() * inv_z, 0.0, inv_z, -xn.y() * inv_z;
    Mat2 k2;
    k2 << fx, sfx, 0.0, fy;
    *d_px_d_p = k2 * d_xn;
  }
  return true;
}

bool PinholeCamera::project(const Vec3& p_c, Vec2& px) const {
  if (!(p_c.z() > 1e-9)) return false;
  const Vec2 xn(p_c.x() / p_c.z(), p_c.y() / p_c.z());
  px = normalizedToIdealPixel(distortNormalized(xn));
  return true;
}

Vec2 PinholeCamera::undistortPixel(const Vec2& px_distorted) const {
  if (m_k.distortion.isZero()) return px_distorted;
  return normalizedToIdealPixel(undistortNormalized(idealPixelToNormalized(px_distorted)));
}

Vec2 PinholeCamera::distortPixel(const Vec2& px_ideal) const {
  if (m_k.distortion.isZero()) return px_ideal;
  return normalizedToIdealPixel(distortNormalized(idealPixelToNormalized(px_ideal)));
}

Vec3 PinholeCamera::bearing(const Vec2& px_distorted) const {
  const Vec2 xn = undistortNormalized(idealPixelToNormalized(px_distorted));
  return Vec3(xn.x(), xn.y(), 1.0).normalized();
}

}  // namespace visnav
