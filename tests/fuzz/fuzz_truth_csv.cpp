// truth.csv (drivers/replay loadTruthCsv: numbers, unit quaternions, YPR consistency).
#include <vector>

#include "fuzz_util.hpp"
#include "visnav/replay/sequence.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("truth.csv", data, size);
  std::vector<visnav::replay::TruthRow> rows;
  (void)visnav::replay::loadTruthCsv(path, rows);
  return 0;
}
