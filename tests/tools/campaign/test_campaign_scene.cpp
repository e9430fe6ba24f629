// visnav-campaign scene draws: reproducibility from (family, seed), the ranges of the draws, the frame cap,
// the rerun command, the gradient background and the named cases.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "visnav/campaign/options.hpp"
#include "visnav/campaign/scene.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::campaign {
namespace {

ModelLibrary loadModels() {
  ModelLibrary m;
  m.smallsat_path = std::string(VISNAV_SOURCE_DIR) + "/config/models/smallsat_panels.toml";
  m.cao_path = std::string(VISNAV_SOURCE_DIR) + "/config/models/plate_2300x1800.cao";
  EXPECT_TRUE(io::loadModel(m.smallsat_path, m.smallsat).ok);
  EXPECT_TRUE(io::loadModel(m.cao_path, m.cao).ok);
  return m;
}

const ModelLibrary& models() {
  static const ModelLibrary m = loadModels();
  return m;
}

std::string paramText(const Scene& s) {
  std::string out;
  for (const SceneParam& p : sceneParameters(s)) out += p.key + "=" + p.value + ";";
  return out;
}

Scene draw(Family f, std::uint64_t seed, int max_frames = 0) {
  Scene s;
  EXPECT_TRUE(drawScene(f, seed, models(), max_frames, s).ok);
  return s;
}

TEST(CampaignScene, SameFamilyAndSeedGiveTheSameScene) {
  for (int f = 0; f < kFamilyCount; ++f) {
    for (std::uint64_t seed : {1ULL, 42ULL, 123456789ULL}) {
      const Scene a = draw(static_cast<Family>(f), seed);
      const Scene b = draw(static_cast<Family>(f), seed);
      EXPECT_EQ(paramText(a), paramText(b));
      ASSERT_EQ(a.frames, b.frames);
      for (int i = 0; i < a.frames; i += 7) {
        EXPECT_EQ(a.truth(i).R_c_m, b.truth(i).R_c_m);
        EXPECT_EQ(a.truth(i).t_c_m, b.truth(i).t_c_m);
        EXPECT_EQ(a.eclipsed(i), b.eclipsed(i));
      }
      EXPECT_EQ(a.model.vertices(), b.model.vertices());
      EXPECT_EQ(a.render.glints.size(), b.render.glints.size());
      EXPECT_EQ(a.render.limb.center_x_px, b.render.limb.center_x_px);
      EXPECT_EQ(a.noise_seed, b.noise_seed);
    }
  }
}

TEST(CampaignScene, SeedsAndFamiliesGiveDifferentScenes) {
  EXPECT_NE(paramText(draw(Family::kBox, 1)), paramText(draw(Family::kBox, 2)));
  // The family is part of the stream: the same seed draws another camera for another family.
  EXPECT_NE(draw(Family::kPlate, 7).camera.fx_px, draw(Family::kBox, 7).camera.fx_px);
}

TEST(CampaignScene, DrawsStayInTheirRanges) {
  int approach = 0, eclipse = 0, slew = 0, shading = 0;
  int kinds[5] = {};
  for (int f = 0; f < kFamilyCount; ++f) {
    for (std::uint64_t seed = 1; seed <= 60; ++seed) {
      const Scene s = draw(static_cast<Family>(f), seed);
      SCOPED_TRACE(s.name);
      EXPECT_GE(s.camera.fx_px, 600.0);
      EXPECT_LE(s.camera.fx_px, 1400.0);
      EXPECT_GE(s.camera.distortion.k1, -0.08);
      EXPECT_LE(s.camera.distortion.k1, 0.02);
      EXPECT_NEAR(s.camera.cx_px, 0.5 * s.camera.width_px, 0.021 * s.camera.width_px);
      EXPECT_GE(s.render.noise_sigma, 0.02);
      EXPECT_LE(s.render.noise_sigma, 0.12);
      EXPECT_GE(s.render.blur_sigma_px, 0.3);
      EXPECT_LE(s.render.blur_sigma_px, 1.2);
      EXPECT_TRUE(s.render.blur_size_px == 5 || s.render.blur_size_px == 7);
      EXPECT_GE(s.target_brightness, 0.25);
      EXPECT_LE(s.target_brightness, 0.9);
      EXPECT_GE(s.render.background, 0.0);
      EXPECT_LE(s.render.background, 1.0);
      EXPECT_GE(s.tumble_deg_per_frame, 0.0);
      EXPECT_LE(s.tumble_deg_per_frame, 1.0);
      EXPECT_NEAR(s.tumble_axis_m.norm(), 1.0, 1e-12);
      EXPECT_GT(s.gamma, 0.0);
      if (s.approach) {
        ++approach;
        EXPECT_EQ(s.d_start_m, 750.0);
        EXPECT_GE(s.frames, 150);
        EXPECT_LE(s.frames, 250);
        EXPECT_GE(s.d_end_m, 5.0);
      } else {
        EXPECT_GE(s.frames, 100);
        EXPECT_LE(s.frames, 200);
        EXPECT_GE(s.d_end_m, 5.0);
        EXPECT_GE(s.d_start_m, s.d_end_m);
        // Near scenes start with the target at least 20 px across and inside the image.
        const Silhouette sil = s.silhouette(s.truth(0));
        EXPECT_TRUE(sil.in_front);
        EXPECT_GE(2.0 * sil.radius_px, 20.0 - 1e-9);
        EXPECT_LE(2.0 * sil.radius_px, std::min(s.camera.width_px, s.camera.height_px) + 1e-9);
      }
      if (s.events.eclipse) {
        ++eclipse;
        EXPECT_GE(s.events.eclipse_frames, 10);
        EXPECT_LE(s.events.eclipse_frames, 50);
        EXPECT_LE(s.events.eclipse_first + s.events.eclipse_frames, s.frames - 20);
      }
      if (s.events.slew) {
        ++slew;
        EXPECT_GE(s.events.slew_deg, 3.0);
        EXPECT_LE(s.events.slew_deg, 10.0);
        EXPECT_LT(s.events.slew_frame, s.frames);
        EXPECT_NEAR(s.events.slew_axis_c.z(), 0.0, 1e-12);
        if (s.events.eclipse) {
          EXPECT_TRUE(s.events.slew_frame < s.events.eclipse_first - 10 ||
                      s.events.slew_frame >= s.events.eclipse_first + s.events.eclipse_frames + 10);
        }
      }
      shading += s.render.shading.enabled ? 1 : 0;
      ++kinds[static_cast<int>(s.background)];
    }
  }
  // 300 scenes: every kind of draw happens, none always.
  EXPECT_GT(approach, 30);
  EXPECT_LT(approach, 120);
  EXPECT_GT(eclipse, 30);
  EXPECT_GT(slew, 30);
  EXPECT_GT(shading, 100);
  for (int k : kinds) EXPECT_GT(k, 25);
}

TEST(CampaignScene, MaxFramesCapsWithoutChangingTheDraws) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Scene full = draw(Family::kOctagon, seed);
    const Scene capped = draw(Family::kOctagon, seed, 60);
    EXPECT_EQ(capped.frames, std::min(60, full.frames));
    EXPECT_EQ(capped.frames_drawn, full.frames_drawn);
    EXPECT_EQ(capped.camera.fx_px, full.camera.fx_px);
    EXPECT_EQ(capped.model_text, full.model_text);
    EXPECT_EQ(capped.render.noise_sigma, full.render.noise_sigma);
    EXPECT_EQ(capped.d_start_m, full.d_start_m);
    EXPECT_EQ(capped.d_end_m, full.d_end_m);  // an approach still ends at d_end, in fewer frames
    EXPECT_EQ(capped.truth(0).t_c_m, full.truth(0).t_c_m);
    if (capped.approach) {
      EXPECT_NEAR(capped.distance(capped.frames - 1), capped.d_end_m, 1e-9);
    }
  }
}

