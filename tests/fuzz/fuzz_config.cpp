// The whole visnavd config (fsw/app loadVisnavConfig: every parameter table, partition, unknown keys).
#include "fuzz_util.hpp"
#include "visnav/app/visnav_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("visnavd.toml", data, size);
  visnav::app::VisnavConfig config;
  (void)visnav::app::loadVisnavConfig(path, config);
  return 0;
}
