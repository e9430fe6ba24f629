// visnav's TOML camera format (fsw/io loadCameraToml, then the physical-range and distortion checks).
#include "fuzz_util.hpp"
#include "visnav/io/camera_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("camera.toml", data, size);
  visnav::CameraIntrinsics camera;
  (void)visnav::io::loadCameraToml(path, camera);
  return 0;
}
