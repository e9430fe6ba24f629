#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "visnav/replay/sequence.hpp"

namespace visnav::replay {
namespace {
namespace fs = std::filesystem;

class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    m_path = fs::temp_directory_path() / ("visnav_test_seq_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(m_path);
    fs::create_directories(m_path);
  }
  ~TempDir() { fs::remove_all(m_path); }
  std::string str(const std::string& rel = "") const { return (m_path / rel).string(); }

 private:
  fs::path m_path;
};

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

void replaceInFile(const std::string& path, const std::string& from, const std::string& to) {
  std::string text = slurp(path);
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  spit(path, text);
}

CameraIntrinsics camera() {
  CameraIntrinsics k;
  k.width_px = 64;
  k.height_px = 48;
  k.fx_px = 100.0;
  k.fy_px = 101.5;
  k.cx_px = 32.25;
  k.cy_px = 24.5;
  k.distortion = {-0.1, 0.02, 0.0, 0.001, -0.0005};
  return k;
}

TEST(Pgm, EightBitRoundTripWithStride) {
  TempDir dir("pgm8");
  const int w = 7;
  const int h = 5;
  const int stride = 9;  // padded rows must not reach the file
  std::vector<std::uint8_t> img(static_cast<std::size_t>(stride * h), 0xEE);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img[static_cast<std::size_t>(y * stride + x)] = static_cast<std::uint8_t>(x * 30 + y);
  ASSERT_TRUE(writePgm8(dir.str("a.pgm"), ImageView8(img.data(), w, h, stride)).ok);
  std::uint8_t buf[64];
  int rw = 0;
  int rh = 0;
  int maxval = 0;
  const LoadError e = readPgm(dir.str("a.pgm"), buf, sizeof buf, rw, rh, maxval);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(rw, w);
  EXPECT_EQ(rh, h);
  EXPECT_EQ(maxval, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_EQ(buf[y * w + x], img[static_cast<std::size_t>(y * stride + x)]);
}

TEST(Pgm, SixteenBitIsBigEndianOnDiskAndRoundTrips) {
  TempDir dir("pgm16");
  const std::vector<std::uint16_t> img = {0x0102, 4095, 0, 1000, 2048, 7};
  ASSERT_TRUE(writePgm16(dir.str("b.pgm"), ImageView16(img.data(), 3, 2), 4095).ok);
  const std::string raw = slurp(dir.str("b.pgm"));
  ASSERT_EQ(raw.substr(0, 13), "P5\n3 2\n4095\n\x01");
  EXPECT_EQ(static_cast<unsigned char>(raw[13]), 0x02);
  alignas(2) std::uint8_t buf[12];
  int w = 0;
  int h = 0;
  int maxval = 0;
  ASSERT_TRUE(readPgm(dir.str("b.pgm"), buf, sizeof buf, w, h, maxval).ok);
  EXPECT_EQ(maxval, 4095);
  std::uint16_t back[6];
  std::memcpy(back, buf, sizeof back);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(back[i], img[static_cast<std::size_t>(i)]);
}

TEST(Pgm, RejectsSmallBufferAndBadFiles) {
  TempDir dir("pgmbad");
  const std::vector<std::uint8_t> img(20, 5);
  ASSERT_TRUE(writePgm8(dir.str("c.pgm"), ImageView8(img.data(), 5, 4)).ok);
  std::uint8_t buf[19];
  int w = -1;
  int h = -1;
  int maxval = -1;
  LoadError e = readPgm(dir.str("c.pgm"), buf, sizeof buf, w, h, maxval);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("c.pgm"), std::string::npos);
  EXPECT_NE(e.message.find("buffer"), std::string::npos);
  EXPECT_EQ(w, -1);  // outputs untouched on error
  spit(dir.str("ascii.pgm"), "P2\n2 2\n255\n1 2 3 4\n");
  EXPECT_FALSE(readPgm(dir.str("ascii.pgm"), buf, sizeof buf, w, h, maxval).ok);
  spit(dir.str("short.pgm"), std::string("P5\n# comment\n4 4\n255\n") + std::string(10, 'x'));
  e = readPgm(dir.str("short.pgm"), buf, sizeof buf, w, h, maxval);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("truncated"), std::string::npos);
  EXPECT_FALSE(readPgm(dir.str("missing.pgm"), buf, sizeof buf, w, h, maxval).ok);
}

