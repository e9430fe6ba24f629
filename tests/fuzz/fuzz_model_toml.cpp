// visnav's TOML model format (fsw/io loadModelToml, then PolygonModel::build).
#include "fuzz_util.hpp"
#include "visnav/io/model_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("model.toml", data, size);
  visnav::PolygonModel model;
  (void)visnav::io::loadModelToml(path, model);
  return 0;
}
