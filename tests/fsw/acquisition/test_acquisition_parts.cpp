// The pieces of acquisition on their own: the attitude grid, the working image (gradient channels, spread,
// statistics) and the edge scorer (score, two-way agreement, refinement) against hand-made and rendered
// images.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "acquisition_fixture.hpp"
#include "visnav/acquisition/attitude_grid.hpp"
#include "visnav/acquisition/edge_scorer.hpp"
#include "visnav/acquisition/working_image.hpp"

namespace visnav::acq {
namespace {

TEST(AttitudeGrid, RotationZToReachesEveryDirection) {
  for (const Vec3& u : {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0.3, -0.4, 0.866).normalized()}) {
    const Mat3 r = rotationZTo(u);
    EXPECT_NEAR((r * Vec3::UnitZ() - u).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.transpose() * r - Mat3::Identity()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  }
}

TEST(AttitudeGrid, PlateKeepsOnlyViewsThatSeeItsFace) {
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  AttitudeGrid grid;
  ASSERT_TRUE(grid.init(plate, 200, 12, 50.0 * kRadPerDeg).ok);
  // The kept cap (1 - cos 50 deg) / 2 = 17.9 % of the sphere; the Fibonacci lattice is equal-area.
  EXPECT_NEAR(grid.views(), 200 * (1.0 - std::cos(50.0 * kRadPerDeg)) / 2.0, 2.0);
  EXPECT_EQ(grid.size(), grid.views() * 12);
  for (int i = 0; i < grid.size(); ++i) {
    const Mat3 r = grid.rotation(i);
    // The camera sits at -z of the line-of-sight frame: the face normal must point there within 50 deg.
    const Vec3 normal_l = r * Vec3::UnitZ();
    EXPECT_GT(-normal_l.z(), std::cos(50.0 * kRadPerDeg) - 1e-12) << i;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  }
  // A box always shows some face within acos(1 / sqrt(3)) = 54.7 deg (the corner view): all views at 55 deg,
  // fewer at 50 deg (those around the 8 corners).
  AttitudeGrid box;
  ASSERT_TRUE(box.init(makeBox(0.8, 0.6, 0.5), 200, 12, 55.0 * kRadPerDeg).ok);
  EXPECT_EQ(box.views(), 200);
  ASSERT_TRUE(box.init(makeBox(0.8, 0.6, 0.5), 200, 12, 50.0 * kRadPerDeg).ok);
  EXPECT_LT(box.views(), 200);
  EXPECT_GT(box.views(), 150);
}

/// A vertical step at x = 100 px (dark left, bright right) in a 200 x 160 8-bit image.
std::vector<std::uint8_t> stepImage() {
  std::vector<std::uint8_t> pixels(200U * 160U);
  for (int y = 0; y < 160; ++y)
    for (int x = 0; x < 200; ++x) pixels[static_cast<std::size_t>(y * 200 + x)] = x < 100 ? 30 : 200;
  return pixels;
}

TEST(WorkingImage, StepEdgeGivesEvidenceAcrossItOnly) {
  const std::vector<std::uint8_t> pixels = stepImage();
  const MonoImage image = MonoImage::from8(ImageView8(pixels.data(), 200, 160));
  WorkingImage w;
  ASSERT_TRUE(w.init(64, 256, 1280).ok);
  // Window centred on the edge, 120 px wide, box factor 2 -> 60 x 60 working pixels.
  EXPECT_EQ(w.setWindow(Vec2(100.0, 80.0), 60.0, 2), 2);
  w.prepare(image, 1, 4, 1000.0);
  EXPECT_EQ(w.width(), 60);
  EXPECT_NEAR((w.toFull(w.toWorking(Vec2(123.0, 45.5))) - Vec2(123.0, 45.5)).norm(), 0.0, 1e-12);
  const Vec2 on_edge = w.toWorking(Vec2(100.0, 80.0));
  // Sobel / 8 of a step of (200 - 30) / 255 across one working pixel: half of it on each neighbour column.
  const double step = 170.0 / 255.0;
  EXPECT_NEAR(w.evidence(on_edge, 0.0, Evidence::kRaw), 0.5 * step, 0.02);
  EXPECT_NEAR(w.evidence(on_edge, kPi, Evidence::kRaw), 0.5 * step, 0.02);  // either contrast
  EXPECT_NEAR(w.evidence(on_edge, 0.5 * kPi, Evidence::kRaw), 0.0, 1e-6);   // along the edge: nothing
  EXPECT_NEAR(w.evidence(on_edge, 0.25 * kPi, Evidence::kRaw), 0.5 * step * std::cos(0.25 * kPi), 0.02);
  // Spread: 3 working px off the edge only the coarse copy (radius 4) still sees it, with the tent weight
  // 1 - 3 / 5 of the nearest edge column.
  const Vec2 off = on_edge + Vec2(3.0, 0.0);
  EXPECT_NEAR(w.evidence(off, 0.0, Evidence::kRaw), 0.0, 1e-6);
  EXPECT_NEAR(w.evidence(off, 0.0, Evidence::kFine), 0.0, 1e-6);
  EXPECT_NEAR(w.evidence(off, 0.0, Evidence::kCoarse), 0.4 * 0.5 * step, 0.01);
  EXPECT_NEAR(w.evidence(on_edge, 0.0, Evidence::kCoarse), 0.5 * step, 0.02);  // peaks on the edge
  EXPECT_EQ(w.evidence(Vec2(-1.0, 5.0), 0.0, Evidence::kRaw), 0.0);            // outside the window
  EXPECT_TRUE(w.stats().has_strong);
  EXPECT_NEAR(w.toFull(w.stats().strong_centroid_w).x(), 100.0, 2.0);
  // Saturation: with a cap of 4 x 3 x (quarter code step) every value is clipped to the cap.
  w.prepare(image, 1, 4, 4.0);
  EXPECT_NEAR(w.cap(), 4.0 * 3.0 * 0.25 / 255.0, 1e-7);
  EXPECT_NEAR(w.evidence(on_edge, 0.0, Evidence::kRaw), w.cap(), 1e-7);
  EXPECT_NEAR(w.evidence(on_edge, 0.0, Evidence::kCoarse), w.cap(), 1e-7);
}

// Whatever a caller asks (a prediction coasted past the camera asked for a window many times wider than
// the image, in blocks as wide; campaign plate/26 ran for an hour), the window covers at most
// max_window_px raw pixels a side with at least 16 working pixels (max_side 64 here), and is read in
// bounded time.
TEST(WorkingImage, AnyWindowAskedForIsBoundedByTheLargestWindow) {
  const std::vector<std::uint8_t> pixels = stepImage();
  const MonoImage image = MonoImage::from8(ImageView8(pixels.data(), 200, 160));
  WorkingImage w;
  constexpr int kMaxWindow = 400;  // twice the image's larger side
  ASSERT_TRUE(w.init(64, 256, kMaxWindow).ok);
  EXPECT_FALSE(w.init(64, 256, 8).ok);
  ASSERT_TRUE(w.init(64, 256, kMaxWindow).ok);
  struct Ask {
    double half_px;
    int scale;
  };
  for (const Ask ask :
       {Ask{1.0e5, 1}, Ask{1.0e5, 30000}, Ask{60.0, 1 << 30},
        Ask{std::numeric_limits<double>::quiet_NaN(), 4}, Ask{std::numeric_limits<double>::infinity(), 2}}) {
    const int used = w.setWindow(Vec2(100.0, 80.0), ask.half_px, ask.scale);
    EXPECT_EQ(used, w.scale());
    EXPECT_GE(used, 1);
    EXPECT_LE(w.width() * used, kMaxWindow + used) << ask.half_px << " " << ask.scale;  // + rounding
    EXPECT_GE(w.width(), 16) << "a window keeps working pixels";
    EXPECT_EQ(w.width(), w.height());
    w.prepare(image, 1, 4, 1000.0);
    EXPECT_TRUE(std::isfinite(w.stats().edge_snr));
  }
  // An ordinary window is as asked.
  EXPECT_EQ(w.setWindow(Vec2(100.0, 80.0), 60.0, 2), 2);
  EXPECT_EQ(w.width(), 60);
}

TEST(WorkingImage, AWindowCentredFarOffTheImageIsPaddingAndNoPointReachesAnIntCast) {
  // A coasted prediction's line of sight through a strong distortion can project past the int range
  // (or NaN): the window's origin stays within a few windows of the image, where prepare() indexes in int,
  // and a sample point anywhere (1e300, NaN) reads no evidence.
  const std::vector<std::uint8_t> pixels = stepImage();
  const MonoImage image = MonoImage::from8(ImageView8(pixels.data(), 200, 160));
  WorkingImage w;
  constexpr int kMaxWindow = 400;
  ASSERT_TRUE(w.init(64, 256, kMaxWindow).ok);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Vec2& centre : {Vec2(1.0e12, -1.0e12), Vec2(-1.0e300, 1.0e300), Vec2(nan, nan)}) {
    w.setWindow(centre, 60.0, 1);
    const Vec2 origin = w.toFull(Vec2::Zero());
    const Vec2 far_corner = w.toFull(Vec2(w.width(), w.height()));
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(origin[k], -2.0 * kMaxWindow) << centre.transpose();
      EXPECT_LE(far_corner[k], 3.0 * kMaxWindow) << centre.transpose();
    }
    w.prepare(image, 1, 4, 1000.0);
    EXPECT_TRUE(std::isfinite(w.stats().edge_snr));
  }
  w.setWindow(Vec2(100.0, 80.0), 60.0, 1);
  w.prepare(image, 1, 4, 1000.0);
  const ChannelBlend blend = ChannelBlend::of(0.0);
  EXPECT_GT(w.evidence(w.toWorking(Vec2(100.0, 80.0)), blend, Evidence::kFine), 0.0)
      << "on the step: a live check";
  for (const Vec2& p : {Vec2(1.0e300, 5.0), Vec2(5.0, -1.0e300), Vec2(nan, 5.0), Vec2(-0.5, 5.0)})
    EXPECT_EQ(w.evidence(p, blend, Evidence::kFine), 0.0) << p.transpose();
}

