// visnav-edge-score's metric (tools/realimages/README.md, "The metric") on rendered frames: the projected
// model lies on the image edges at the true pose and not at a perturbed one; an image without the target
// scores no edge at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "visnav/realimages/edge_score.hpp"
#include "visnav/synthetic/renderer.hpp"

namespace visnav::realimages {
namespace {

constexpr double kDeg = M_PI / 180.0;

CameraIntrinsics vga() {
  CameraIntrinsics k;
  k.width_px = 640;
  k.height_px = 480;
  k.fx_px = 800.0;
  k.fy_px = 800.0;
  k.cx_px = 320.0;
  k.cy_px = 240.0;
  k.distortion.k1 = -0.05;  // the samples follow the distorted edges
  return k;
}

// A box seen from a corner: three faces (+z, +x, +y), albedos 0.25 or more apart from each other and from the
// background (0.1), so every visible edge, interior ones too, is a step of 60 grey levels or more.
Pose truePose() { return Pose::fromYpr({25.0 * kDeg, 20.0 * kDeg, 200.0 * kDeg}, Vec3(0.1, -0.05, 4.0)); }

struct Rendered {
  PinholeCamera camera{vga()};
  PolygonModel model = makeBox(0.5, 0.4, 0.3);
  std::vector<std::uint8_t> pixels = std::vector<std::uint8_t>(640 * 480);
  Gradient gradient;

  explicit Rendered(bool with_target) {
    synthetic::RenderOptions options;
    options.surface_albedo = {0.9, 0.5, 0.6, 0.5, 0.35, 0.5};  // +z, -z, +x, -x, +y, -y
    options.noise_sigma = 0.02;
    synthetic::Renderer renderer;
    EXPECT_TRUE(renderer.init(camera, model, options).ok);
    // Without the target: the same renderer looking away (the box behind the camera).
    const Pose pose = with_target ? truePose() : Pose::fromYpr({}, Vec3(0.0, 0.0, -10.0));
    renderer.render(pose, 7, pixels.data(), 640);
    gradient.compute(pixels.data(), 640, 480, 640);
  }
};

TEST(EdgeScore, TruePoseLiesOnTheRenderedEdges) {
  const Rendered frame(true);
  const FrameEdgeScore s = scoreFrame(frame.gradient, frame.camera, frame.model, truePose(), {});
  EXPECT_GT(s.samples, 300);  // 9 visible edges, ~100 px each, every 2 px
  EXPECT_EQ(s.with_edge, s.samples);
  EXPECT_LT(s.median_abs_offset_px(), 0.2);
  EXPECT_GT(s.withinFraction(), 0.95);
}

TEST(EdgeScore, PerturbedPoseIsOffTheEdges) {
  const Rendered frame(true);
  // 3 px sideways (x by 3 px at 4 m and 800 px) and 2 deg about the boresight.
  Pose perturbed = truePose();
  perturbed.t_c_m.x() += 3.0 * 4.0 / 800.0;
  perturbed.R_c_m = expSo3(Vec3(0.0, 0.0, 2.0 * kDeg)) * perturbed.R_c_m;
  const FrameEdgeScore s = scoreFrame(frame.gradient, frame.camera, frame.model, perturbed, {});
  EXPECT_GT(s.samples, 300);
  EXPECT_GT(s.median_abs_offset_px(), 1.5);
  EXPECT_LT(s.withinFraction(), 0.35);
}

TEST(EdgeScore, AnImageWithoutTheTargetHasNoEdge) {
  const Rendered frame(false);
  const FrameEdgeScore s = scoreFrame(frame.gradient, frame.camera, frame.model, truePose(), {});
  EXPECT_GT(s.samples, 300);
  EXPECT_EQ(s.with_edge, 0);
  EXPECT_EQ(s.within, 0);
  EXPECT_TRUE(std::isnan(s.median_abs_offset_px()));
}

TEST(EdgeScore, OnlyEdgesOfFrontFacesAreSampled) {
  const Rendered frame(true);
  // Face-on: the +z face (1.0 x 0.8 m at 3.7 m: 216.2 x 173.0 px) is the only front face; the four sides are
  // edge-on (back faces by eq. 8) and the -z face looks away. Its four edges give 2 x (floor((216.2 - 8) / 2)
  // + 1) + 2 x (floor((173.0 - 8) / 2) + 1) = 376 samples; the eight hidden edges would add ~190 more.
  const Pose face_on = Pose::fromYpr({0.0, 0.0, 180.0 * kDeg}, Vec3(0.0, 0.0, 4.0));
  const FrameEdgeScore s = scoreFrame(frame.gradient, frame.camera, frame.model, face_on, {});
  EXPECT_GE(s.samples, 372);
  EXPECT_LE(s.samples, 380);
}

}  // namespace
}  // namespace visnav::realimages
