// Shared by test_far_sharpness.cpp and test_far_silhouette.cpp: a 640 x 480 8-bit frame drawn directly from a
// brightness function (not rendered), so each case is the shape its name says.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "visnav/core/image_view.hpp"

namespace visnav::far::drawn {

struct Drawn {
  int w = 640;
  int h = 480;
  std::vector<std::uint8_t> px;
  MonoImage view() const { return MonoImage::from8(ImageView8(px.data(), w, h)); }
};

/// brightness(x, y) on [0, 1] at pixel centres, plus Gaussian noise of `noise` (fixed seed), quantised.
inline Drawn draw(const std::function<double(double, double)>& brightness, double noise, unsigned seed = 7U) {
  Drawn d;
  d.px.resize(static_cast<std::size_t>(d.w) * static_cast<std::size_t>(d.h));
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int y = 0; y < d.h; ++y)
    for (int x = 0; x < d.w; ++x) {
      const double v = brightness(x + 0.5, y + 0.5) + noise * gauss(rng);
      const int i = y * d.w + x;
      d.px[static_cast<std::size_t>(i)] =
          static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
    }
  return d;
}

}  // namespace visnav::far::drawn