TEST(CampaignScene, RerunCommandReproducesTheScene) {
  CampaignOptions campaign;
  campaign.seed = 1000;
  campaign.max_frames = 80;
  const Scene s = draw(Family::kBox, sceneSeed(campaign.seed, 7), campaign.max_frames);
  const std::string cmd = rerunCommand(s, campaign);
  EXPECT_EQ(cmd, "visnav-campaign --runs 1 --seed 1007 --families box --max-frames 80");
  // Parse it back (without the program name) and draw the one scene it asks for.
  std::vector<std::string> args;
  std::size_t start = cmd.find(' ') + 1;
  while (start < cmd.size()) {
    const std::size_t end = cmd.find(' ', start);
    args.push_back(cmd.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  CampaignOptions again;
  ASSERT_TRUE(parseArguments(args, again).ok);
  ASSERT_EQ(again.runs, 1);
  ASSERT_EQ(again.families.size(), 1U);
  const Scene t = draw(again.families[0], sceneSeed(again.seed, 0), again.max_frames);
  EXPECT_EQ(t.name, s.name);
  EXPECT_EQ(paramText(t), paramText(s));
}

TEST(CampaignScene, GradientCrossesTheTargetBrightnessInsideTheOutline) {
  const Vec2 centre(300.0, 200.0);
  const double r = 80.0;
  const double angle = 0.7;
  const GradientSolution g = solveGradient(0.25, 0.2, 0.3, centre, r, angle, 24.0, 1024.0);
  EXPECT_NEAR(g.contrast_plus, 0.2, 1e-6);
  EXPECT_NEAR(g.contrast_minus, 0.3, 1e-6);
  // The renderer's limb formula at the centre and at +-r along the ramp direction.
  auto level = [&](const Vec2& p) {
    const double depth = g.limb.radius_px - (p - Vec2(g.limb.center_x_px, g.limb.center_y_px)).norm();
    return g.background +
           (g.limb.brightness_limb - g.background) / (1.0 + std::exp(-depth / g.limb.softness_px));
  };
  const Vec2 u(std::cos(angle), std::sin(angle));
  EXPECT_NEAR(level(centre), 0.25, 1e-4);
  EXPECT_NEAR(level(centre - r * u), 0.25 - 0.2, 1e-4);  // target brighter by 0.2
  EXPECT_NEAR(level(centre + r * u), 0.25 + 0.3, 1e-4);  // target darker by 0.3
  // Infeasible contrasts are reduced so every level stays in [0, 1].
  const GradientSolution h = solveGradient(0.1, 0.3, 0.3, centre, r, angle, 24.0, 1024.0);
  EXPECT_GE(h.background, 0.0);
  EXPECT_LE(h.limb.brightness_limb, 1.0);
  EXPECT_LT(h.contrast_plus, 0.3);
}

TEST(CampaignScene, NamedCases) {
  for (const std::string& name : caseNames()) {
    Scene s;
    ASSERT_TRUE(makeCase(name, models(), 0, s).ok) << name;
    EXPECT_TRUE(s.is_case);
    EXPECT_EQ(s.name, name);
    EXPECT_GT(s.frames, 0);
  }
  Scene s;
  EXPECT_FALSE(makeCase("no_such_case", models(), 0, s).ok);
  ASSERT_TRUE(makeCase("eclipse_box", models(), 0, s).ok);
  EXPECT_EQ(s.events.eclipse_frames, 25);
  EXPECT_TRUE(s.eclipsed(60));
  ASSERT_TRUE(makeCase("slew_box", models(), 0, s).ok);
  // 8 deg at 10 m moves the target ~60 px sideways.
  const Silhouette before = s.silhouette(s.truth(39));
  const Silhouette after = s.silhouette(s.truth(40));
  EXPECT_NEAR(std::fabs(after.centre_px.x() - before.centre_px.x()), 60.0, 3.0);
  ASSERT_TRUE(makeCase("low_contrast_octagon", models(), 0, s).ok);
  EXPECT_NEAR(s.gradient_contrast_plus, 0.2, 1e-6);
  EXPECT_NEAR(s.gradient_contrast_minus, 0.3, 1e-6);
  EXPECT_EQ(s.camera.width_px, 1024);
  ASSERT_TRUE(makeCase("approach_smallsat", models(), 0, s).ok);
  EXPECT_TRUE(s.approach);
  EXPECT_NEAR(s.distance(0), 750.0, 1e-9);
  EXPECT_NEAR(s.distance(s.frames - 1), 5.0, 1e-9);
}

TEST(CampaignScene, FaceOnAreaAndGamma) {
  EXPECT_NEAR(faceOnArea(makeRectanglePlate(2.0, 1.5)), 3.0, 1e-12);
  EXPECT_NEAR(faceOnArea(makeBox(0.5, 0.4, 0.3)), 0.8, 1e-12);  // the +z face only
  const double s = 2.0 * std::sin(22.5 * kRadPerDeg);           // regular octagon side for r = 1
  EXPECT_NEAR(faceOnArea(makeRegularOctagonPlate(1.0)), 2.0 * (1.0 + std::sqrt(2.0)) * s * s, 1e-12);
  EXPECT_NEAR(faceOnArea(makeOctagonPlate(2.0, 1.0, 0.2)), 2.0 - 4.0 * 0.5 * 0.2 * 0.2, 1e-12);
  Scene sc = draw(Family::kPlate, 5);
  EXPECT_NEAR(sc.gamma, sc.camera.fx_px * std::sqrt(faceOnArea(sc.model)), 1e-9);
}

}  // namespace
}  // namespace visnav::campaign
