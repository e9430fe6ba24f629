// REQUIREMENT: the per-frame far-range call allocates nothing after init (fsw/farrange/README.md), in every
// path: full frame, region of interest, ROI fallback, coasting, lost, both methods, 8- and 16-bit frames,
// the flattened background (background_block_px), the outline search of an extended target, the track
// recheck and its switch, refuted regions that follow their cluster.
#include <gtest/gtest.h>

#include "../../support/alloc_counter.hpp"
#include "far_fixture.hpp"

namespace visnav::far {
namespace {

std::vector<test::FarFrame> frames() {
  synthetic::RenderOptions o = test::farRender();
  synthetic::MovingBar bar;
  bar.first_frame = 5;
  bar.last_frame = 12;
  bar.start_px = Vec2(0.0, 120.0);
  bar.end_px = Vec2(640.0, 160.0);
  bar.brightness_start = bar.brightness_end = 1.0;
  bar.length_px = 160.0;
  bar.width_px = 14.0;
  o.bars.push_back(bar);
  synthetic::Glint glint;
  glint.first_frame = 3;
  glint.last_frame = 15;
  glint.start_px = glint.end_px = Vec2(100.5, 400.5);
  glint.peak = 2.0;
  o.glints.push_back(glint);
  synthetic::Renderer renderer;
  EXPECT_TRUE(renderer.init(test::farCamera(), test::smallsat(), o).ok);
  std::vector<test::FarFrame> out;
  for (int i = 0; i < 16; ++i) {
    const double range = 600.0 - 35.0 * i;
    out.push_back(test::renderFar(renderer, test::satAt(range, 0.5 * i - 3.0, 1.0, 2.0 * i), 100 + i, i));
  }
  out.push_back(test::renderFar(renderer, test::satAt(300.0, 80.0), 999, 20));  // nothing in view: coast
  out.push_back(out.back());
  out.push_back(test::renderFar(renderer, test::satAt(200.0, -5.0, -4.0), 998, 21));  // jump: ROI fallback
  return out;
}

std::uint64_t countOver(FarRangeEstimator& e, const std::vector<test::FarFrame>& f, bool sixteen_bit,
                        int& valid) {
  // 16-bit copies are made before counting.
  std::vector<std::vector<std::uint16_t>> wide(f.size());
  for (std::size_t i = 0; i < f.size(); ++i)
    for (const std::uint8_t v : f[i].pixels) wide[i].push_back(static_cast<std::uint16_t>(v * 16U));
  FarRangeResult r;
  constexpr int kFrames = 60;  // > 3 passes over the 19 frames, 4 configurations: 240 frames
  const std::uint64_t before = test::allocationCount();
  for (int i = 0; i < kFrames; ++i) {
    const std::size_t k = static_cast<std::size_t>(i) % f.size();
    const MonoImage image =
        sixteen_bit ? MonoImage::from16(ImageView16(wide[k].data(), 640, 480), 4095) : f[k].image();
    e.estimate(image, r);
    valid += r.valid ? 1 : 0;
  }
  return test::allocationCount() - before;
}

TEST(FarRangeNoAlloc, EveryPathOverManyFrames) {
  const std::vector<test::FarFrame> f = frames();
  for (const FarRangeMethod m : {FarRangeMethod::kRobust, FarRangeMethod::kPaper}) {
    for (const bool sixteen_bit : {false, true}) {
      // eq. 11 as printed, over the flattened background, and that only as a fallback (robust only); 3:
      // the flattened fallback with the outline sharpness rule (robust only)
      for (const int flattening : {0, 1, 2, 3}) {
        if (m == FarRangeMethod::kPaper && flattening > 0) continue;
        FarRangeParams p;
        p.method = static_cast<int>(m);
        p.background_block_px = flattening > 0 ? 128 : 0;
        p.background_fallback_only = flattening >= 2;
        p.min_outline_sharpness = flattening == 3 ? 0.5 : 0.0;
        FarRangeEstimator e;
        ASSERT_TRUE(e.init(test::farCamera(), p).ok);
        int valid = 0;
        EXPECT_EQ(countOver(e, f, sixteen_bit, valid), 0U)
            << "method " << p.method << " 16 bit " << sixteen_bit << " flattening " << flattening
            << " (malloc counted: " << test::countsMalloc() << ")";
        EXPECT_GT(valid, 30);  // the frames really exercised the full pipeline
      }
    }
  }
}

// The bright plate of test_far_estimator's approach (640 x 480, f 1180 px) in noise `noise`, at `ranges_m`
// (frame i turned 30 + i deg about its axis, rendered with seed seed + i).
struct BrightPlateFrames {
  PinholeCamera camera;
  std::vector<test::FarFrame> frames;
};
BrightPlateFrames brightPlateFrames(double noise, const std::vector<double>& ranges_m, std::uint64_t seed) {
  synthetic::RenderOptions o;
  o.background = 0.28;
  o.target_brightness = 0.87;
  o.noise_sigma = noise;
  o.blur_sigma_px = 0.33;
  CameraIntrinsics k = CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320.0, 240.0);
  k.fx_px = k.fy_px = 1180.0;
  BrightPlateFrames out{PinholeCamera(k), {}};
  synthetic::Renderer renderer;
  EXPECT_TRUE(renderer.init(out.camera, makeRectanglePlate(2.0, 2.2), o).ok);
  out.frames.reserve(ranges_m.size());
  for (std::size_t i = 0; i < ranges_m.size(); ++i) {
    const auto n = static_cast<int>(i);
    out.frames.push_back(
        test::renderFar(renderer, test::satAt(ranges_m[i], 1.0, -0.5, 30.0 + n), seed + i, n));
  }
  return out;
}

// `rounds` estimates over `frames` in turn (each searched afresh when `reset_each`), with eq. 11 as printed;
// expects no allocation and returns how many fixes an outline search found.
int extendedFixesWithoutAllocation(const BrightPlateFrames& plate, int rounds, bool reset_each,
                                   double min_outline_sharpness = 0.0) {
  FarRangeParams p;
  p.min_outline_sharpness = min_outline_sharpness;
  p.extended_min_half_px = 12.0;  // the default, stated: these tests are about it
  // Eq. 11 as printed: the plate's grey levels turn common and the outline search runs on most frames (over
  // the flattened background eq. 13 keeps the whole plate, and the outline search is not needed).
  p.background_block_px = 0;
  FarRangeEstimator e;
  EXPECT_TRUE(e.init(plate.camera, p).ok);
  FarRangeResult r;
  int extended = 0;
  const std::vector<test::FarFrame>& f = plate.frames;
  const std::uint64_t before = test::allocationCount();
  for (int i = 0; i < rounds; ++i) {
    if (reset_each) e.reset();
    e.estimate(f[static_cast<std::size_t>(i) % f.size()].image(), r);
    extended += (r.flags & kFlagExtended) != 0U ? 1 : 0;
  }
  EXPECT_EQ(test::allocationCount() - before, 0U) << "(malloc counted: " << test::countsMalloc() << ")";
  return extended;
}

TEST(FarRangeNoAlloc, TheOutlineSearchOfAnExtendedTarget) {
  // A plate close enough that eq. 12 no longer finds it (test_far_estimator's approach): the outline search
  // on the edge response runs on most of these frames.
  std::vector<double> ranges;
  for (int i = 0; i < 16; ++i) ranges.push_back(21.0 * std::pow(0.97, i));
  EXPECT_GT(extendedFixesWithoutAllocation(brightPlateFrames(0.063, ranges, 50), 64, false), 20);
}

TEST(FarRangeNoAlloc, TheSilhouetteSearchWithoutATrackAndTheHullOfAnOutlineWithGaps) {
  // The plate above in noise 0.09, which breaks its outline: each frame searched without a track (reset),
  // so the whole frame's silhouette search and the hulls of its outline fragments run on every frame.
  const BrightPlateFrames plate =
      brightPlateFrames(0.09, {25.0, 24.0, 23.0, 22.0, 21.0, 20.0, 19.0, 18.0}, 70);
  EXPECT_GE(extendedFixesWithoutAllocation(plate, 32, true), 8) << "the silhouette search found the plate";
  // The same with [farrange] min_outline_sharpness: every candidate outline and hull is measured.
  EXPECT_GE(extendedFixesWithoutAllocation(plate, 32, true, 0.5), 8)
      << "and kept it: a plate's edge is sharp";
}

TEST(FarRangeNoAlloc, TheBlockMeanSilhouetteOfADimTargetsFragment) {
  // test_far_extended.cpp's dim plate (contrast 0.27 in noise 0.08, 1024 x 768, f 1134 px) from 32 m to 12 m:
  // its fixes are fragments, and the block-mean silhouette (its windows doubling, the outline sharpness of
  // each region found) runs on each, and is taken on some.
  synthetic::RenderOptions o;
  o.background = 0.246;
  o.target_brightness = 0.52;
  o.noise_sigma = 0.08;
  o.blur_sigma_px = 0.4;
  CameraIntrinsics k = CameraIntrinsics::fromSi(1024, 768, 6e-3, 6e-6, 6e-6, 0.0, 512.0, 384.0);
  k.fx_px = k.fy_px = 1134.0;
  const PinholeCamera camera(k);
  const PolygonModel plate = makeRectanglePlate(2.9, 1.2);
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(camera, plate, o).ok);
  std::vector<test::FarFrame> frames;
  for (int i = 0; i < 24; ++i) {
    const double range = 32.0 * std::pow(0.96, i);
    frames.push_back(
        test::renderFar(renderer, test::satAt(range, 1.0 + 0.02 * i, -0.5, 10.0 + 0.3 * i), 300 + i, i));
  }
  FarRangeParams p;
  p.gamma = 1134.0 * std::sqrt(2.9 * 1.2);
  p.silhouette_min_half_px = 48.0;  // experimental, off by default
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(camera, p).ok);
  e.setTargetRadius(plate.boundingRadius());
  FarRangeResult r;
  int silhouettes = 0;
  const std::uint64_t before = test::allocationCount();
  for (int round = 0; round < 3; ++round)
    for (const test::FarFrame& f : frames) {
      e.estimate(f.image(), r);
      silhouettes += (r.flags & kFlagSilhouetteExtent) != 0U ? 1 : 0;
    }
  EXPECT_EQ(test::allocationCount() - before, 0U) << "(malloc counted: " << test::countsMalloc() << ")";
  EXPECT_GE(silhouettes, 6) << "the path really ran (8 of the 72)";
}

