// frames.csv (drivers/replay loadSequence: rows, order, paths that must stay in the directory, counts).
#include "sequence_fixture.hpp"
#include "visnav/replay/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = visnav::fuzz::writeSequenceFixture();
  visnav::fuzz::writeFile("seq/frames.csv", data, size);
  visnav::replay::Sequence sequence;
  (void)visnav::replay::loadSequence(dir, sequence);
  return 0;
}
