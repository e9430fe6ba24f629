#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "io_test_util.hpp"
#include "visnav/io/camera_io.hpp"
#include "visnav/io/model_io.hpp"

namespace visnav::io {
namespace {

using test::expectError;
using test::makeTempDir;
using test::sourcePath;
using test::writeFile;

void expectSameModel(const PolygonModel& a, const PolygonModel& b) {
  ASSERT_EQ(a.vertices().size(), b.vertices().size());
  for (std::size_t i = 0; i < a.vertices().size(); ++i) EXPECT_EQ(a.vertices()[i], b.vertices()[i]) << i;
  ASSERT_EQ(a.surfaces().size(), b.surfaces().size());
  for (std::size_t s = 0; s < a.surfaces().size(); ++s) {
    EXPECT_EQ(a.surfaces()[s].name, b.surfaces()[s].name);
    EXPECT_EQ(a.surfaces()[s].vertex_indices, b.surfaces()[s].vertex_indices);
    EXPECT_EQ(a.surfaces()[s].albedo, b.surfaces()[s].albedo);
    EXPECT_LE((a.surfaces()[s].normal_m - b.surfaces()[s].normal_m).norm(), 1e-15);
  }
  EXPECT_EQ(a.edges().size(), b.edges().size());
}

bool allNormalsOutward(const PolygonModel& m) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : m.vertices()) c += v;
  c /= static_cast<double>(m.vertices().size());
  for (const ModelSurface& s : m.surfaces())
    if (s.normal_m.dot(s.centroid_m - c) <= 0.0) return false;
  return true;
}

const char* kGoodToml = R"(# a triangle and a square sharing nothing
[model]
name = "two"
units = "m"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 2.5], [1, 0, 2.5], [1, 1, 2.5], [0, 1, 2.5]]

[[surface]]
vertices = [0, 1, 2]

[[surface]]
name = "top"
vertices = [3, 4, 5, 6]
normal = [0, 0, 2]
albedo = 0.25
)";