// The track recheck (recheck_frames): the whole-frame search, and the switch from a glow tracked alone to
// the satellite at 40 m (test_far_refuted.cpp, TrackRecheck), many times over.
TEST(FarRangeNoAlloc, TheTrackRecheckAndItsSwitch) {
  synthetic::RenderOptions o = test::farRender();
  o.glints.push_back(test::glowAt(Vec2(150.0, 360.0)));
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::farCamera(), test::smallsat(), o).ok);
  const test::FarFrame clutter_only = test::renderFar(renderer, test::satAt(300.0, 0.0, 80.0, 0.0), 5, 0);
  const test::FarFrame near = test::renderFar(renderer, test::satAt(40.0, 5.0, -3.0, 20.0), 6, 1);
  FarRangeParams p;
  p.min_outline_sharpness =
      0.0;  // the glow as clutter the sharpness rule does not catch (test_far_refuted.cpp)
  p.recheck_frames = 3;
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(test::farCamera(), p).ok);
  e.setTargetRadius(test::smallsat().boundingRadius());
  e.setRecheckMaxDistance(100.0);
  FarRangeResult r;
  int switches = 0;
  const std::uint64_t before = test::allocationCount();
  for (int round = 0; round < 10; ++round) {
    e.reset();
    e.estimate(clutter_only.image(), r);
    for (int i = 0; i < 6; ++i) {
      e.estimate(near.image(), r);
      switches += (r.flags & kFlagRecheckSwitched) != 0U ? 1 : 0;
    }
  }
  EXPECT_EQ(test::allocationCount() - before, 0U) << "(malloc counted: " << test::countsMalloc() << ")";
  EXPECT_EQ(switches, 10) << "one switch a round: the path really ran";
}

