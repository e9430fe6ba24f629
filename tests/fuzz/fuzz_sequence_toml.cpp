// sequence.toml (drivers/replay loadSequence with the fixture's camera, model, frames and truth).
#include "sequence_fixture.hpp"
#include "visnav/replay/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = visnav::fuzz::writeSequenceFixture();
  visnav::fuzz::writeFile("seq/sequence.toml", data, size);
  visnav::replay::Sequence sequence;
  (void)visnav::replay::loadSequence(dir, sequence);
  return 0;
}