TEST(ModelToml, LoadsGoodFileWithDefaults) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  const LoadError e = loadModelToml(writeFile(dir, "good.toml", kGoodToml), m);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(m.vertices().size(), 7U);
  ASSERT_EQ(m.surfaces().size(), 2U);
  EXPECT_EQ(m.surfaces()[0].name, "");
  EXPECT_EQ(m.surfaces()[0].albedo, 0.8);
  EXPECT_LE((m.surfaces()[0].normal_m - Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_EQ(m.surfaces()[1].name, "top");
  EXPECT_EQ(m.surfaces()[1].albedo, 0.25);
  EXPECT_EQ(m.surfaces()[1].normal_m, Vec3::UnitZ());
  EXPECT_EQ(m.vertices()[5], Vec3(1, 1, 2.5));
}

TEST(ModelToml, ShippedPlateMatchesMakeRectanglePlate) {
  PolygonModel m;
  const LoadError e = loadModel(sourcePath("config/models/plate_2300x1800.toml"), m);
  ASSERT_TRUE(e.ok) << e.message;
  expectSameModel(m, makeRectanglePlate(2.3, 1.8));
  EXPECT_EQ(m.surfaces()[0].normal_m, Vec3::UnitZ());
}

TEST(ModelToml, ShippedBoxMatchesMakeBox) {
  PolygonModel m;
  const LoadError e = loadModel(sourcePath("config/models/box_1600x1200x1000.toml"), m);
  ASSERT_TRUE(e.ok) << e.message;
  expectSameModel(m, makeBox(0.8, 0.6, 0.5));
  EXPECT_EQ(m.edges().size(), 12U);
  EXPECT_TRUE(allNormalsOutward(m));
}

TEST(ModelToml, RoundTripIsExact) {
  const std::string dir = makeTempDir();
  // Values without a short decimal form check the 17-digit printing.
  std::vector<Vec3> v = {{0.1, 1.0 / 3.0, -2e-7}, {1.1, 1.0 / 3.0, -2e-7}, {1.1, 1.0 / 3.0 + 0.7, -2e-7}};
  ModelSurface s;
  s.name = "odd \"name\" \\ with\ttab";
  s.vertex_indices = {0, 1, 2};
  s.albedo = 0.123456789012345678;
  PolygonModel odd;
  ASSERT_TRUE(PolygonModel::build(v, {s}, odd).ok);

  for (const PolygonModel& original : {odd, makeBox(0.8, 0.6, 0.5, 0.3), makeRectanglePlate(2.3, 1.8)}) {
    const std::string path = dir + "rt.toml";
    const LoadError w = writeModelToml(path, original);
    ASSERT_TRUE(w.ok) << w.message;
    PolygonModel loaded;
    const LoadError r = loadModelToml(path, loaded);
    ASSERT_TRUE(r.ok) << r.message;
    expectSameModel(original, loaded);
  }
}

TEST(ModelToml, WriteToBadPathFails) {
  const std::string path = makeTempDir() + "no_such_dir/m.toml";
  const LoadError e = writeModelToml(path, makeRectanglePlate(1, 1));
  EXPECT_FALSE(e.ok);
  expectError(e.message, path, 0, "cannot open");
  EXPECT_FALSE(writeModelToml(makeTempDir() + "empty.toml", PolygonModel()).ok);
}

struct BadCase {
  const char* name;
  int line;  // 0: the problem has no line (e.g. a missing top-level table)
  const char* word;
};

const char* kHead = "[model]\nunits = \"m\"\nvertices = [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]\n";

std::string withHead(const char* tail) { return std::string(kHead) + tail; }

TEST(ModelToml, BadFilesNameFileLineAndProblem) {
  const std::vector<std::pair<std::string, BadCase>> cases = {
      {"[model]\nunits = \"m\"\nvertices = [[0,0,0]] junk\n", {"syntax", 3, "3:"}},
      {"[surface]\nvertices = [0]\n", {"no_model", 0, "missing key 'model'"}},
      {"[model]\nvertices = [[0,0,0]]\n[[surface]]\nvertices = [0,0,0]\n",
       {"no_units", 1, "missing key 'units'"}},
      {"[model]\nunits = \"mm\"\nvertices = [[0,0,0]]\n", {"units", 2, "not supported"}},
      {"[model]\nunits = \"m\"\nvertices = \"square\"\n", {"vertices_type", 3, "wrong type"}},
      {"[model]\nunits = \"m\"\nvertices = [\n[0,0,0],\n[0,nan,0]]\n", {"nan", 5, "not finite"}},
      {"[model]\nunits = \"m\"\nvertices = [\n[0,0,0],\n[0,0]]\n", {"vec2", 5, "expected an array of 3"}},
      {"[model]\nunits = \"m\"\nvertices = [[0,0,\"z\"]]\n", {"vertex_string", 3, "wrong type"}},
      {withHead("[[surface]]\nvertices = [0, 1,\n 7]\n"), {"index", 6, "out of range"}},
      {withHead("[[surface]]\nvertices = [0, 1.5, 2]\n"), {"index_float", 5, "wrong type"}},
      {withHead("[[surface]]\nvertices = [0, 1, 2]\nalbedo = 1.5\n"), {"albedo", 6, "out of range"}},
      {withHead("[[surface]]\nvertices = [0, 1, 2]\nalbeod = 0.5\n"), {"typo", 6, "unknown key"}},
      {withHead("[[surface]]\nname = \"s\"\n"), {"no_indices", 4, "missing key 'vertices'"}},
      {withHead("[[surface]]\nvertices = [0, 1, 2]\nnormal = [0, 0, 0]\n"),
       {"zero_normal", 6, "normal is zero"}},
      {std::string("surface = 3\n") + kHead, {"surface_type", 1, "array of tables"}},
      {kHead, {"no_surface", 0, "missing [[surface]]"}},
      // Geometry errors come from PolygonModel::build, prefixed with the path and the surface's line.
      {withHead("[[surface]]\nvertices = [0, 1, 2, 3]\nnormal = [0, 0, -1]\n"), {"normal", 4, "disagrees"}},
      {withHead("[[surface]]\nvertices = [0, 1, 2, 0]\n"), {"repeat", 4, "repeats vertex"}},
  };
  const std::string dir = makeTempDir();
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  for (const auto& [text, c] : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = writeFile(dir, std::string(c.name) + ".toml", text);
    PolygonModel m = plate;
    const LoadError e = loadModelToml(path, m);
    EXPECT_FALSE(e.ok);
    expectError(e.message, path, c.line, c.word);
    expectSameModel(m, plate);  // untouched
  }
}

TEST(ModelToml, MissingFileAndUnknownExtension) {
  PolygonModel m;
  const std::string dir = makeTempDir();
  LoadError e = loadModelToml(dir + "absent.toml", m);
  EXPECT_FALSE(e.ok);
  expectError(e.message, dir + "absent.toml", 0, "cannot open");
  e = loadModel(writeFile(dir, "m.obj", "v 0 0 0\n"), m);
  EXPECT_FALSE(e.ok);
  expectError(e.message, dir + "m.obj", 0, "extension");
}

// ---------------------------------------------------------------------------------------------- .cao

TEST(ModelCao, ShippedPlateMatchesToml) {
  PolygonModel cao;
  PolygonModel toml;
  const LoadError e = loadModel(sourcePath("config/models/plate_2300x1800.cao"), cao);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_TRUE(loadModel(sourcePath("config/models/plate_2300x1800.toml"), toml).ok);
  expectSameModel(cao, toml);
}

// A unit cube written the way ViSP files come: comments everywhere, line-faces listed in any order and
// direction, point-faces with mixed orientation. The loader must orient every face outwards.
const char* kCaoCube = R"(V1  # version
# 3D Points
8 # count
0 0 0
1 0 0   # point 1
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
# 3D Lines
8
0 1
2 1 name=reversed_edge
2 3
0 3
4 5
5 6
6 7
7 4
# Faces from 3D lines
2
4 0 2 1 3 name=bottom   # scrambled order and directions
4 4 5 6 7 name="top face"
# Faces from 3D points
4
4 0 1 5 4 name=front   # outward
4 1 5 6 2 name=right   # inward in the file: must be reversed
4 2 6 7 3
4 0 4 7 3 name=left    # outward
# 3D cylinders
0
# 3D circles
0
)";

