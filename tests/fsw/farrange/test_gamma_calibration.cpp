// Gamma of eq. 16 from frames at known distance: the paper's example (25 m at 1/30 scale = 750 m, a 16 px
// cluster) must give 3000, from the numbers and from a frame through the estimator and the tool's code.
#include <gtest/gtest.h>

#include <filesystem>

#include "visnav/far_eval/far_evaluation.hpp"
#include "visnav/farrange/gamma_calibration.hpp"

namespace visnav::far {
namespace {

TEST(GammaCalibration, PaperExampleIs3000) {
  EXPECT_DOUBLE_EQ(gammaOf({25.0 * 30.0, 16.0}), 3000.0);
  const GammaEstimate e = calibrateGamma({{750.0, 16.0}});
  ASSERT_TRUE(e.ok);
  EXPECT_DOUBLE_EQ(e.gamma, 3000.0);
  EXPECT_EQ(e.inliers, 1);
}

TEST(GammaCalibration, RobustAverageIgnoresAWrongFrame) {
  // gamma 3000 seen at several distances with +-1 % scatter, plus a frame that caught a glint (n = 4).
  std::vector<GammaSample> s = {{750.0, 16.0}, {600.0, 25.0 * 1.02}, {300.0, 100.0 * 0.98}, {100.0, 900.0}};
  s.push_back({500.0, 4.0});
  const GammaEstimate e = calibrateGamma(s);
  ASSERT_TRUE(e.ok);
  EXPECT_EQ(e.samples, 5);
  EXPECT_EQ(e.inliers, 4);
  EXPECT_NEAR(e.gamma, 3000.0, 10.0);
  EXPECT_FALSE(calibrateGamma({{0.0, 10.0}, {100.0, 0.0}}).ok);
}

TEST(GammaCalibration, FrameAtKnownDistanceThroughTheEstimator) {
  // A 16 px target (2 x 8) on the optical axis "at 750 m": every pixel of it has an edge response, so the
  // published method's cluster is those 16 px. (A 4 x 4 block would lose its 2 x 2 interior: zero gradient,
  // and a rare grey level alone gives S = 0.5 G < t_out; the interior drop in miniature.)
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "visnav_gamma_frame";
  std::filesystem::create_directories(dir);
  std::vector<std::uint8_t> px(640U * 480U, 20);
  for (int y = 239; y < 241; ++y)
    for (int x = 316; x < 324; ++x) px[static_cast<std::size_t>(y * 640 + x)] = 200;
  const std::string file = (dir / "frame.pgm").string();
  ASSERT_TRUE(replay::writePgm8(file, ImageView8(px.data(), 640, 480)).ok);
  replay::Sequence seq;
  seq.camera = CameraIntrinsics::fromSi(640, 480, 6e-3, 6e-6, 6e-6, 0.0, 320.0, 240.0);
  seq.frames.push_back({0, 0, file});
  replay::TruthRow row;
  row.pose.t_c_m = Vec3(0.0, 0.0, 750.0);
  seq.truth.push_back(row);
  FarRangeParams params;
  params.method = static_cast<int>(FarRangeMethod::kPaper);
  std::vector<far_eval::FrameRecord> records;
  ASSERT_TRUE(far_eval::runSequence(seq, params, true, records).ok);
  ASSERT_EQ(records.size(), 1U);
  EXPECT_EQ(records[0].cluster_pixels, 16);
  EXPECT_TRUE(records[0].right_target);
  const GammaEstimate e = far_eval::calibrateFromRecords(records, 0.0, 1e9);
  ASSERT_TRUE(e.ok);
  EXPECT_DOUBLE_EQ(e.gamma, 3000.0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace visnav::far
