// Per-frame cost of the live camera drivers on our side: the YUYV -> Y copy (the only pixel work), and one
// V4L2 acquire() + release() round (poll, DQBUF, QBUF, view set-up) against the FAKE device, whose own
// frame filling is switched off and its bookkeeping runs with the timer paused. VGA, the flight image size.
#include <benchmark/benchmark.h>

#include <vector>

#include "../drivers/v4l2/fake_v4l2_device.hpp"
#include "visnav/camera/mono_view.hpp"
#include "visnav/v4l2/v4l2_camera.hpp"

namespace {

void BM_YuyvLumaVga(benchmark::State& state) {
  std::vector<std::uint8_t> yuyv(640 * 2 * 480, 0x80);
  std::vector<std::uint8_t> luma(640 * 480);
  for (auto _ : state) {
    const visnav::MonoImage image = visnav::camera::extractLumaYuyv(yuyv.data(), 640, 480, 1280, luma.data());
    benchmark::DoNotOptimize(image);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * 640 * 480 * 2);
}
BENCHMARK(BM_YuyvLumaVga);

void BM_V4l2AcquireReleaseVga(benchmark::State& state) {
  visnav::test::FakeV4l2Device::Config config;
  config.max_width = 640;
  config.max_height = 480;
  config.fill_pixels = false;  // measure the driver, not the fake's pattern writer
  visnav::test::FakeV4l2Device device(config);
  visnav::camera::CameraParams params;
  params.device = config.path;
  params.pixel_format = static_cast<int>(state.range(0));
  visnav::camera::V4l2Camera camera(params, device);
  if (!camera.open().ok) {
    state.SkipWithError(camera.lastError());
    return;
  }
  for (auto _ : state) {
    state.PauseTiming();
    device.produceFrame();
    state.ResumeTiming();
    visnav::Frame frame;
    if (camera.acquire(0, frame) != visnav::camera::AcquireResult::kFrame) {
      state.SkipWithError("no frame");
      break;
    }
    benchmark::DoNotOptimize(frame);
    camera.release(frame);
  }
}
BENCHMARK(BM_V4l2AcquireReleaseVga)
    ->Arg(static_cast<int>(visnav::camera::RequestedFormat::kGrey))
    ->Arg(static_cast<int>(visnav::camera::RequestedFormat::kYuyv));

}  // namespace

BENCHMARK_MAIN();