TEST(ModelCao, ConvertsLineFacesAndOrientsOutwards) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  const LoadError e = loadModelCao(writeFile(dir, "cube.cao", kCaoCube), m);
  ASSERT_TRUE(e.ok) << e.message;
  ASSERT_EQ(m.vertices().size(), 8U);
  ASSERT_EQ(m.surfaces().size(), 6U);
  EXPECT_EQ(m.edges().size(), 12U);
  EXPECT_TRUE(allNormalsOutward(m));
  EXPECT_EQ(m.surfaces()[0].name, "bottom");
  EXPECT_EQ(m.surfaces()[1].name, "top face");
  EXPECT_EQ(m.surfaces()[4].name, "");
  EXPECT_LE((m.surfaces()[0].normal_m + Vec3::UnitZ()).norm(), 1e-12);
  EXPECT_LE((m.surfaces()[3].normal_m - Vec3::UnitX()).norm(), 1e-12);
}

TEST(ModelCao, CylinderAndCircleSectionsAreOptional) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  const LoadError e =
      loadModelCao(writeFile(dir, "tri.cao", "V1\n3\n0 0 0\n1 0 0\n0 1 0\n0\n0\n1\n3 0 1 2\n"), m);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(m.surfaces()[0].normal_m, Vec3::UnitZ());
}

