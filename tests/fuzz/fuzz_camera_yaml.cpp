// OpenCV FileStorage YAML calibrations (fsw/io loadCameraOpenCvYaml).
#include "fuzz_util.hpp"
#include "visnav/io/camera_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = visnav::fuzz::writeFile("camera.yaml", data, size);
  visnav::CameraIntrinsics camera;
  (void)visnav::io::loadCameraOpenCvYaml(path, camera);
  return 0;
}
