#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "io_test_util.hpp"
#include "visnav/io/camera_io.hpp"

namespace visnav::io {
namespace {

using test::expectError;
using test::makeTempDir;
using test::sourcePath;
using test::writeFile;

void expectSameCamera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  EXPECT_EQ(a.width_px, b.width_px);
  EXPECT_EQ(a.height_px, b.height_px);
  EXPECT_EQ(a.fx_px, b.fx_px);
  EXPECT_EQ(a.fy_px, b.fy_px);
  EXPECT_EQ(a.skew, b.skew);
  EXPECT_EQ(a.cx_px, b.cx_px);
  EXPECT_EQ(a.cy_px, b.cy_px);
  EXPECT_EQ(a.distortion.k1, b.distortion.k1);
  EXPECT_EQ(a.distortion.k2, b.distortion.k2);
  EXPECT_EQ(a.distortion.k3, b.distortion.k3);
  EXPECT_EQ(a.distortion.p1, b.distortion.p1);
  EXPECT_EQ(a.distortion.p2, b.distortion.p2);
}

CameraIntrinsics sentinel() {
  CameraIntrinsics k;
  k.width_px = 11;
  k.height_px = 7;
  k.fx_px = 3.0;
  k.fy_px = 4.0;
  k.skew = 0.0625;
  k.cx_px = 1.25;
  k.cy_px = 2.5;
  k.distortion.k1 = 0.015625;
  return k;
}

struct BadCameraCase {
  const char* name;
  int line;  // 0: the problem has no line
  const char* word;
};

// ------------------------------------------------------------------------------------------------ TOML

TEST(CameraToml, ShippedVga6mm) {
  CameraIntrinsics k;
  const LoadError e = loadCamera(sourcePath("config/cameras/vga_6mm.toml"), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(k.width_px, 640);
  EXPECT_EQ(k.height_px, 480);
  EXPECT_NEAR(k.fx_px, 1000.0, 1e-9);
  EXPECT_NEAR(k.fy_px, 1000.0, 1e-9);
  EXPECT_EQ(k.skew, 0.0);
  EXPECT_EQ(k.cx_px, 320.0);
  EXPECT_EQ(k.cy_px, 240.0);
  EXPECT_TRUE(k.distortion.isZero());
}

TEST(CameraToml, ShippedVga6mmDistorted) {
  CameraIntrinsics k;
  const LoadError e = loadCamera(sourcePath("config/cameras/vga_6mm_distorted.toml"), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_NEAR(k.fx_px, 1000.0, 1e-9);
  EXPECT_EQ(k.distortion.k1, -0.05);
  EXPECT_EQ(k.distortion.k2, 0.01);
  EXPECT_EQ(k.distortion.k3, 0.0);
  EXPECT_EQ(k.distortion.p1, 0.0);
  EXPECT_EQ(k.distortion.p2, 0.0);
}

TEST(CameraToml, PixelFormWithDefaults) {
  const std::string dir = makeTempDir();
  CameraIntrinsics k;
  const std::string text =
      "[camera]\nwidth_px = 1024\nheight_px = 768\nfx_px = 1500\nfy_px = 1510.5\n"
      "[camera.distortion]\np2 = -1e-4\n";
  const LoadError e = loadCameraToml(writeFile(dir, "px.toml", text), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(k.fx_px, 1500.0);
  EXPECT_EQ(k.fy_px, 1510.5);
  EXPECT_EQ(k.skew, 0.0);
  EXPECT_EQ(k.cx_px, 512.0);  // image centre
  EXPECT_EQ(k.cy_px, 384.0);
  EXPECT_EQ(k.distortion.p2, -1e-4);
  EXPECT_EQ(k.distortion.k1, 0.0);
}

TEST(CameraToml, SiFormWithRectangularPixels) {
  const std::string dir = makeTempDir();
  CameraIntrinsics k;
  const std::string text =
      "[camera]\nwidth_px = 640\nheight_px = 480\nfocal_length_m = 8e-3\npixel_pitch_x_m = 4e-6\n"
      "pixel_pitch_y_m = 5e-6\nskew = 0.001\ncx_px = 300.5\ncy_px = 250.5\n";
  const LoadError e = loadCameraToml(writeFile(dir, "si.toml", text), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_NEAR(k.fx_px, 2000.0, 1e-9);
  EXPECT_NEAR(k.fy_px, 1600.0, 1e-9);
  EXPECT_EQ(k.skew, 0.001);
  EXPECT_EQ(k.cx_px, 300.5);
  EXPECT_EQ(k.cy_px, 250.5);
}

TEST(CameraToml, RoundTripIsExact) {
  CameraIntrinsics k;
  k.width_px = 1280;
  k.height_px = 1024;
  k.fx_px = 1234.5678901234567;
  k.fy_px = 1000.0 + 1.0 / 3.0;
  k.skew = 1e-3 / 3.0;
  k.cx_px = 0.1;
  k.cy_px = 511.99999999999994;
  k.distortion = {-0.1 / 3.0, 2e-17, 1e-3 / 7.0, -3e-8, 7e-4};  // awkward digits, a possible lens
  const std::string path = makeTempDir() + "rt.toml";
  for (const CameraIntrinsics& original : {k, sentinel()}) {
    const LoadError w = writeCameraToml(path, original);
    ASSERT_TRUE(w.ok) << w.message;
    CameraIntrinsics loaded;
    const LoadError r = loadCamera(path, loaded);
    ASSERT_TRUE(r.ok) << r.message;
    expectSameCamera(original, loaded);
  }
}

TEST(CameraToml, WriterRejectsInvalidIntrinsics) {
  const std::string path = makeTempDir() + "bad.toml";
  CameraIntrinsics k = sentinel();
  k.fx_px = -1.0;
  const LoadError e = writeCameraToml(path, k);
  EXPECT_FALSE(e.ok);
  expectError(e.message, path, 0, "fx_px");
}

TEST(CameraToml, BadFilesNameFileLineAndProblem) {
  const std::string head = "[camera]\nwidth_px = 640\nheight_px = 480\n";  // lines 1..3
  const std::vector<std::pair<std::string, BadCameraCase>> cases = {
      {"[camera]\nwidth_px = = 640\n", {"syntax", 2, "2:"}},
      {"[cam]\nwidth_px = 640\n", {"table", 1, "unknown key 'cam'"}},
      {"width_px = 640\n", {"no_table", 1, "unknown key"}},
      {"", {"empty", 0, "missing key 'camera'"}},
      {"[camera]\nheight_px = 480\nfx_px = 1\nfy_px = 1\n", {"no_width", 1, "missing key 'width_px'"}},
      {"[camera]\nwidth_px = 0\n", {"width_zero", 2, "out of range"}},
      {"[camera]\nwidth_px = 640.0\n", {"width_float", 2, "wrong type"}},
      {head + "fx_px = 1000\nfy_px = 1000\nfocal_length_m = 6e-3\npixel_pitch_m = 6e-6\n",
       {"both_forms", 1, "not both"}},
      {head + "skew = 0\n", {"no_focal", 1, "missing key"}},
      {head + "fx_px = 1000\n", {"no_fy", 1, "missing key 'fy_px'"}},
      {head + "fx_px = -1000\nfy_px = 1000\n", {"fx_negative", 4, "out of range"}},
      {head + "fx_px = \"1000\"\nfy_px = 1000\n", {"fx_string", 4, "wrong type"}},
      {head + "fx_px = inf\nfy_px = 1000\n", {"fx_inf", 4, "not finite"}},
      {head + "focal_length_m = 6e-3\npixel_pitch_x_m = 6e-6\n",
       {"no_pitch_y", 1, "missing key 'pixel_pitch_y_m'"}},
      {head + "focal_length_m = 6e-3\npixel_pitch_m = 6e-6\npixel_pitch_y_m = 6e-6\n",
       {"pitch_twice", 1, "not both"}},
      {head + "focal_length_m = 6e-3\npixel_pitch_m = 0\n", {"pitch_zero", 5, "out of range"}},
      {head + "focal_length_m = 1e300\npixel_pitch_m = 1e-300\n", {"fx_overflow", 1, "not finite"}},
      {head + "fx_px = 1000\nfy_px = 1000\ncx_px = nan\n", {"cx_nan", 6, "not finite"}},
      {head + "fx_px = 1000\nfy_px = 1000\nfocal = 3\n", {"typo", 6, "unknown key 'focal'"}},
      {head + "fx_px = 1000\nfy_px = 1000\n[camera.distortion]\nk1 = -inf\n", {"k1_inf", 7, "not finite"}},
      {head + "fx_px = 1000\nfy_px = 1000\n[camera.distortion]\nk4 = 0.1\n", {"k4", 7, "unknown key 'k4'"}},
      {head + "fx_px = 1000\nfy_px = 1000\ndistortion = 0\n", {"dist_type", 6, "wrong type"}},
  };
  const std::string dir = makeTempDir();
  for (const auto& [text, c] : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = writeFile(dir, std::string(c.name) + ".toml", text);
    CameraIntrinsics k = sentinel();
    const LoadError e = loadCamera(path, k);
    EXPECT_FALSE(e.ok);
    expectError(e.message, path, c.line, c.word);
    expectSameCamera(k, sentinel());  // untouched
  }
}

TEST(CameraIo, MissingFileAndUnknownExtension) {
  const std::string dir = makeTempDir();
  CameraIntrinsics k = sentinel();
  LoadError e = loadCamera(dir + "absent.yaml", k);
  EXPECT_FALSE(e.ok);
  expectError(e.message, dir + "absent.yaml", 0, "cannot open");
  e = loadCamera(writeFile(dir, "cam.json", "{}"), k);
  EXPECT_FALSE(e.ok);
  expectError(e.message, dir + "cam.json", 0, "extension");
  expectSameCamera(k, sentinel());
}

// ----------------------------------------------------------------------------------------- OpenCV YAML

TEST(CameraOpenCvYaml, ShippedExample) {
  CameraIntrinsics k;
  const LoadError e = loadCamera(sourcePath("config/cameras/example_opencv.yaml"), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(k.width_px, 640);
  EXPECT_EQ(k.height_px, 480);
  EXPECT_EQ(k.fx_px, 1.0012345678901234e+03);
  EXPECT_EQ(k.fy_px, 9.9987654321098765e+02);
  EXPECT_EQ(k.skew, 0.0);
  EXPECT_EQ(k.cx_px, 320.0);  // 319.5 + 0.5: OpenCV pixel centres are integers, ours at +0.5
  EXPECT_EQ(k.cy_px, 240.0);
  EXPECT_EQ(k.distortion.k1, -5.0000000000000003e-02);
  EXPECT_EQ(k.distortion.k2, 0.01);
  EXPECT_EQ(k.distortion.k3, 0.0);
}

std::string yaml(const std::string& k_data, const std::string& d_dims, const std::string& d_data,
                 const std::string& dt = "d") {
  return "%YAML:1.0\n---\nimage_width: 800\nimage_height: 600\n"              // lines 1..4
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: " +  // lines 5..8
         dt +
         "\n   data: [ " + k_data + " ]\n" +                      // line 9
         "distortion_coefficients: !!opencv-matrix\n" + d_dims +  // line 10, 11..12
         "   dt: d\n   data: [ " + d_data + " ]\n";               // lines 13, 14
}

const std::string kK = "900., 1.8, 399.5, 0., 905., 299.5, 0., 0., 1.";
const std::string k1x5 = "   rows: 1\n   cols: 5\n";

TEST(CameraOpenCvYaml, OrderSkewAndShift) {
  const std::string dir = makeTempDir();
  CameraIntrinsics k;
  const LoadError e =
      loadCameraOpenCvYaml(writeFile(dir, "c.yml", yaml(kK, k1x5, "0.01, 0.02, 0.003, 0.004, 0.05")), k);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(k.width_px, 800);
  EXPECT_EQ(k.fx_px, 900.0);
  EXPECT_EQ(k.fy_px, 905.0);
  EXPECT_EQ(k.skew, 1.8 / 900.0);
  EXPECT_EQ(k.cx_px, 400.0);
  EXPECT_EQ(k.cy_px, 300.0);
  // OpenCV order k1, k2, p1, p2, k3.
  EXPECT_EQ(k.distortion.k1, 0.01);
  EXPECT_EQ(k.distortion.k2, 0.02);
  EXPECT_EQ(k.distortion.p1, 0.003);
  EXPECT_EQ(k.distortion.p2, 0.004);
  EXPECT_EQ(k.distortion.k3, 0.05);
}

TEST(CameraOpenCvYaml, AcceptsAllCoefficientCounts) {
  const std::string dir = makeTempDir();
  const std::vector<std::pair<std::string, std::string>> shapes = {
      {"   rows: 1\n   cols: 4\n", "0.01, 0.02, 0.003, 0.004"},
      {"   rows: 5\n   cols: 1\n", "0.01, 0.02, 0.003, 0.004, 0.05"},
      {"   rows: 1\n   cols: 8\n", "0.01, 0.02, 0.003, 0.004, 0.05, 0., 0., 0."},
      {"   rows: 12\n   cols: 1\n", "0.01, 0.02, 0.003, 0.004, 0.05,\n 0., 0., 0., 0.,\n 0., 0., 0."},
      {"   rows: 1\n   cols: 14\n", "0.01, 0.02, 0.003, 0.004, 0.05, 0, 0, 0, 0, 0, 0, 0, 0, 0"},
  };
  for (const auto& [dims, data] : shapes) {
    SCOPED_TRACE(dims);
    CameraIntrinsics k;
    const LoadError e = loadCamera(writeFile(dir, "c.yaml", yaml(kK, dims, data, "f")), k);
    ASSERT_TRUE(e.ok) << e.message;
    EXPECT_EQ(k.distortion.p2, 0.004);
    EXPECT_EQ(k.distortion.k3, dims.find("cols: 4") != std::string::npos ? 0.0 : 0.05);
  }
}

TEST(CameraOpenCvYaml, BadFilesNameFileLineAndProblem) {
  const std::vector<std::pair<std::string, BadCameraCase>> cases = {
      {"image_width: 800\n", {"header", 1, "missing header"}},
      {"%YAML:1.0\nimage_height: 600\n", {"no_width", 0, "missing key 'image_width'"}},
      {"%YAML:1.0\nimage_width: 0\n", {"width_zero", 2, "out of range"}},
      {"%YAML:1.0\nimage_width: wide\n", {"width_text", 2, "wrong type"}},
      {"%YAML:1.0\nimage_width: 8\nimage_width: 8\n", {"duplicate", 3, "duplicate key"}},
      {"%YAML:1.0\n  rows: 3\n", {"indent", 2, "unexpected indented line"}},
      {"%YAML:1.0\nnot a mapping\n", {"mapping", 2, "expected 'key: value'"}},
      {"%YAML:1.0\nimage_width: 8\nimage_height: 6\ncamera_matrix: [1, 2]\n", {"k_type", 4, "wrong type"}},
      {yaml(kK, k1x5, "0.1, 0.2, 0.3, 0.4"), {"count", 14, "4 values"}},
      {yaml(kK, "   rows: 1\n   cols: 3\n", "0.1, 0.2, 0.3"), {"d_shape", 10, "must be 1xN"}},
      {yaml(kK, "   rows: 1\n   cols: 8\n", "0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0., 0."),
       {"rational", 14, "rational/thin-prism model not supported"}},
      {yaml(kK, k1x5, "0.1, 0.2, zero, 0.4, 0.5"), {"nan_text", 14, "is not a number"}},
      {yaml(kK, k1x5, "0.1, 0.2, .nan, 0.4, 0.5"), {"nan", 14, "is not a number"}},
      {yaml(kK, k1x5, "0.1, 0.2, nan, 0.4, 0.5"), {"nan_c", 14, "not finite"}},
      {yaml("900., 0., 399.5, 0., 905., 299.5, 0., 0., 2.", k1x5, "0, 0, 0, 0, 0"),
       {"k22", 9, "out of range"}},
      {yaml("-900., 0., 399.5, 0., 905., 299.5, 0., 0., 1.", k1x5, "0, 0, 0, 0, 0"),
       {"fx", 9, "out of range"}},
      {yaml(kK, k1x5, "0, 0, 0, 0, 0", "u"), {"dt", 8, "not supported"}},
      {yaml("900., 0., 399.5,\n 0., 905., 299.5,\n 0., 0., 1.", k1x5, "0, 0, 0, 0, 0 "),
       {"multi_line_ok", 0, ""}},
      {"%YAML:1.0\nimage_width: 8\nimage_height: 6\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n"
       "   dt: d\n   data: [ 1., 0., 4.,\n  0., 1., 3.,\n",
       {"unclosed", 9, "missing closing ']'"}},
      {"%YAML:1.0\nimage_width: 8\nimage_height: 6\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   dt: d\n",
       {"no_cols", 4, "missing key 'cols'"}},
      {"%YAML:1.0\nimage_width: 8\nimage_height: 6\ncamera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n"
       "   dt: d\n   data: [ 1., 0., 4., 0., 1., 3., 0., 0., 1. ]\n",
       {"no_dist", 0, "missing key 'distortion_coefficients'"}},
  };
  const std::string dir = makeTempDir();
  for (const auto& [text, c] : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = writeFile(dir, std::string(c.name) + ".yaml", text);
    CameraIntrinsics k = sentinel();
    const LoadError e = loadCamera(path, k);
    if (std::string(c.name) == "multi_line_ok") {  // data over several lines is fine
      EXPECT_TRUE(e.ok) << e.message;
      EXPECT_EQ(k.cx_px, 400.0);
      continue;
    }
    EXPECT_FALSE(e.ok);
    expectError(e.message, path, c.line, c.word);
    expectSameCamera(k, sentinel());
  }
}

}  // namespace
}  // namespace visnav::io