TEST(ModelCao, BadFilesNameFileLineAndProblem) {
  const std::string pts = "V1\n3\n0 0 0\n1 0 0\n0 1 0\n";  // points end on line 5
  const std::vector<std::pair<std::string, BadCase>> cases = {
      {"V2\n3\n0 0 0\n1 0 0\n0 1 0\n0\n0\n0\n", {"version", 1, "unsupported header"}},
      {"V1\nload(\"other.cao\")\n", {"load", 2, "not supported"}},
      {"V1\n3\n0 0 0\n1 zero 0\n", {"number", 4, "expected a number"}},
      {"V1\n3\n0 0 0\n1 inf 0\n", {"inf", 4, "not finite"}},
      {"V1\n3\n0 0 0\n1 0 0 7\n", {"extra", 4, "unexpected extra value"}},
      {pts + "1\n0 3\n", {"line_index", 7, "out of range"}},
      {pts + "1\n1 1\n", {"line_self", 7, "to itself"}},
      {pts + "2\n0 1\n1 2\n1\n3 0 1 4\n", {"face_line_index", 10, "out of range"}},
      {pts + "3\n0 1\n1 2\n1 2\n1\n3 0 1 2\n", {"open_loop", 11, "closed loop"}},
      {pts + "0\n0\n1\n3 0 1 5 # bad\n", {"face_point_index", 9, "out of range"}},
      {pts + "0\n0\n1\n2 0 1\n", {"face_count", 9, "out of range"}},
      {pts + "0\n0\n1\n3 0 1 2\n1\n0 0 0 0 1 0 0.1\n", {"cylinder", 10, "cylinders are not polygons"}},
      {pts + "0\n0\n1\n3 0 1 2\n0\n2\n", {"circle", 11, "circles are not polygons"}},
      {pts + "0\n0\n1\n3 0 1\n", {"truncated", 9, "unexpected end of file"}},
      {pts + "0\n0\n0\n", {"no_faces", 0, "no faces"}},
      {pts + "0\n0\n1\n3 0 1 2\n0\n0\n7\n", {"trailing", 12, "unexpected '7'"}},
      {"V1\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n0\n0\n1\n4 0 1 2 3\n", {"planar", 10, "not planar"}},
  };
  const std::string dir = makeTempDir();
  const PolygonModel plate = makeRectanglePlate(2.3, 1.8);
  for (const auto& [text, c] : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = writeFile(dir, std::string(c.name) + ".cao", text);
    PolygonModel m = plate;
    const LoadError e = loadModel(path, m);
    EXPECT_FALSE(e.ok);
    expectError(e.message, path, c.line, c.word);
    expectSameModel(m, plate);
  }
}

// Issue 13 item 10: the loader's work and memory are bounded. One face listing the same line a million
// times took over 60 s (quadratic chaining); now the count is bounded and chaining is linear.
TEST(ModelCao, RepeatedLineInAFaceIsRejectedFast) {
  const std::string dir = makeTempDir();
  std::string text = "V1\n3\n0 0 0\n1 0 0\n0 1 0\n3\n0 1\n1 2\n2 0\n1\n1000000";
  for (int k = 0; k < 1000000; ++k) text += " 0";
  text += "\n0\n";
  const std::string path = writeFile(dir, "repeat.cao", text);
  PolygonModel m;
  const auto t0 = std::chrono::steady_clock::now();
  const LoadError e = loadModel(path, m);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_FALSE(e.ok);
  expectError(e.message, path, 11, "out of range [3, 1000]");
  EXPECT_LT(seconds, 2.0);
  // Within the bound, a face that repeats a line fails at once in the linear walk.
  const std::string within =
      writeFile(dir, "repeat_within.cao", "V1\n3\n0 0 0\n1 0 0\n0 1 0\n3\n0 1\n1 2\n2 0\n1\n4 0 1 2 0\n0\n");
  EXPECT_NE(loadModel(within, m).message.find("more than twice"), std::string::npos);
}

TEST(ModelCao, LongFaceChainsInLinearTime) {
  // A 1000-gon (the per-face bound) listed as lines in scrambled order: the walk must find them all.
  constexpr int kN = 1000;
  std::string text = "V1\n" + std::to_string(kN) + "\n";
  for (int k = 0; k < kN; ++k) {
    const double a = 2.0 * kPi * k / kN;
    text += std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
  }
  text += std::to_string(kN) + "\n";
  for (int k = 0; k < kN; ++k) text += std::to_string(k) + " " + std::to_string((k + 1) % kN) + "\n";
  text += "1\n" + std::to_string(kN);
  for (int k = 0; k < kN; ++k) text += " " + std::to_string((k * 7) % kN);  // 7 is coprime with 1000
  text += "\n0\n";
  PolygonModel m;
  const LoadError e = loadModel(writeFile(makeTempDir(), "ngon.cao", text), m);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(m.surfaces()[0].vertex_indices.size(), static_cast<std::size_t>(kN));
}