// Issue 13 item 14: the sizes in the message, trailing bytes, the sequence's max_code, non-regular files.
TEST(Pgm, SaysTheSizesAndRejectsTrailingBytesForeignMaxvalAndDevices) {
  TempDir dir("pgmstrict");
  const std::vector<std::uint8_t> img(20, 5);
  ASSERT_TRUE(writePgm8(dir.str("c.pgm"), ImageView8(img.data(), 5, 4)).ok);
  std::uint8_t buf[64];
  int w = -1;
  int h = -1;
  int maxval = -1;
  LoadError e = readPgm(dir.str("c.pgm"), buf, 19, w, h, maxval);
  EXPECT_NE(e.message.find("image 5x4 with 1-byte samples needs 20 bytes, the buffer holds 19"),
            std::string::npos)
      << e.message;
  EXPECT_TRUE(readPgm(dir.str("c.pgm"), buf, sizeof buf, w, h, maxval, 255).ok);
  e = readPgm(dir.str("c.pgm"), buf, sizeof buf, w, h, maxval, 1023);
  EXPECT_NE(e.message.find("PGM maxval 255 differs from the sequence's max_code 1023"), std::string::npos)
      << e.message;
  spit(dir.str("tail.pgm"), slurp(dir.str("c.pgm")) + "x");
  e = readPgm(dir.str("tail.pgm"), buf, sizeof buf, w, h, maxval);
  EXPECT_NE(e.message.find("trailing bytes"), std::string::npos) << e.message;
  e = readPgm("/dev/zero", buf, sizeof buf, w, h, maxval);
  EXPECT_NE(e.message.find("not a regular file"), std::string::npos) << e.message;
  e = readPgm(dir.str("missing.pgm"), buf, sizeof buf, w, h, maxval);
  EXPECT_NE(e.message.find("No such file or directory"), std::string::npos) << e.message;
  EXPECT_EQ(w, 5);  // from the one good read
}

// Writes a 4-frame sequence with truth; returns its directory.
void writeSequence(const TempDir& dir, std::vector<Pose>& poses) {
  SequenceWriter writer;
  const PolygonModel model = makeBox(0.8, 0.6, 0.5, 0.7);
  ASSERT_TRUE(writer.open(dir.str("seq"), "unit \"test\"", camera(), model, 8, 255, 5.0).ok);
  const std::vector<std::uint8_t> img(64 * 48, 9);
  for (int i = 0; i < 4; ++i) {
    poses.push_back(
        Pose::fromYpr({0.1 * i - 0.2, 0.05 * i, kPi - 0.03 * i}, Vec3(0.01 * i, -0.02, 10.0 - i / 3.0)));
    ASSERT_TRUE(writePgm8(writer.framePath(i * 2), ImageView8(img.data(), 64, 48)).ok);
    writer.addFrame(i * 2, 1000 + 200000000LL * i, &poses.back());
  }
  ASSERT_TRUE(writer.close().ok);
}