// Refuted regions that follow a drifting glint (refuted_follow) and are refuted again, many times over.
TEST(FarRangeNoAlloc, RefutedRegionsFollowingADriftingGlint) {
  synthetic::RenderOptions o = test::farRender();
  synthetic::Glint glint = test::glowAt(Vec2(60.0, 400.0));
  glint.last_frame = 100;
  glint.end_px = Vec2(660.0, 400.0);
  o.glints.push_back(glint);
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::farCamera(), test::smallsat(), o).ok);
  std::vector<test::FarFrame> f;
  f.reserve(20);
  for (int i = 0; i < 20; ++i) f.push_back(test::renderFar(renderer, test::satAt(300.0, 0.0, 80.0), 7, i));
  FarRangeParams p;
  p.min_outline_sharpness =
      0.0;  // the glow as clutter the sharpness rule does not catch (test_far_refuted.cpp)
  p.refuted_fix_frames = 4;
  FarRangeEstimator e;
  ASSERT_TRUE(e.init(test::farCamera(), p).ok);
  FarRangeResult r;
  int refuted = 0;
  int passed_over = 0;
  const std::uint64_t before = test::allocationCount();
  for (int i = 0; i < 120; ++i) {
    e.estimate(f[static_cast<std::size_t>(i) % f.size()].image(), r);
    passed_over += (r.flags & kFlagRefutedSkipped) != 0U ? 1 : 0;
    if (r.valid && e.refuteLastFix()) {
      ++refuted;
      e.reset();
    }
    if (i % 40 == 39) e.clearRefuted();  // the doublings start over: more refutations
  }
  EXPECT_EQ(test::allocationCount() - before, 0U) << "(malloc counted: " << test::countsMalloc() << ")";
  EXPECT_GE(refuted, 6) << "the glint was refuted again and again: the path really ran";
  EXPECT_GE(passed_over, 60);
}

TEST(FarRangeNoAlloc, CounterSeesAllocations) {
  const std::uint64_t before = test::allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(test::allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav::far