TEST(WorkingImage, NoiseAloneHasLowEdgeSnrAndATargetHigh) {
  const test::Scene scene = test::makeScene(test::Target::kPlate);
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::vgaCamera(), scene.model, scene.render).ok);
  const Pose truth = test::plateAt(15.0);
  const test::RenderedFrame target = test::renderFrame(renderer, truth, 3);
  const test::RenderedFrame empty = test::renderFrame(renderer, test::plateAt(15.0, 100.0), 3);
  WorkingImage w;
  ASSERT_TRUE(w.init(256, 2048, 1280).ok);
  w.setWindow(Vec2(320.0, 240.0), 120.0, 1);
  w.prepare(empty.image(), 2, 8, 4.0);
  // Rayleigh-distributed noise gradients: p99.9 / median = sqrt(2 ln 1000) / sqrt(2 ln 2) = 3.2.
  EXPECT_NEAR(w.stats().edge_snr, 3.2, 0.8);
  w.prepare(target.image(), 2, 8, 4.0);
  EXPECT_GT(w.stats().edge_snr, 8.0);
  const Vec2 centre = w.toFull(w.stats().strong_centroid_w);
  EXPECT_NEAR((centre - Vec2(320.0, 240.0)).norm(), 0.0, 3.0);  // the plate's outline is centred there
}