TEST(Sequence, WriteLoadRoundTrip) {
  TempDir dir("rt");
  std::vector<Pose> poses;
  writeSequence(dir, poses);
  Sequence seq;
  const LoadError e = loadSequence(dir.str("seq"), seq);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(seq.name, "unit \"test\"");
  EXPECT_EQ(seq.bit_depth, 8);
  EXPECT_EQ(seq.max_code, 255);
  EXPECT_DOUBLE_EQ(seq.rate_hz, 5.0);
  EXPECT_EQ(seq.camera.fy_px, 101.5);
  EXPECT_EQ(seq.camera.distortion.p2, -0.0005);
  EXPECT_EQ(seq.model.surfaces().size(), 6U);
  ASSERT_EQ(seq.frames.size(), 4U);
  ASSERT_EQ(seq.truth.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(seq.frames[i].frame, static_cast<std::int64_t>(2 * i));
    EXPECT_EQ(seq.frames[i].timestamp_ns, 1000 + 200000000LL * static_cast<std::int64_t>(i));
    EXPECT_TRUE(fs::path(seq.frames[i].file).is_absolute());
    EXPECT_TRUE(fs::exists(seq.frames[i].file));
    EXPECT_EQ(seq.truth[i].frame, seq.frames[i].frame);
    EXPECT_LT((seq.truth[i].pose.R_c_m - poses[i].R_c_m).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((seq.truth[i].pose.t_c_m - poses[i].t_c_m).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// Each corruption must be rejected naming file, line and problem, leaving the output untouched.
struct Corruption {
  const char* file;
  const char* from;
  const char* to;
  const char* expect;  // substring of the message
};

TEST(Sequence, BadFilesAreRejectedWithFileLineAndProblem) {
  const Corruption cases[] = {
      {"sequence.toml", "rate_hz", "rate_hz_typo", "sequence.toml:"},
      {"sequence.toml", "bit_depth = 8", "bit_depth = 12", "bit_depth"},
      {"sequence.toml", "frame_count = 4", "frame_count = 5", "frame_count"},
      {"sequence.toml", "rate_hz = 5.0", "rate_hz = \"fast\"", "expected a finite number"},
      {"sequence.toml", "version = 1", "version = [", "sequence.toml:"},
      {"frames.csv", "\n2,", "\n2x,", "frames.csv:3: bad frame number"},
      {"frames.csv", "frames/000004.pgm", "frames/999999.pgm", "frames.csv:4: missing frame file"},
      {"frames.csv", "frame,timestamp_ns,file", "frame,file", "frames.csv:1: expected header"},
      {"frames.csv", "\n4,", "\n1,", "frames.csv:4: frame numbers must increase"},
      {"truth.csv", "\n0,1000,", "\n0,1000,1,", "truth.csv:2: expected 12 fields"},
      {"truth.csv", "\n2,200001000,", "\n3,200001000,", "truth.csv:3: frame 3 is not in frames.csv"},
      // Issue 13 item 14: frame files stay inside the sequence directory, and a sequence has frames.
      {"frames.csv", "frames/000004.pgm", "frames/../../seq/frames/000004.pgm", "frames.csv:4: frame file"},
      {"frames.csv", "frames/000004.pgm", "/etc/passwd",
       "frames.csv:4: frame file '/etc/passwd' is an absolute"},
      {"sequence.toml", "frame_count = 4", "frame_count = 0", "frame_count"},
      // Item 12: non-ASCII where toml++ expects a key never reaches toml++.
      {"sequence.toml", "rate_hz", "\xc3\xa9 = 1\nrate_hz", "sequence.toml:"},
  };
  for (const Corruption& c : cases) {
    TempDir dir("bad");
    std::vector<Pose> poses;
    writeSequence(dir, poses);
    replaceInFile(dir.str("seq/") + c.file, c.from, c.to);
    Sequence seq;
    seq.name = "sentinel";
    const LoadError e = loadSequence(dir.str("seq"), seq);
    EXPECT_FALSE(e.ok) << c.file << ": " << c.from;
    EXPECT_NE(e.message.find(c.expect), std::string::npos) << e.message;
    EXPECT_NE(e.message.find(c.file), std::string::npos) << e.message;
    EXPECT_EQ(seq.name, "sentinel");
    EXPECT_TRUE(seq.frames.empty());
  }
}

TEST(Sequence, TruthYprMustAgreeWithQuaternion) {
  TempDir dir("ypr");
  spit(dir.str("t.csv"),
       "frame,timestamp_ns,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg\n"
       "0,0,0,0,10,1,0,0,0,0,0,0\n"
       "1,1,0,0,10,1,0,0,0,5,0,0\n");
  std::vector<TruthRow> rows;
  const LoadError e = loadTruthCsv(dir.str("t.csv"), rows);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("t.csv:3:"), std::string::npos) << e.message;
  EXPECT_TRUE(rows.empty());
}

}  // namespace
}  // namespace visnav::replay
