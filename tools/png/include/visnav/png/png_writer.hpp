// The one PNG writer of the ground tools' pictures: visnav-eval's plots, visnav-campaign's and
// visnav-closedloop's plots and visnav-replay's overlays all reach it through eval::Canvas::writePng.
// 8-bit RGB, every row with PNG filter 2 (Up: the difference to the row above, which turns the long flat runs
// of a plot into zeros), deflated by zlib at its best compression: visnav-closedloop's 1400 x 1490 plot of
// the ci scenario is 24 KB, where the stored-block encoder before wrote 6.3 MB (tools/eval/README.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"

namespace visnav::png {

/// Encodes width x height RGB pixels (row-major, 3 bytes each) into a complete PNG file image in `png`.
/// Fails on a size that does not match `rgb` or that PNG cannot hold, and when zlib fails.
LoadError encodeRgb(int width, int height, const std::vector<std::uint8_t>& rgb,
                    std::vector<std::uint8_t>& png);

/// encodeRgb, written to `path`; the error names the file.
LoadError writeRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace visnav::png