// A dim disc (0.34 on 0.20, 48 px radius) under Gaussian noise sigma 0.1, like the campaign's dim targets
// (octagon/8: 0.28 on 0.145, noise 0.09), and the same noise alone. At the working scale the outline is lost
// in the noise's tail (edge SNR 3.2-3.3, as noise alone's 3.1); box-averaged to a 12 px radius (factor 4)
// the noise's gradient drops 4 times, the step's does not: 6.4-6.8 here, noise alone 2.9-3.5.
std::vector<std::uint8_t> dimDiscImage(bool with_disc, std::uint32_t seed) {
  constexpr int kW = 320;
  constexpr int kH = 240;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(kW) * kH);
  std::uint32_t state = seed;
  auto uniform = [&state]() {  // xorshift32: the same image on every machine
    state ^= state << 13U;
    state ^= state >> 17U;
    state ^= state << 5U;
    return (static_cast<double>(state) + 1.0) / 4294967297.0;
  };
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const bool inside = with_disc && std::hypot(x + 0.5 - 160.0, y + 0.5 - 120.0) < 48.0;
      const double gauss = std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * kPi * uniform());
      const double v = (inside ? 0.34 : 0.20) + 0.1 * gauss;
      pixels[static_cast<std::size_t>(y) * kW + static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(std::clamp(v * 255.0 + 0.5, 0.0, 255.0));
    }
  }
  return pixels;
}

