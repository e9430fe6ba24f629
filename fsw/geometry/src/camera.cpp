#include "visnav/geometry/camera.hpp"

#include <cmath>

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
