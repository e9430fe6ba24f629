#include "capi_test_support.hpp"

#include <cstring>

#include "gtest/gtest.h"
#include "visnav/synthetic/scenario_camera.hpp"

namespace visnav::test {

const RenderedSequence& fullApproachFrames() {
  static const RenderedSequence sequence = [] {
    RenderedSequence s;
    synthetic::ScenarioCamera camera(
        {sourcePath("config/scenarios/full_approach_ci.toml"), camera::Pacing::kAsFastAsPossible, false, 2});
    const LoadError e = camera.open();
    EXPECT_TRUE(e.ok) << e.message;
    if (!e.ok) return s;
    Frame frame;
    while (camera.acquire(0, frame) == camera::AcquireResult::kFrame) {
      const ImageView8& view = frame.image.u8;
      EXPECT_EQ(frame.image.depth, MonoImage::Depth::kU8);
      s.width = view.width();
      s.height = view.height();
      RenderedFrame f;
      f.exposure_time_ns = frame.exposure_time_ns;
      f.pixels.resize(static_cast<std::size_t>(s.width) * s.height);
      for (int y = 0; y < s.height; ++y)
        std::memcpy(f.pixels.data() + static_cast<std::size_t>(y) * s.width, view.row(y),
                    static_cast<std::size_t>(s.width));
      s.frames.push_back(std::move(f));
      camera.release(frame);
    }
    camera.close();
    return s;
  }();
  return sequence;
}

}  // namespace visnav::test
