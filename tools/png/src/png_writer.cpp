#include "visnav/png/png_writer.hpp"

#include <zlib.h>

#include <cstdio>
#include <limits>

namespace visnav::png {
namespace {

constexpr std::uint8_t kFilterUp = 2;

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24U));
  out.push_back(static_cast<std::uint8_t>(v >> 16U));
  out.push_back(static_cast<std::uint8_t>(v >> 8U));
  out.push_back(static_cast<std::uint8_t>(v));
}

// Chunk = length, type, data, CRC-32 (zlib's) over type + data.
void putChunk(std::vector<std::uint8_t>& out, const char* type, const std::uint8_t* data, std::size_t size) {
  putU32(out, static_cast<std::uint32_t>(size));
  const std::size_t type_pos = out.size();
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(type[i]));
  out.insert(out.end(), data, data + size);
  putU32(out, static_cast<std::uint32_t>(
                  crc32(0UL, out.data() + type_pos, static_cast<uInt>(out.size() - type_pos))));
}

}  // namespace

LoadError encodeRgb(int width, int height, const std::vector<std::uint8_t>& rgb,
                    std::vector<std::uint8_t>& png) {
  png.clear();
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 3U;
  const std::size_t filtered_size = (row_bytes + 1U) * static_cast<std::size_t>(height);
  // One IDAT chunk holds at most 2^31 - 1 bytes, and zlib's compressBound() takes a uLong: far above a plot.
  if (width <= 0 || height <= 0 || rgb.size() != row_bytes * static_cast<std::size_t>(height) ||
      filtered_size > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max() / 2))
    return LoadError::failure("PNG: invalid image size " + std::to_string(width) + " x " +
                              std::to_string(height));
  // Filter Up on every row (the first row's "above" is zeros: the row itself).
  std::vector<std::uint8_t> filtered(filtered_size);
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    std::uint8_t* out = filtered.data() + y * (row_bytes + 1U);
    const std::uint8_t* row = rgb.data() + y * row_bytes;
    const std::uint8_t* above = y == 0 ? nullptr : row - row_bytes;
    out[0] = kFilterUp;
    for (std::size_t i = 0; i < row_bytes; ++i)
      out[1 + i] = static_cast<std::uint8_t>(above == nullptr ? row[i] : row[i] - above[i]);
  }
  uLongf deflated_size = compressBound(static_cast<uLong>(filtered.size()));
  std::vector<std::uint8_t> deflated(deflated_size);
  const int z = compress2(deflated.data(), &deflated_size, filtered.data(),
                          static_cast<uLong>(filtered.size()), Z_BEST_COMPRESSION);
  if (z != Z_OK) return LoadError::failure(std::string("PNG: zlib compress2 failed: ") + zError(z));

  png = {0x89U, 'P', 'N', 'G', '\r', '\n', 0x1AU, '\n'};
  std::vector<std::uint8_t> ihdr;
  putU32(ihdr, static_cast<std::uint32_t>(width));
  putU32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(),
              {8U, 2U, 0U, 0U, 0U});  // bit depth 8, colour type RGB, deflate, filter 0, no interlace
  putChunk(png, "IHDR", ihdr.data(), ihdr.size());
  putChunk(png, "IDAT", deflated.data(), deflated_size);
  putChunk(png, "IEND", nullptr, 0);
  return LoadError::success();
}

LoadError writeRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  std::vector<std::uint8_t> png;
  if (LoadError e = encodeRgb(width, height, rgb, png); !e.ok)
    return LoadError::failure(path + ": " + e.message);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return LoadError::failure(path + ": cannot open for writing");
  const bool written = std::fwrite(png.data(), 1, png.size(), f) == png.size();
  if (std::fclose(f) != 0 || !written) return LoadError::failure(path + ": write failed");
  return LoadError::success();
}

}  // namespace visnav::png
