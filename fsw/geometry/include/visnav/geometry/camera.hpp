// Pinhole camera of paper eq. 2 plus Brown-Conrady distortion. Frames and pixel conventions:
// fsw/geometry/CONVENTIONS.md (the one place they are written down).
#pragma once

#include <string>

#include "visnav/core/types.hpp"

namespace visnav {

/// Brown-Conrady radial (k1..k3) and tangential (p1, p2) coefficients on normalised coordinates,
/// the same polynomial as OpenCV's 5-coefficient model.
struct Distortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;
  bool isZero() const { return k1 == 0.0 && k2 == 0.0 && k3 == 0.0 && p1 == 0.0 && p2 == 0.0; }
};

struct CameraIntrinsics {
  int width_px = 0;
  int height_px = 0;
  double fx_px = 0.0;  ///< focal length / pixel pitch along x (f/g of eq. 2)
  double fy_px = 0.0;  ///< focal length / pixel pitch along y
  double skew = 0.0;   ///< shear s of eq. 2, dimensionless: K(0,1) = s * fx
  double cx_px = 0.0;  ///< principal point x; pixel centres sit at integer + 0.5 (CONVENTIONS.md)
  double cy_px = 0.0;  ///< principal point y
  Distortion distortion;

  /// Paper's SI parametrisation: focal length f [m], pixel pitch g [m] (square pixels unless pitch_y given).
  static CameraIntrinsics fromSi(int width, int height, double focal_length_m, double pixel_pitch_x_m,
                                 double pixel_pitch_y_m, double skew, double cx_px, double cy_px);
};

/// Physical range of a camera (fsw/io/README.md, "Limits"). Not parameters: they separate a camera from a
/// corrupt or mistyped calibration (fx = 1e308, k1 = -50) and every real navigation camera is far inside.
struct IntrinsicsLimits {
  static constexpr int kMaxImageSidePx = 1 << 20;
  static constexpr double kMinFocalPx = 1.0;
  static constexpr double kMaxFocalPx = 1e6;
  static constexpr double kMaxAspect = 10.0;  ///< fx / fy and fy / fx
  static constexpr double kMaxSkew = 0.1;     ///< |s| (K(0,1) = s * fx): about 6 degrees of shear
  /// Largest round-trip error of the iterative undistortion at any checked pixel [px].
  static constexpr double kMaxUndistortErrorPx = 0.01;
};

/// True when `k` is a usable camera: image size in [1, kMaxImageSidePx], fx and fy in [kMinFocalPx,
/// kMaxFocalPx] with fx/fy within [1/kMaxAspect, kMaxAspect], |skew| <= kMaxSkew, principal point within
/// [-width, 2 width] x [-height, 2 height], all finite, and a distortion that is one-to-one over the image:
/// the radial map r -> r (1 + k1 r^2 + k2 r^4 + k3 r^6) strictly increasing (sampled densely) from 0 to the
/// image corners' radius, and the iterative undistortion converging on a 17 x 17 grid of pixels.
/// Otherwise false with the reason in `problem`. Init-time (allocates the message).
bool checkIntrinsics(const CameraIntrinsics& k, std::string& problem);

class PinholeCamera {
 public:
  PinholeCamera() = default;
  explicit PinholeCamera(const CameraIntrinsics& intrinsics) : m_k(intrinsics) {}

  const CameraIntrinsics& intrinsics() const { return m_k; }
  int width() const { return m_k.width_px; }
  int height() const { return m_k.height_px; }

  /// Camera-frame point -> distorted pixel. False if the point is not in front of the camera.
  bool project(const Vec3& p_c, Vec2& px) const;
  /// Camera-frame point -> undistorted ("ideal") pixel, i.e. eq. 2 alone. Optional Jacobian d px / d p_c.
  bool projectIdeal(const Vec3& p_c, Vec2& px, Mat23* d_px_d_p = nullptr) const;

  /// Normalised image coordinates (x/z, y/z) <-> pixels, without distortion.
  Vec2 normalizedToIdealPixel(const Vec2& xn) const;
  Vec2 idealPixelToNormalized(const Vec2& px) const;

  /// Apply / remove lens distortion on normalised coordinates.
  Vec2 distortNormalized(const Vec2& xn) const;
  /// Iterative inverse (bounded: at most 20 fixed-point steps). Exact for zero distortion.
  Vec2 undistortNormalized(const Vec2& xd) const;

  /// Distorted (raw image) pixel <-> ideal pixel.
  Vec2 undistortPixel(const Vec2& px_distorted) const;
  Vec2 distortPixel(const Vec2& px_ideal) const;

  /// Unit bearing in the camera frame through a raw image pixel (distortion removed).
  Vec3 bearing(const Vec2& px_distorted) const;

  bool inImage(const Vec2& px, double margin_px = 0.0) const {
    return px.x() >= margin_px && px.y() >= margin_px && px.x() <= m_k.width_px - margin_px &&
           px.y() <= m_k.height_px - margin_px;
  }

 private:
  CameraIntrinsics m_k;
};

}  // namespace visnav
