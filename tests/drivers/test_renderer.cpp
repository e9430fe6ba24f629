#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <numeric>
#include <vector>

#include "../support/alloc_counter.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::synthetic {
namespace {

constexpr int kW = 640;
constexpr int kH = 480;

PinholeCamera vga(bool distorted = false) {
  CameraIntrinsics k;
  k.width_px = kW;
  k.height_px = kH;
  k.fx_px = 1000.0;
  k.fy_px = 1000.0;
  k.cx_px = 320.0;
  k.cy_px = 240.0;
  if (distorted) k.distortion = {-0.12, 0.05, 0.0, 0.0005, -0.0003};
  return PinholeCamera(k);
}

// Plate facing the camera: roll 180 deg maps the model normal +z onto -z_c.
Pose facing(double distance_m, double yaw_deg = 0.0) {
  return Pose::fromYpr({yaw_deg * kRadPerDeg, 0.0, kPi}, Vec3(0.0, 0.0, distance_m));
}

double sum(const double* p, std::size_t n) { return std::accumulate(p, p + n, 0.0); }

TEST(CoverageRaster, AxisAlignedRectangleHasExactFractionalEdges) {
  CoverageRaster raster;
  raster.init(40, 20);
  const Vec2 c[4] = {{10.25, 5.5}, {10.25, 8.125}, {20.75, 8.125}, {20.75, 5.5}};
  for (int k = 0; k < 4; ++k) raster.addSegment(c[k], c[(k + 1) % 4], 1.0, 0.5);
  std::vector<double> cov(40 * 20);
  std::vector<double> wei(40 * 20);
  raster.resolve(cov.data(), wei.data());
  auto fx = [](int u) { return u == 10 || u == 20 ? 0.75 : (u > 10 && u < 20 ? 1.0 : 0.0); };
  auto fy = [](int v) { return v == 5 ? 0.5 : v == 8 ? 0.125 : (v == 6 || v == 7 ? 1.0 : 0.0); };
  for (int v = 0; v < 20; ++v) {
    for (int u = 0; u < 40; ++u) {
      EXPECT_NEAR(cov[static_cast<std::size_t>(v * 40 + u)], fx(u) * fy(v), 1e-12) << u << "," << v;
      EXPECT_NEAR(wei[static_cast<std::size_t>(v * 40 + u)], 0.5 * fx(u) * fy(v), 1e-12);
    }
  }
  EXPECT_NEAR(sum(cov.data(), cov.size()), 10.5 * 2.625, 1e-9);
}

TEST(CoverageRaster, RotatedPolygonAreaIsExact) {
  CoverageRaster raster;
  raster.init(100, 80);
  // A convex hexagon at odd angles, traversed so that the signed area is negative (sign +1).
  std::vector<Vec2> poly;
  for (int k = 0; k < 6; ++k) {
    const double a = -k * kPi / 3.0 + 0.3;
    poly.emplace_back(50.3 + 30.7 * std::cos(a), 40.1 + 25.3 * std::sin(a));
  }
  double area2 = 0.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2& a = poly[k];
    const Vec2& b = poly[(k + 1) % poly.size()];
    area2 += a.x() * b.y() - b.x() * a.y();
    raster.addSegment(a, b, 1.0, 1.0);
  }
  std::vector<double> cov(100 * 80);
  std::vector<double> wei(100 * 80);
  raster.resolve(cov.data(), wei.data());
  ASSERT_LT(area2, 0.0);
  EXPECT_NEAR(sum(cov.data(), cov.size()), -0.5 * area2, 1e-9);
  for (const double c : cov) {
    EXPECT_GE(c, 0.0);
    EXPECT_LE(c, 1.0);
  }
}

TEST(CoverageRaster, PolygonLeavingTheImageIsClippedExactly) {
  CoverageRaster raster;
  raster.init(30, 20);
  // Rectangle [-5.3, 12.4] x [-3.2, 7.7] crosses the left and top borders; a second one leaves on the right.
  const Vec2 a[4] = {{-5.3, -3.2}, {-5.3, 7.7}, {12.4, 7.7}, {12.4, -3.2}};
  const Vec2 b[4] = {{20.5, 10.0}, {20.5, 15.0}, {45.0, 15.0}, {45.0, 10.0}};
  for (int k = 0; k < 4; ++k) raster.addSegment(a[k], a[(k + 1) % 4], 1.0, 1.0);
  for (int k = 0; k < 4; ++k) raster.addSegment(b[k], b[(k + 1) % 4], 1.0, 1.0);
  std::vector<double> cov(30 * 20);
  std::vector<double> wei(30 * 20);
  raster.resolve(cov.data(), wei.data());
  EXPECT_NEAR(sum(cov.data(), cov.size()), 12.4 * 7.7 + 9.5 * 5.0, 1e-9);
  EXPECT_NEAR(cov[7 * 30 + 12], 0.4 * 0.7, 1e-12);
}