TEST(WorkingImage, ADimOutlineUnderNoiseStandsOutBoxAveragedAndNoiseAloneDoesNot) {
  WorkingImage w;
  ASSERT_TRUE(w.init(256, 2048, 640).ok);
  for (std::uint32_t seed : {1U, 2U, 3U}) {
    const std::vector<std::uint8_t> disc = dimDiscImage(true, seed);
    const std::vector<std::uint8_t> noise = dimDiscImage(false, seed);
    w.setWindow(Vec2(160.0, 120.0), 80.0, 1);
    w.setCoarseSnrFactor(1);
    w.prepare(MonoImage::from8(ImageView8(disc.data(), 320, 240)), 2, 8, 4.0);
    EXPECT_LT(w.stats().edge_snr, 5.0) << "the working scale cannot see it: what the coarse test is for";
    EXPECT_EQ(w.stats().coarse_edge_snr, 0.0) << "not asked";
    EXPECT_EQ(w.stats().detectionSnr(), w.stats().edge_snr);
    w.setCoarseSnrFactor(4);
    w.prepare(MonoImage::from8(ImageView8(disc.data(), 320, 240)), 2, 8, 4.0);
    EXPECT_EQ(w.stats().coarse_factor, 4);
    EXPECT_GT(w.stats().coarse_edge_snr, 5.5) << seed;
    EXPECT_EQ(w.stats().detectionSnr(), w.stats().coarse_edge_snr);
    w.prepare(MonoImage::from8(ImageView8(noise.data(), 320, 240)), 2, 8, 4.0);
    EXPECT_LT(w.stats().coarse_edge_snr, 4.2) << seed;
    EXPECT_LT(w.stats().detectionSnr(), 4.2) << seed;
  }
  // A factor that would leave the copy under 8 px a side is lowered to one that does not.
  w.setWindow(Vec2(160.0, 120.0), 20.0, 1);  // 40 working px
  w.setCoarseSnrFactor(16);
  const std::vector<std::uint8_t> disc = dimDiscImage(true, 1U);
  w.prepare(MonoImage::from8(ImageView8(disc.data(), 320, 240)), 2, 8, 4.0);
  EXPECT_EQ(w.stats().coarse_factor, 5);
}

class ScorerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene = test::makeScene(test::Target::kPlate);
    ASSERT_TRUE(renderer.init(test::vgaCamera(), scene.model, scene.render).ok);
    truth = Pose{test::tiltedAttitude(25.0, 30.0, 40.0), Vec3(0.2, -0.1, 12.0)};
    frame = test::renderFrame(renderer, truth, 21);
    ASSERT_TRUE(window.init(256, 2048, 1280).ok);
    Vec2 centre;
    test::vgaCamera().project(truth.t_c_m, centre);
    window.setWindow(centre, 200.0, 4);
    window.prepare(frame.image(), 2, 8, 4.0);
    ASSERT_TRUE(scorer.init(test::vgaCamera(), scene.model, ScorerSettings{}).ok);
  }
  test::Scene scene;
  synthetic::Renderer renderer;
  Pose truth;
  test::RenderedFrame frame;
  WorkingImage window;
  EdgeScorer scorer;
};

TEST_F(ScorerTest, TruthScoresBestAndAgreesBothWays) {
  Vec6 off;
  off << 0.0, 0.0, 0.0, 0.2, 0.0, 0.0;  // 0.2 m at 12 m: 17 px, 4 working px
  const Pose shifted = truth.boxPlus(off);
  EXPECT_GT(scorer.score(truth, window, Evidence::kRaw), 0.8);  // every sample on a clear edge (saturated)
  EXPECT_LT(scorer.score(shifted, window, Evidence::kRaw), 0.6);
  // The coarse copy still sees the shifted outline, less (tent-weighted): a slope towards the truth.
  EXPECT_GT(scorer.score(shifted, window, Evidence::kCoarse), 0.5);
  EXPECT_LT(scorer.score(shifted, window, Evidence::kCoarse),
            scorer.score(truth, window, Evidence::kCoarse) - 0.1);
  const EdgeAgreement at_truth = scorer.agreement(truth, window, 2.5);
  EXPECT_GT(at_truth.precision, 0.95);
  EXPECT_GT(at_truth.recall, 0.95);
  EXPECT_LT(scorer.agreement(shifted, window, 2.5).f1, 0.7);
  // Seen from behind nothing is visible: no score.
  Pose behind = truth;
  behind.R_c_m = truth.R_c_m * Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();
  EXPECT_EQ(scorer.score(behind, window, Evidence::kRaw), -1.0);
}

