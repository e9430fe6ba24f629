// The whole-config loader: every table lands in its struct, a typo or a bad value anywhere is an error naming
// file:line:key, relative paths resolve against the config's folder, cross-table rules hold, and the shipped
// configs are valid.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "visnav/app/visnav_config.hpp"

namespace visnav::app {
namespace {

const std::string kSource = VISNAV_SOURCE_DIR;

class ConfigFiles : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    std::string path = m_dir + "/config" + std::to_string(m_count++) + ".toml";
    std::ofstream(path) << text;
    return path;
  }
  void SetUp() override {
    char pattern[] = "/tmp/visnav-config-XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    m_dir = pattern;
  }
  void TearDown() override {
    std::error_code ignored;  // a temporary folder left behind is not a test failure
    std::filesystem::remove_all(m_dir, ignored);
  }
  std::string m_dir;
  int m_count = 0;
};

TEST_F(ConfigFiles, EveryTableLandsInItsStruct) {
  const std::string path = write(
      "[navigation]\nenter_frames = 7\n[nearrange]\nransac_iterations = 55\n[farrange]\ngamma = 4480.0\n"
      "[acquisition]\nroll_steps = 12\n[filter]\npose_gate_chi2 = 16.81\n[executive]\nmajor_frame_hz = 20.0\n"
      "[camera]\ndriver = \"replay\"\ndevice = \"seq\"\n[telemetry]\npartition = \"bench-1\"\ndomain_id = 7\n"
      "[files]\nmodel = \"/abs/model.toml\"\n[daemon]\nplayback_pacing = \"as_fast_as_possible\"\n"
      "playback_loop = true\nlog_throttle = 3\n");
  VisnavConfig c;
  const LoadError e = loadVisnavConfig(path, c);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(c.pipeline.navigation.enter_frames, 7);
  EXPECT_EQ(c.pipeline.nearrange.ransac_iterations, 55);
  EXPECT_EQ(c.pipeline.farrange.gamma, 4480.0);
  EXPECT_EQ(c.pipeline.acquisition.roll_steps, 12);
  EXPECT_EQ(c.pipeline.filter.pose_gate_chi2, 16.81);
  EXPECT_EQ(c.executive.major_frame_hz, 20.0);
  EXPECT_EQ(c.camera.driverKind(), camera::CameraDriver::kReplay);
  EXPECT_EQ(c.camera.device, m_dir + "/seq");  // replay: relative to the config's folder
  EXPECT_STREQ(c.telemetry.partitionName(), "bench-1");
  EXPECT_EQ(c.telemetry.domain_id, 7);
  EXPECT_EQ(c.files.model, "/abs/model.toml");  // absolute: unchanged
  EXPECT_TRUE(c.files.camera.empty());
  EXPECT_EQ(c.daemon.pacing(), PlaybackPacing::kAsFastAsPossible);
  EXPECT_TRUE(c.daemon.playback_loop);
  EXPECT_EQ(c.daemon.log_throttle, 3);
  // Untouched keys keep their defaults.
  EXPECT_EQ(c.pipeline.navigation.coast_frames, nav::NavigationParams{}.coast_frames);
  EXPECT_EQ(c.executive.minor_frames_per_major, 1);
}

// A typo in any table is an error naming the file, the line and the key.
TEST_F(ConfigFiles, UnknownKeyInAnyTableNamesFileLineAndKey) {
  for (const char* table : {"navigation", "nearrange", "farrange", "acquisition", "filter", "executive",
                            "camera", "telemetry", "files", "daemon", "nosuchtable"}) {
    const std::string path = write(std::string("# comment\n[") + table + "]\nenter_framez = 3\n");
    VisnavConfig c;
    const LoadError e = loadVisnavConfig(path, c);
    ASSERT_FALSE(e.ok) << table;
    EXPECT_EQ(e.message, path + ":3: unknown key [" + table + "] enter_framez") << table;
  }
}

TEST_F(ConfigFiles, BadValuesNameTheKey) {
  struct Case {
    const char* text;
    const char* expected;  // substring of the message
  };
  const Case cases[] = {
      {"[navigation]\nenter_frames = 0\n", ":2: [navigation] enter_frames = 0 is outside [1, 1000]"},
      {"[executive]\nmajor_frame_hz = \"fast\"\n", ":2: [executive] major_frame_hz must be a number"},
      {"[camera]\ndriver = \"usb\"\n", ":2: [camera] driver 'usb' is not one of"},
      {"[daemon]\nplayback_pacing = \"slow\"\n", ":2: [daemon] playback_pacing 'slow' is not one of"},
      {"[filter]\npose_gate_chi2 = -1.0\n", ":2: [filter] pose_gate_chi2 = -1 is outside"},
      {"[telemetry]\npartition = \"a b\"\n", "[telemetry] partition 'a b' may hold only"},
      {"[navigation]\nacquire_below_m = 50.0\nfar_range_above_m = 40.0\n", "far_range_above_m must exceed"},
      {"[navigation]\nhandover_radius_px = 30.0\nnear_range_min_radius_px = 30.0\n",
       "near_range_min_radius_px must be below handover_radius_px"},
      {"[camera]\ndriver = \"v4l2\"\n", "[camera] device must name the V4L2 node"},
  };
  for (const Case& c : cases) {
    const std::string path = write(c.text);
    VisnavConfig config;
    const LoadError e = loadVisnavConfig(path, config);
    ASSERT_FALSE(e.ok) << c.text;
    EXPECT_NE(e.message.find(c.expected), std::string::npos) << e.message;
    EXPECT_EQ(e.message.rfind(path, 0), 0U) << "message starts with the file: " << e.message;
  }
}

