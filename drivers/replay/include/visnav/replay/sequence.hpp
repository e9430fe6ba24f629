// The on-disk sequence format (documented in drivers/replay/README.md): a directory with
//   sequence.toml   name, frame count, bit depth, rate, file names of the parts below
//   camera.toml     camera (fsw/io format; .yaml OpenCV calibrations are accepted too)
//   model.toml      target model (fsw/io format; .cao accepted too)
//   frames.csv      frame,timestamp_ns,file          (one row per frame, file relative to the directory)
//   frames/NNNNNN.pgm   binary PGM (P5), 8-bit or 16-bit big-endian, maxval = the sensor's max code
//   truth.csv       optional: frame,timestamp_ns,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg
// Reading a sequence is init-time work (allocates); reading one frame into a preallocated buffer does not.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/image_view.hpp"
#include "visnav/core/status.hpp"
#include "visnav/geometry/camera.hpp"
#include "visnav/geometry/polygon_model.hpp"
#include "visnav/geometry/pose.hpp"

namespace visnav::replay {

struct TruthRow {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  Pose pose;  ///< T_c_m, CONVENTIONS.md
};

struct FrameEntry {
  std::int64_t frame = 0;
  std::int64_t timestamp_ns = 0;
  std::string file;  ///< absolute path
};

struct Sequence {
  std::string directory;
  std::string name;
  int bit_depth = 8;             ///< 8 or 16
  std::uint16_t max_code = 255;  ///< PGM maxval
  double rate_hz = 5.0;          ///< recorded rate
  std::string camera_path;       ///< absolute paths of the parts
  std::string model_path;
  CameraIntrinsics camera;
  PolygonModel model;
  std::vector<FrameEntry> frames;
  std::vector<TruthRow> truth;  ///< empty when the sequence has no truth
};

/// Loads sequence.toml, camera, model, frames.csv and truth.csv (if named). Errors name file, line, problem.
LoadError loadSequence(const std::string& directory, Sequence& out);

/// Reads truth.csv-format rows (also used by visnav-eval).
LoadError loadTruthCsv(const std::string& path, std::vector<TruthRow>& out);

/// PGM I/O. `readPgm` fills a caller-owned buffer of capacity `capacity_bytes` (no allocation on success);
/// 16-bit samples are converted to host order. Reports width, height, maxval. Rejects a file that is not
/// regular, has bytes after the raster, or (expected_maxval > 0) whose maxval differs from expected_maxval
/// (the sequence's max_code).
LoadError readPgm(const std::string& path, std::uint8_t* buffer, std::size_t capacity_bytes, int& width,
                  int& height, int& maxval, int expected_maxval = 0);
LoadError writePgm8(const std::string& path, const ImageView8& image);
LoadError writePgm16(const std::string& path, const ImageView16& image, std::uint16_t maxval);

/// Writes a sequence directory's metadata; frames are written by the caller with writePgm*.
/// Copies/writes camera and model into the directory, writes sequence.toml, frames.csv and truth.csv.
class SequenceWriter {
 public:
  LoadError open(const std::string& directory, const std::string& name, const CameraIntrinsics& camera,
                 const PolygonModel& model, int bit_depth, std::uint16_t max_code, double rate_hz);
  /// Path the caller must write frame `frame` to (frames/NNNNNN.pgm under the directory).
  std::string framePath(std::int64_t frame) const;
  /// Records one frame (and its truth pose, if has_truth).
  void addFrame(std::int64_t frame, std::int64_t timestamp_ns, const Pose* truth);
  LoadError close();

 private:
  std::string m_directory;
  std::string m_name;
  int m_bit_depth = 8;
  std::uint16_t m_max_code = 255;
  double m_rate_hz = 5.0;
  std::vector<FrameEntry> m_frames;
  std::vector<TruthRow> m_truth;
  bool m_has_truth = false;
};

}  // namespace visnav::replay
