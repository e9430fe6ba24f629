// A small valid sequence directory in the scratch directory: the sequence, frames and truth fuzzers each
// replace one of its files with the input.
#pragma once

#include <string>

#include "fuzz_util.hpp"

namespace visnav::fuzz {

inline const char* kSequenceToml =
    "format = \"visnav-sequence\"\nversion = 1\nname = \"fuzz\"\nframe_count = 2\nbit_depth = 8\n"
    "max_code = 255\nrate_hz = 5.0\ncamera = \"camera.toml\"\nmodel = \"model.toml\"\nframes = "
    "\"frames.csv\"\n"
    "truth = \"truth.csv\"\n";
inline const char* kFramesCsv =
    "frame,timestamp_ns,file\n0,1000,frames/000000.pgm\n2,200001000,frames/000002.pgm\n";
inline const char* kTruthCsv =
    "frame,timestamp_ns,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg\n"
    "0,1000,0,0,10,1,0,0,0,0,0,0\n2,200001000,0,0,9,1,0,0,0,0,0,0\n";

/// Writes every file of the fixture into <scratch>/seq/ and returns that directory.
inline std::string writeSequenceFixture() {
  std::filesystem::create_directories(scratchDir() + "seq/frames");
  writeFile("seq/camera.toml", "[camera]\nwidth_px = 8\nheight_px = 6\nfx_px = 10.0\nfy_px = 10.0\n");
  writeFile("seq/model.toml",
            "[model]\nunits = \"m\"\nvertices = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]\n"
            "[[surface]]\nvertices = [0, 1, 2, 3]\n");
  const std::string pgm = "P5\n8 6\n255\n" + std::string(48, '\x40');
  writeFile("seq/frames/000000.pgm", pgm);
  writeFile("seq/frames/000002.pgm", pgm);
  writeFile("seq/sequence.toml", kSequenceToml);
  writeFile("seq/frames.csv", kFramesCsv);
  writeFile("seq/truth.csv", kTruthCsv);
  return scratchDir() + "seq";
}

}  // namespace visnav::fuzz