TEST(Renderer, PlateCoverageMatchesProjectedArea) {
  Renderer r;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  EXPECT_EQ(r.rasterize(facing(10.0)), 1);
  const std::size_t n = kW * kH;
  EXPECT_NEAR(sum(r.coverage(), n), 230.0 * 180.0, 1e-6);
  // Centre pixel fully covered at the flat paper brightness; corners of the image untouched.
  EXPECT_DOUBLE_EQ(r.radiance()[240 * kW + 320], 0.8);
  EXPECT_DOUBLE_EQ(r.radiance()[0], 0.1);
  // Edge at u = 320 - 115 = 205 exactly: pixel 204 empty, 205 full.
  EXPECT_NEAR(r.coverage()[240 * kW + 204], 0.0, 1e-9);
  EXPECT_NEAR(r.coverage()[240 * kW + 205], 1.0, 1e-9);
}

TEST(Renderer, DistortedPlateFollowsCurvedEdges) {
  Renderer plain;
  Renderer bent;
  ASSERT_TRUE(plain.init(vga(false), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  ASSERT_TRUE(bent.init(vga(true), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  plain.rasterize(facing(6.0));
  bent.rasterize(facing(6.0));
  // Barrel distortion (k1 < 0) shrinks the outline; every coverage stays a valid fraction.
  const std::size_t n = kW * kH;
  EXPECT_LT(sum(bent.coverage(), n), sum(plain.coverage(), n) - 100.0);
  for (std::size_t i = 0; i < n; ++i) ASSERT_TRUE(bent.coverage()[i] >= 0.0 && bent.coverage()[i] <= 1.0);
}

TEST(Renderer, BackFacesAreNotDrawn) {
  Renderer r;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  EXPECT_EQ(r.rasterize(Pose::fromYpr({}, Vec3(0.0, 0.0, 10.0))), 0);  // normal +z_c points away
  EXPECT_EQ(sum(r.coverage(), kW * kH), 0.0);
  Renderer box;
  ASSERT_TRUE(box.init(vga(), makeBox(0.8, 0.6, 0.5), RenderOptions{}).ok);
  EXPECT_EQ(box.rasterize(Pose::fromYpr({}, Vec3(0.0, 0.0, 10.0))), 1);  // only -z faces the camera
  EXPECT_EQ(box.rasterize(Pose::fromYpr({0.4, 0.3, 0.5}, Vec3(0.0, 0.0, 10.0))), 3);
  // Visible faces of a convex body tile its silhouette without overlap.
  for (std::size_t i = 0; i < kW * kH; ++i) ASSERT_LE(box.coverage()[i], 1.0);
}

TEST(Renderer, SameSeedIsBitIdenticalAndOtherSeedDiffers) {
  Renderer a;
  Renderer b;
  ASSERT_TRUE(a.init(vga(true), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  ASSERT_TRUE(b.init(vga(true), makeRectanglePlate(2.3, 1.8), RenderOptions{}).ok);
  std::vector<std::uint8_t> i1(kW * kH);
  std::vector<std::uint8_t> i2(kW * kH);
  std::vector<std::uint8_t> i3(kW * kH);
  a.render(facing(12.0, 3.0), Renderer::frameSeed(7, 42), i1.data(), kW);
  b.render(facing(12.0, 3.0), Renderer::frameSeed(7, 42), i2.data(), kW);
  a.render(facing(12.0, 3.0), Renderer::frameSeed(7, 43), i3.data(), kW);
  EXPECT_EQ(i1, i2);
  EXPECT_NE(i1, i3);
  EXPECT_NE(Renderer::frameSeed(7, 42), Renderer::frameSeed(8, 42));
}

TEST(Renderer, NoiseStatisticsOfFlatBackground) {
  RenderOptions o;
  o.background = 0.5;
  o.blur_size_px = 1;  // raw noise first
  Renderer r;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  const Pose away = Pose::fromYpr({}, Vec3(0.0, 0.0, 10.0));
  std::vector<std::uint8_t> img(kW * kH);
  auto stats = [&](double& mean, double& sigma) {
    const std::size_t n = kW * kH;
    mean = sum(r.image(), n) / n;
    double ss = 0.0;
    for (std::size_t i = 0; i < n; ++i) ss += (r.image()[i] - mean) * (r.image()[i] - mean);
    sigma = std::sqrt(ss / (n - 1));
  };
  double mean = 0.0;
  double sigma = 0.0;
  r.render(away, 1, img.data(), kW);
  stats(mean, sigma);
  EXPECT_NEAR(mean, 0.5, 1e-3);
  EXPECT_NEAR(sigma, 0.1, 1e-3);

  // With the paper's blur the white noise shrinks by sum(k_i^2) (separable kernel).
  o.blur_size_px = 5;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  r.render(away, 1, img.data(), kW);
  stats(mean, sigma);
  double k2 = 0.0;
  for (int i = 0; i < r.blurSize(); ++i) k2 += r.blurKernel()[i] * r.blurKernel()[i];
  EXPECT_NEAR(mean, 0.5, 1e-3);
  EXPECT_NEAR(sigma, 0.1 * k2, 2e-3);
  // Quantised output is the clamped, rounded image.
  EXPECT_EQ(img[1000], static_cast<std::uint8_t>(std::clamp(r.image()[1000], 0.0, 1.0) * 255.0 + 0.5));
}

TEST(Renderer, BlurKernelIsNormalisedAndSymmetric) {
  Renderer r;
  RenderOptions o;
  o.noise_sigma = 0.0;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  ASSERT_EQ(r.blurSize(), 5);
  const double* k = r.blurKernel();
  EXPECT_NEAR(k[0] + k[1] + k[2] + k[3] + k[4], 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(k[0], k[4]);
  EXPECT_DOUBLE_EQ(k[1], k[3]);
  EXPECT_NEAR(k[2], 1.0 / (1.0 + 2.0 * std::exp(-2.0) + 2.0 * std::exp(-8.0)), 1e-15);
  // A flat image stays flat (border replication included).
  std::vector<std::uint8_t> img(kW * kH);
  r.render(Pose::fromYpr({}, Vec3(0.0, 0.0, 10.0)), 1, img.data(), kW);
  for (std::size_t i = 0; i < kW * kH; ++i) ASSERT_NEAR(r.image()[i], 0.1, 1e-15);
}

TEST(Renderer, SunShadingAndAlbedo) {
  RenderOptions o;
  o.target_brightness = -1.0;  // use the model's albedo
  o.shading.enabled = true;
  o.shading.ambient = 0.2;
  o.shading.sun_dir_c = Vec3(std::sin(kPi / 3.0), 0.0, std::cos(kPi / 3.0));
  Renderer r;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8, 0.7), o).ok);
  r.rasterize(facing(10.0));
  EXPECT_NEAR(r.radiance()[240 * kW + 320], 0.7 * (0.2 + 0.8 * 0.5), 1e-12);
  o.surface_albedo = {0.9, 0.1};
  EXPECT_FALSE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);  // one entry per surface
}

TEST(Renderer, LimbAndBlobClutter) {
  RenderOptions o;
  o.limb.enabled = true;
  o.limb.center_x_px = 320.0;
  o.limb.center_y_px = 1240.0;
  o.limb.radius_px = 1000.0;
  o.limb.brightness_limb = 0.6;
  o.limb.brightness_centre = 0.9;
  o.limb.softness_px = 5.0;
  Renderer r;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  EXPECT_NEAR(r.background()[10 * kW + 320], 0.1, 1e-6);                       // far outside the disc
  EXPECT_NEAR(r.background()[(kH - 1) * kW + 320], 0.6 + 0.3 * 0.2395, 0.01);  // 239.5 px deep
  EXPECT_NEAR(r.background()[239 * kW + 320], 0.34, 0.02);                     // on the boundary: half way
  o.blobs.count = 20;
  o.blobs.seed = 3;
  Renderer with_blobs;
  ASSERT_TRUE(with_blobs.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  double diff = 0.0;
  for (std::size_t i = 0; i < kW * kH; ++i) diff += std::abs(with_blobs.background()[i] - r.background()[i]);
  EXPECT_GT(diff, 100.0);
}

TEST(Renderer, SixteenBitOutputUsesMaxCode) {
  Renderer r;
  RenderOptions o;
  o.noise_sigma = 0.0;
  o.blur_size_px = 1;
  ASSERT_TRUE(r.init(vga(), makeRectanglePlate(2.3, 1.8), o).ok);
  std::vector<std::uint16_t> img(kW * kH);
  r.render(facing(10.0), 1, img.data(), kW * 2, 4095);
  EXPECT_EQ(img[240 * kW + 320], static_cast<std::uint16_t>(0.8 * 4095 + 0.5));
  EXPECT_EQ(img[0], static_cast<std::uint16_t>(0.1 * 4095 + 0.5));
}

TEST(Renderer, RenderDoesNotAllocate) {
  Renderer r;
  RenderOptions o;
  o.limb.enabled = true;
  o.blobs.count = 5;
  ASSERT_TRUE(r.init(vga(true), makeBox(0.8, 0.6, 0.5, 0.7), o).ok);
  std::vector<std::uint8_t> img8(kW * kH);
  std::vector<std::uint16_t> img16(kW * kH);
  const std::uint64_t before = visnav::test::allocationCount();
  for (int i = 0; i < 50; ++i) {
    const Pose p = Pose::fromYpr({0.01 * i, 0.3, 0.5 + 0.02 * i}, Vec3(0.1, -0.1, 8.0 - 0.01 * i));
    if (i % 2 == 0) {
      r.render(p, Renderer::frameSeed(1, static_cast<std::uint64_t>(i)), img8.data(), kW);
    } else {
      r.render(p, Renderer::frameSeed(1, static_cast<std::uint64_t>(i)), img16.data(), kW * 2, 1023);
    }
  }
  EXPECT_EQ(visnav::test::allocationCount() - before, 0U);
}

}  // namespace
}  // namespace visnav::synthetic