TEST_F(ScorerTest, AlignedScoreFindsTheShift) {
  Vec6 off;
  off << 0.0, 0.0, 0.0, 0.25, -0.15, 0.0;  // 5.2 and 3.1 working px
  Vec2 shift;
  // Centroid alignment then +-2 one-pixel steps on the raw evidence: back within a pixel.
  const double aligned = scorer.scoreAligned(truth.boxPlus(off), window, Evidence::kRaw,
                                             window.stats().strong_centroid_w, 2, 1.0, shift);
  EXPECT_GT(aligned, 0.8);
  const Pose back = scorer.shifted(truth.boxPlus(off), window, shift);
  EXPECT_LT((back.t_c_m - truth.t_c_m).norm(), 0.05);  // one working px is 4.8 cm here
  // On a plateau of the coarse evidence the centred shift wins the tie.
  Vec2 coarse_shift;
  scorer.scoreAligned(truth, window, Evidence::kCoarse, window.stats().strong_centroid_w, 1, 8.0,
                      coarse_shift);
  EXPECT_LT(coarse_shift.norm(), 2.0);
}

TEST_F(ScorerTest, BestShiftsFindTheOutlineWhereverItMovedAndKeepTheirPeaksApart) {
  // The close-range reacquisition's cue: the outline at a stale pose slid over the window. 0.9 m and
  // -0.6 m at 12 m are 75 and 50 px (19 and 12.5 working px) from where the stale pose puts the plate.
  Vec6 off;
  off << 0.0, 0.0, 0.0, 0.9, -0.6, 0.0;
  const Pose stale = truth.boxPlus(off);
  std::array<ShiftPeak, 4> peaks{};
  const int n = scorer.bestShifts(stale, window, 40.0, 4.0, 20.0, peaks.data(), 4);
  ASSERT_GE(n, 1);
  ASSERT_LE(n, 4);
  const Pose back = scorer.shifted(stale, window, peaks[0].shift);
  EXPECT_LT((back.t_c_m - truth.t_c_m).norm(), 0.1) << "within 2 working px (one is 4.8 cm here)";
  EXPECT_GT(peaks[0].score, 0.5);
  for (int i = 1; i < n; ++i) {
    EXPECT_LE(peaks[static_cast<std::size_t>(i)].score, peaks[static_cast<std::size_t>(i - 1)].score);
    // 20 px apart on the coarse grid; the fine refinement moves each by at most two half steps
    // diagonally (2 sqrt(2) 2 px).
    for (int j = 0; j < i; ++j)
      EXPECT_GE((peaks[static_cast<std::size_t>(i)].shift - peaks[static_cast<std::size_t>(j)].shift).norm(),
                20.0 - 2.0 * 4.0 * std::sqrt(2.0));
  }
  // Out of reach (the disc is smaller than the motion): no peak there.
  const int near_only = scorer.bestShifts(stale, window, 8.0, 4.0, 8.0, peaks.data(), 4);
  for (int i = 0; i < near_only; ++i)
    EXPECT_GT(
        (scorer.shifted(stale, window, peaks[static_cast<std::size_t>(i)].shift).t_c_m - truth.t_c_m).norm(),
        0.3);
  // Nothing visible or nowhere to write: nothing.
  Pose behind = truth;
  behind.R_c_m = truth.R_c_m * Eigen::AngleAxisd(kPi, Vec3::UnitX()).toRotationMatrix();
  EXPECT_EQ(scorer.bestShifts(behind, window, 40.0, 4.0, 8.0, peaks.data(), 4), 0);
  EXPECT_EQ(scorer.bestShifts(stale, window, 40.0, 4.0, 8.0, peaks.data(), 0), 0);
}