// What a daemon run needs beyond valid tables; tools that read only the algorithm tables skip it.
TEST_F(ConfigFiles, RunRequirements) {
  VisnavConfig c;
  ASSERT_TRUE(loadVisnavConfig(write("[camera]\ndriver = \"v4l2\"\ndevice = \"/dev/video0\"\n"), c).ok);
  ASSERT_NE(runProblem(c), nullptr);
  EXPECT_NE(std::string(runProblem(c)).find("[files] camera must name the calibration"), std::string::npos);
  ASSERT_TRUE(
      loadVisnavConfig(write("[camera]\ndriver = \"libcamera\"\n[files]\ncamera = \"c.toml\"\n"), c).ok);
  ASSERT_NE(runProblem(c), nullptr);
  EXPECT_NE(std::string(runProblem(c)).find("[files] model must name"), std::string::npos);
  ASSERT_TRUE(
      loadVisnavConfig(write("[nearrange]\nransac_iterations = 50\n"), c).ok);  // synthetic, no scenario
  ASSERT_NE(runProblem(c), nullptr);
  EXPECT_NE(std::string(runProblem(c)).find("must name the scenario file"), std::string::npos);
  // A libcamera id is not a path: never resolved.
  ASSERT_TRUE(loadVisnavConfig(write("[camera]\ndriver = \"libcamera\"\ndevice = \"cam0\"\n[files]\n"
                                     "camera = \"c.toml\"\nmodel = \"m.toml\"\n"),
                               c)
                  .ok);
  EXPECT_EQ(runProblem(c), nullptr);
  EXPECT_EQ(c.camera.device, "cam0");
  EXPECT_EQ(c.files.camera, m_dir + "/c.toml");
}

TEST_F(ConfigFiles, ConfiguredFilesAreLoadedAndCheckedAgainstTheCamera) {
  const std::string cameras = kSource + "/config/cameras/vga_6mm.toml";
  VisnavConfig c;
  ASSERT_TRUE(loadVisnavConfig(
                  write("[camera]\ndriver = \"v4l2\"\ndevice = \"/dev/video0\"\nwidth_px = 320\n"
                        "[files]\ncamera = \"" +
                        cameras + "\"\nmodel = \"" + kSource + "/config/models/plate_2300x1800.toml\"\n"),
                  c)
                  .ok);
  CameraIntrinsics intrinsics;
  PolygonModel model;
  bool have_camera = false;
  bool have_model = false;
  LoadError e = loadConfiguredFiles(c, intrinsics, have_camera, model, have_model);
  ASSERT_FALSE(e.ok);
  EXPECT_NE(e.message.find("width_px x height_px = 320x480 but the calibration"), std::string::npos)
      << e.message;
  c.camera.width_px = 640;
  e = loadConfiguredFiles(c, intrinsics, have_camera, model, have_model);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_TRUE(have_camera && have_model);
  EXPECT_EQ(intrinsics.width_px, 640);
  EXPECT_EQ(model.vertices().size(), 4U);
  c.files.model = m_dir + "/missing.toml";
  e = loadConfiguredFiles(c, intrinsics, have_camera, model, have_model);
  ASSERT_FALSE(e.ok);
  EXPECT_NE(e.message.find("missing.toml"), std::string::npos) << e.message;
}

TEST(ShippedConfigs, AreValidWithTheirFiles) {
  for (const char* name : {"visnav.toml", "visnavd.toml", "visnavd-testbed.toml"}) {
    VisnavConfig c;
    const LoadError e = loadVisnavConfig(kSource + "/config/" + name, c);
    ASSERT_TRUE(e.ok) << name << ": " << e.message;
    CameraIntrinsics intrinsics;
    PolygonModel model;
    bool have_camera = false;
    bool have_model = false;
    const LoadError f = loadConfiguredFiles(c, intrinsics, have_camera, model, have_model);
    EXPECT_TRUE(f.ok) << name << ": " << f.message;
    if (std::string(name) != "visnav.toml") {  // the daemon's configs are runnable as they are
      EXPECT_EQ(runProblem(c), nullptr) << name;
    }
  }
  VisnavConfig daemon;
  ASSERT_TRUE(loadVisnavConfig(kSource + "/config/visnavd.toml", daemon).ok);
  EXPECT_EQ(daemon.camera.driverKind(), camera::CameraDriver::kSynthetic);
  EXPECT_EQ(daemon.camera.device, kSource + "/config/scenarios/full_approach_ci.toml");
  EXPECT_EQ(access(daemon.camera.device.c_str(), R_OK), 0);
}

TEST(ResolvePaths, AgainstTheConfigFolder) {
  EXPECT_EQ(resolveAgainstConfig("/etc/visnav/v.toml", "cam.yaml"), "/etc/visnav/cam.yaml");
  EXPECT_EQ(resolveAgainstConfig("v.toml", "cam.yaml"), "cam.yaml");
  EXPECT_EQ(resolveAgainstConfig("conf/v.toml", "../cam.yaml"), "conf/../cam.yaml");
  EXPECT_EQ(resolveAgainstConfig("conf/v.toml", "/abs.yaml"), "/abs.yaml");
  EXPECT_EQ(resolveAgainstConfig("conf/v.toml", ""), "");
}

}  // namespace
}  // namespace visnav::app
