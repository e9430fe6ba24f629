// libvisnav (include/visnav/visnav.h): versioning, errors as codes plus text, commands, and the same numbers
// as the C++ pipeline driven the way visnav-replay drives it, bit for bit, through every mode.
#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "capi_test_support.hpp"
#include "gtest/gtest.h"
#include "visnav/app/visnav_config.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"
#include "visnav/navigation/navigation_pipeline.hpp"
#include "visnav/version.hpp"
#include "visnav/visnav.h"

namespace {

using visnav::test::cameraPath;
using visnav::test::configPath;
using visnav::test::modelPath;

visnav_handle* createOrFail() {
  visnav_handle* h = nullptr;
  char err[256] = "untouched";
  const int rc =
      visnav_create(configPath().c_str(), cameraPath().c_str(), modelPath().c_str(), &h, err, sizeof(err));
  EXPECT_EQ(rc, VISNAV_OK) << err;
  EXPECT_STREQ(err, "");
  return h;
}

TEST(CApi, VersionAndAbi) {
  EXPECT_EQ(visnav_abi_version(), VISNAV_ABI_VERSION);
  EXPECT_STREQ(visnav_version(), visnav::kVersion);
  EXPECT_STREQ(visnav_status_text(VISNAV_ERROR_LOAD), "load error");
  EXPECT_STREQ(visnav_status_text(99), "unknown");
  EXPECT_STREQ(visnav_mode_name(VISNAV_MODE_NEAR_RANGE), "near_range");
  EXPECT_STREQ(visnav_mode_name(7), "unknown");
  EXPECT_STREQ(visnav_track_status_name(VISNAV_TRACK_DEGRADED), "degraded");
  EXPECT_STREQ(visnav_fault_name(4), "innovation");
  EXPECT_STREQ(visnav_fault_name(31), "unknown");
}

TEST(CApi, CreateReportsLoadErrorsAsCodeAndText) {
  visnav_handle* h = reinterpret_cast<visnav_handle*>(0x1);  // must be reset to NULL on failure
  char err[256] = {};
  EXPECT_EQ(visnav_create(nullptr, "/nonexistent/camera.toml", modelPath().c_str(), &h, err, sizeof(err)),
            VISNAV_ERROR_LOAD);
  EXPECT_EQ(h, nullptr);
  EXPECT_NE(std::string(err).find("/nonexistent/camera.toml"), std::string::npos) << err;

  EXPECT_EQ(visnav_create(nullptr, cameraPath().c_str(), nullptr, &h, err, sizeof(err)), VISNAV_ERROR_LOAD);
  EXPECT_NE(std::string(err).find("no model"), std::string::npos) << err;

  // A config key that does not exist is an error naming it (visnavd's whole-config loader).
  const std::string bad = std::string(::testing::TempDir()) + "/capi_bad.toml";
  std::FILE* f = std::fopen(bad.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("[farrange]\ngamma_typo = 3.0\n", f);
  std::fclose(f);
  EXPECT_EQ(visnav_create(bad.c_str(), cameraPath().c_str(), modelPath().c_str(), &h, err, sizeof(err)),
            VISNAV_ERROR_LOAD);
  EXPECT_NE(std::string(err).find("gamma_typo"), std::string::npos) << err;

  // Truncated to the caller's buffer, always terminated.
  char small[8];
  std::memset(small, 'x', sizeof(small));
  EXPECT_EQ(visnav_create(nullptr, "/nonexistent/camera.toml", modelPath().c_str(), &h, small, sizeof(small)),
            VISNAV_ERROR_LOAD);
  EXPECT_EQ(std::strlen(small), sizeof(small) - 1);

  EXPECT_EQ(visnav_create(nullptr, cameraPath().c_str(), modelPath().c_str(), nullptr, err, sizeof(err)),
            VISNAV_ERROR_INVALID_ARGUMENT);
}

TEST(CApi, StepRejectsBadArgumentsAndLeavesTheSolutionAlone) {
  visnav_handle* h = createOrFail();
  ASSERT_NE(h, nullptr);
  std::int32_t width = 0, height = 0;
  ASSERT_EQ(visnav_image_size(h, &width, &height), VISNAV_OK);
  EXPECT_EQ(width, 640);
  EXPECT_EQ(height, 480);
  EXPECT_EQ(visnav_image_size(h, nullptr, &height), VISNAV_ERROR_INVALID_ARGUMENT);
  std::vector<std::uint8_t> image(640 * 480, 10);
  visnav_solution sol;
  std::memset(&sol, 0xAB, sizeof(sol));
  visnav_solution before;
  std::memcpy(&before, &sol, sizeof(sol));
  EXPECT_EQ(visnav_step(nullptr, image.data(), 640, 480, 0, 8, 0, &sol), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(visnav_step(h, image.data(), 640, 480, 0, 8, 0, nullptr), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(visnav_step(h, image.data(), 640, 480, 0, 7, 0, &sol), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(visnav_last_error(h)).find("bit_depth"), std::string::npos);
  EXPECT_EQ(visnav_step(h, image.data(), 640, 480, 639, 8, 0, &sol), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(visnav_step(h, image.data(), 320, 240, 641, 12, 0, &sol), VISNAV_ERROR_INVALID_ARGUMENT);  // odd
  EXPECT_EQ(visnav_step(h, image.data(), 0, 480, 0, 8, 0, &sol), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(std::memcmp(&sol, &before, sizeof(sol)), 0);

  // A frame of the wrong size is processed as visnavd does: not used, the bad_frame fault raised.
  ASSERT_EQ(visnav_step(h, image.data(), 320, 240, 0, 8, 1000, &sol), VISNAV_OK);
  EXPECT_EQ(sol.frame_received, 0);
  EXPECT_NE(sol.fault_bits & (1U << 11), 0U) << sol.fault_bits;
  EXPECT_STREQ(visnav_last_error(h), "");
  // No image: a cycle without a frame.
  ASSERT_EQ(visnav_step(h, nullptr, 0, 0, 0, 0, 2000, &sol), VISNAV_OK);
  EXPECT_EQ(sol.frame_received, 0);
  EXPECT_EQ(sol.cycle_number, 2U);
  EXPECT_NE(sol.fault_bits & (1U << 7), 0U);
  // 12-bit pixels in 16-bit words, padded rows.
  std::vector<std::uint16_t> wide(660 * 480, 400);
  ASSERT_EQ(visnav_step(h, wide.data(), 640, 480, 660 * 2, 12, 3000, &sol), VISNAV_OK);
  EXPECT_EQ(sol.frame_received, 1);
  EXPECT_EQ(sol.frame_number, 1U);  // the second image stepped (the wrong-size one was number 0)
  EXPECT_EQ(sol.mode, VISNAV_MODE_FAR_RANGE);
  visnav_destroy(h);
  visnav_destroy(nullptr);
  EXPECT_EQ(visnav_set_timing(nullptr, 1), VISNAV_ERROR_INVALID_ARGUMENT);
  EXPECT_STREQ(visnav_last_error(nullptr), "visnav: NULL handle");
}

TEST(CApi, CommandsAreValidatedAndAcknowledged) {
  visnav_handle* h = createOrFail();
  ASSERT_NE(h, nullptr);
  visnav_command_ack ack;
  EXPECT_EQ(visnav_command(h, VISNAV_COMMAND_RESUME, 7, &ack), VISNAV_ERROR_REJECTED);
  EXPECT_EQ(ack.accepted, 0);
  EXPECT_EQ(ack.command_id, 7U);
  EXPECT_STREQ(ack.reason, "not in standby");
  EXPECT_STREQ(visnav_last_error(h), "not in standby");
  EXPECT_EQ(visnav_command(h, VISNAV_COMMAND_STANDBY, 8, &ack), VISNAV_OK);
  EXPECT_EQ(ack.accepted, 1);
  EXPECT_EQ(ack.kind, VISNAV_COMMAND_STANDBY);
  EXPECT_STREQ(ack.reason, "ok");
  visnav_solution sol;
  ASSERT_EQ(visnav_step(h, nullptr, 0, 0, 0, 0, 1, &sol), VISNAV_OK);
  EXPECT_EQ(sol.mode, VISNAV_MODE_STANDBY);
  EXPECT_EQ(visnav_command(h, VISNAV_COMMAND_RESUME, 9, nullptr), VISNAV_OK);
  ASSERT_EQ(visnav_step(h, nullptr, 0, 0, 0, 0, 2, &sol), VISNAV_OK);
  EXPECT_EQ(sol.mode, VISNAV_MODE_FAR_RANGE);
  EXPECT_EQ(visnav_command(h, 17, 10, &ack), VISNAV_ERROR_INVALID_ARGUMENT);
  // Near range from a given pose, as visnav-replay --initial-pose.
  const double t[3] = {0.0, 0.0, 10.0};
  const double q[4] = {0.0, 1.0, 0.0, 0.0};
  EXPECT_EQ(visnav_start_near_range(h, t, q), VISNAV_OK);
  ASSERT_EQ(visnav_step(h, nullptr, 0, 0, 0, 0, 3, &sol), VISNAV_OK);
  EXPECT_EQ(sol.mode, VISNAV_MODE_NEAR_RANGE);
  const double zero[4] = {0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(visnav_start_near_range(h, t, zero), VISNAV_ERROR_INVALID_ARGUMENT);
  visnav_destroy(h);
}

// The reference: NavigationPipeline with visnav-replay's wiring (tools/replay/src/replay_runner.cpp): the
// whole-config loader's pipeline tables, the camera and model loaders, frames numbered by index, processed
// at their exposure time, no clock.
TEST(CApi, SameNumbersAsThePipelineBitForBitThroughEveryMode) {
  const visnav::test::RenderedSequence& seq = visnav::test::fullApproachFrames();
  ASSERT_EQ(seq.frames.size(), 198U);
  visnav::app::VisnavConfig config;
  ASSERT_TRUE(visnav::app::loadVisnavConfig(configPath(), config).ok);
  visnav::CameraIntrinsics intrinsics;
  ASSERT_TRUE(visnav::io::loadCamera(cameraPath(), intrinsics).ok);
  visnav::PolygonModel model;
  ASSERT_TRUE(visnav::io::loadModel(modelPath(), model).ok);
  auto reference = std::make_unique<visnav::nav::NavigationPipeline>();
  ASSERT_TRUE(reference->init(visnav::PinholeCamera(intrinsics), model, config.pipeline).ok);

  visnav_handle* h = createOrFail();
  ASSERT_NE(h, nullptr);
  int per_mode[4] = {0, 0, 0, 0};
  int acquisition_frames = 0;
  for (std::size_t i = 0; i < seq.frames.size(); ++i) {
    const visnav::test::RenderedFrame& f = seq.frames[i];
    visnav::Frame frame;
    frame.image = visnav::MonoImage::from8(visnav::ImageView8(f.pixels.data(), seq.width, seq.height));
    frame.exposure_time_ns = f.exposure_time_ns;
    frame.sequence = i;
    visnav::nav::NavSolution ref;
    reference->process(&frame, f.exposure_time_ns, ref);
    visnav_solution sol;
    ASSERT_EQ(visnav_step(h, f.pixels.data(), seq.width, seq.height, seq.width, 8, f.exposure_time_ns, &sol),
              VISNAV_OK);
    SCOPED_TRACE("frame " + std::to_string(i));
    ASSERT_EQ(sol.mode, static_cast<int>(ref.mode));
    ++per_mode[sol.mode];
    // The acquisition runs beside far range (acquire_beside_far_range) or in its own mode.
    acquisition_frames += reference->lastAcquisition().state != visnav::acq::AcquisitionState::kIdle ? 1 : 0;
    ASSERT_EQ(sol.frame_number, ref.frame_number);
    ASSERT_EQ(sol.fault_bits, ref.fault_bits);
    ASSERT_EQ(sol.pose_valid, ref.pose_valid ? 1 : 0);
    ASSERT_EQ(sol.symmetric_twins, ref.symmetric_twins);
    ASSERT_EQ(sol.twin_by_continuity, ref.twin_by_continuity ? 1 : 0);
    ASSERT_EQ(sol.quality, ref.quality);  // exact: same code, same inputs
    ASSERT_EQ(sol.far_valid, ref.far.valid ? 1 : 0);
    ASSERT_EQ(sol.far_distance_m, ref.far.distance_m);
    ASSERT_EQ(sol.far_azimuth_rad, ref.far.azimuth_rad);
    ASSERT_EQ(sol.far_elevation_rad, ref.far.elevation_rad);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(sol.far_direction_c[k], ref.far.direction_c[k]);
    if (ref.pose_valid) {
      for (int k = 0; k < 3; ++k) ASSERT_EQ(sol.position_m[k], ref.pose.t_c_m[k]);
      Eigen::Quaterniond q = ref.pose.quaternion();
      if (q.w() < 0.0) q.coeffs() *= -1.0;
      ASSERT_EQ(sol.quaternion[0], q.w());
      ASSERT_EQ(sol.quaternion[1], q.x());
      ASSERT_EQ(sol.quaternion[2], q.y());
      ASSERT_EQ(sol.quaternion[3], q.z());
      ASSERT_EQ(sol.ypr_rad[1], ref.pose.ypr().pitch_rad);
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) ASSERT_EQ(sol.covariance[r * 6 + c], ref.covariance(r, c));
    }
    if (sol.mode == VISNAV_MODE_NEAR_RANGE) {
      ASSERT_EQ(sol.rms_px, reference->lastNearRange().rms_px);
      ASSERT_EQ(sol.edge_points, reference->lastNearRange().edge_points);
    }
  }
  // The comparison covered every estimator (numbers of README.md "750 m to 5 m without help").
  EXPECT_GT(per_mode[VISNAV_MODE_FAR_RANGE], 100);
  EXPECT_GT(acquisition_frames, 0);
  EXPECT_GT(per_mode[VISNAV_MODE_NEAR_RANGE], 50);
  visnav_destroy(h);
}

}  // namespace