/// RMS image distance [px, full resolution] between the model's vertices at two poses.
double vertexRmsPx(const PolygonModel& model, const Pose& a, const Pose& b) {
  double sum = 0.0;
  for (const Vec3& v : model.vertices()) {
    Vec2 pa, pb;
    test::vgaCamera().project(a.transform(v), pa);
    test::vgaCamera().project(b.transform(v), pb);
    sum += (pa - pb).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(model.vertices().size()));
}

TEST_F(ScorerTest, RefinementClimbsBackToTheTruth) {
  Vec6 off;
  off << 0.08, -0.06, 0.1, 0.1, 0.05, 0.8;  // ~8 deg, 10 cm lateral, 7 % range
  Pose pose = truth.boxPlus(off);
  int evaluations = 0;
  const double s = scorer.refine(window, RefineSettings{}, pose, evaluations);
  EXPECT_GT(s, scorer.score(truth.boxPlus(off), window, Evidence::kRaw));
  // What the tracker needs is the image: the outline comes back within its wide scanlines (16 px). Tilt and
  // range of a plate trade against each other at this resolution, so the pose itself may stay a few deg off.
  const double before_px = vertexRmsPx(scene.model, truth.boxPlus(off), truth);
  const double after_px = vertexRmsPx(scene.model, pose, truth);
  EXPECT_GT(before_px, 15.0);
  EXPECT_LT(after_px, 0.3 * before_px);
  EXPECT_LT(after_px, 6.0);
  // Bounded: levels x (1 + sweeps x 12 trials).
  const RefineSettings r;
  EXPECT_LE(evaluations, r.levels * (1 + r.sweeps_per_level * 12));
}

TEST(AcquisitionParamsTest, CrossCheckAndInit) {
  AcquisitionParams p;
  EXPECT_EQ(p.crossCheck(), nullptr);
  p.candidates = p.search_candidates + 1;
  EXPECT_NE(p.crossCheck(), nullptr);
  Acquisition a;
  const LoadError e = a.init(test::vgaCamera(), makeRectanglePlate(2.3, 1.8), p, NearRangeParams{});
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("candidates"), std::string::npos);
}

}  // namespace
TEST(AcquisitionDebugView, EveryRefinedCandidateSaysWhatTheVerifyingTrackerMadeOfIt) {
  // The campaign trace's verify: line: each refined candidate carries the verifier's last pass.
  const test::Scene scene = test::makeScene(test::Target::kPlate);
  acq::Acquisition acquisition;
  ASSERT_TRUE(
      acquisition.init(test::vgaCamera(), scene.model, acq::AcquisitionParams{}, NearRangeParams{}).ok);
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::vgaCamera(), scene.model, scene.render).ok);
  const Pose truth{test::tiltedAttitude(20.0, 30.0, 40.0), Vec3(-0.9, 0.2, 12.0)};
  const auto frames = test::renderStatic(renderer, truth, 8, 900U);
  acquisition.start(test::perturbedCue(truth, 0.5, 0.0, 0.1));
  acq::AcquisitionResult r;
  std::size_t i = 0;
  for (; i + 1 < frames.size() && acquisition.state() == acq::AcquisitionState::kSearching; ++i)
    acquisition.step(frames[i].image(), i, r);
  ASSERT_EQ(acquisition.state(), acq::AcquisitionState::kVerifying);
  EXPECT_EQ(acquisition.verifyPasses().size(), 0U);
  acquisition.step(frames[i].image(), i, r);
  ASSERT_GT(acquisition.refined().size(), 0U);
  ASSERT_EQ(acquisition.verifyPasses().size(), acquisition.refined().size());
  const acq::AcquisitionParams& p = acquisition.params();
  int passed = 0;
  bool right_one = false;
  for (const acq::AcquisitionVerifyPass& v : acquisition.verifyPasses()) {
    const bool ok = v.status != TrackStatus::kLost && v.rms_px <= p.max_rms_px && v.quality >= p.min_quality;
    passed += ok ? 1 : 0;
    right_one = right_one || (ok && (v.pose.t_c_m - truth.t_c_m).norm() < 0.05);
  }
  EXPECT_EQ(passed, r.candidates_verified);
  EXPECT_TRUE(right_one) << "the still plate's right pose is among those the verifier passed";
}

}  // namespace visnav::acq