TEST(ModelCao, CountsAreBounded) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  const std::string pts = "V1\n3\n0 0 0\n1 0 0\n0 1 0\n";
  LoadError e = loadModel(writeFile(dir, "points.cao", "V1\n100000000\n"), m);
  expectError(e.message, dir + "points.cao", 2, "out of range [3, 100000]");
  e = loadModel(writeFile(dir, "lines.cao", pts + "99999999\n"), m);
  expectError(e.message, dir + "lines.cao", 6, "out of range [0, 200000]");
  e = loadModel(writeFile(dir, "faces.cao", pts + "0\n99999999\n"), m);
  expectError(e.message, dir + "faces.cao", 7, "out of range [0, 100000]");
}

TEST(ModelIo, NonRegularFilesAreRejectedWithoutHanging) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  ASSERT_EQ(::symlink("/dev/zero", (dir + "zero.cao").c_str()), 0);
  LoadError e = loadModel(dir + "zero.cao", m);  // was std::bad_alloc (abort)
  expectError(e.message, dir + "zero.cao", 0, "not a regular file");
  ASSERT_EQ(::mkfifo((dir + "fifo.toml").c_str(), 0600), 0);
  e = loadModel(dir + "fifo.toml", m);  // was a hang
  expectError(e.message, dir + "fifo.toml", 0, "not a regular file (a FIFO)");
  e = loadModel(dir + "absent.cao", m);
  expectError(e.message, dir + "absent.cao", 0, "cannot open: No such file or directory");
}

TEST(ModelToml, NonAsciiKeyIsRejectedBeforeToml) {
  PolygonModel m;
  const std::string path = writeFile(makeTempDir(), "key.toml", "\xc3\xa9 = 1\n");
  const LoadError e = loadModel(path, m);
  expectError(e.message, path, 1, "non-ASCII character");
}

TEST(ModelToml, HugeCoordinatesAndStarFacesAreRejected) {
  const std::string dir = makeTempDir();
  PolygonModel m;
  const std::string huge =
      writeFile(dir, "huge.toml",
                "[model]\nunits = \"m\"\nvertices = [[0, 0, 0], [1e300, 0, 0], [0, 1e300, 0]]\n"
                "[[surface]]\nvertices = [0, 1, 2]\n");
  LoadError e = loadModel(huge, m);
  expectError(e.message, huge, 0, "coordinate beyond");
  std::string star = "[model]\nunits = \"m\"\nvertices = [";
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * kPi * k / 5.0;
    star += (k == 0 ? "" : ", ") + std::string("[") + std::to_string(std::cos(a)) + ", " +
            std::to_string(std::sin(a)) + ", 0]";
  }
  star += "]\n[[surface]]\nvertices = [0, 2, 4, 1, 3]\n";
  const std::string star_path = writeFile(dir, "star.toml", star);
  e = loadModel(star_path, m);
  expectError(e.message, star_path, 4, "not a simple polygon");
}

// The physical-range checks (issue 13 item 11) must not reject anything the project ships.
TEST(ShippedFiles, EveryShippedCameraAndModelLoads) {
  for (const char* camera : {"config/cameras/vga_6mm.toml", "config/cameras/vga_6mm_distorted.toml",
                             "config/cameras/example_opencv.yaml"}) {
    CameraIntrinsics k;
    const LoadError e = loadCamera(sourcePath(camera), k);
    EXPECT_TRUE(e.ok) << e.message;
  }
  for (const char* model : {"config/models/box_1600x1200x1000.toml", "config/models/plate_2300x1800.cao",
                            "config/models/plate_2300x1800.toml", "config/models/smallsat_panels.toml"}) {
    PolygonModel m;
    const LoadError e = loadModel(sourcePath(model), m);
    EXPECT_TRUE(e.ok) << e.message;
  }
}

}  // namespace
}  // namespace visnav::io
