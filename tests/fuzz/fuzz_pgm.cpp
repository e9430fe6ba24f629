// Binary PGM frames (drivers/replay readPgm) into a fixed buffer, with and without an expected maxval.
#include <array>

#include "fuzz_util.hpp"
#include "visnav/replay/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static std::array<std::uint8_t, 64 * 1024> buffer;
  const std::string path = visnav::fuzz::writeFile("frame.pgm", data, size);
  int width = 0;
  int height = 0;
  int maxval = 0;
  const visnav::LoadError e =
      visnav::replay::readPgm(path, buffer.data(), buffer.size(), width, height, maxval);
  if (e.ok && (width <= 0 || height <= 0 || maxval <= 0)) __builtin_trap();  // success means a usable frame
  (void)visnav::replay::readPgm(path, buffer.data(), buffer.size(), width, height, maxval, 255);
  return 0;
}
