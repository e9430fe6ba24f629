// ViSP .cao models (fsw/io loadModelCao: tokenizer, counts, face chaining, orientation, build).
#include "fuzz_util.hpp"
#include "visnav/io/model_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("model.cao", data, size);
  visnav::PolygonModel model;
  (void)visnav::io::loadModelCao(path, model);
  return 0;
}
