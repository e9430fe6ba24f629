// An independent PNG reader for the tests of tools/png: walks the chunks, checks every CRC with zlib's crc32,
// inflates the IDAT stream with zlib and undoes the five row filters (PNG spec 9.2), for 8-bit RGB images.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace visnav::test {

struct DecodedPng {
  bool ok = false;
  std::string error;  ///< what was wrong, when !ok
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgb;  ///< row-major, 3 bytes a pixel
  int chunks = 0;
};

inline std::uint32_t readU32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24U) | (std::uint32_t{b[at + 1]} << 16U) |
         (std::uint32_t{b[at + 2]} << 8U) | b[at + 3];
}

inline std::vector<std::uint8_t> readBinaryFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline int paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return pa <= pb && pa <= pc ? a : (pb <= pc ? b : c);
}

inline DecodedPng decodePng(const std::vector<std::uint8_t>& png) {
  DecodedPng d;
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (png.size() < 8 || !std::equal(signature, signature + 8, png.begin())) {
    d.error = "no PNG signature";
    return d;
  }
  std::size_t at = 8;
  std::vector<std::uint8_t> idat;
  bool end = false;
  while (at + 12 <= png.size() && !end) {
    const std::uint32_t len = readU32(png, at);
    if (at + 12 + len > png.size()) {
      d.error = "chunk runs past the end";
      return d;
    }
    const std::string type(png.begin() + static_cast<std::ptrdiff_t>(at + 4),
                           png.begin() + static_cast<std::ptrdiff_t>(at + 8));
    const uLong crc = ::crc32(0UL, png.data() + at + 4, static_cast<uInt>(len + 4));
    if (crc != readU32(png, at + 8 + len)) {
      d.error = "CRC mismatch in " + type;
      return d;
    }
    ++d.chunks;
    if (type == "IHDR") {
      if (len != 13 || png[at + 16] != 8 || png[at + 17] != 2 || png[at + 20] != 0) {
        d.error = "not an 8-bit RGB non-interlaced IHDR";
        return d;
      }
      d.width = readU32(png, at + 8);
      d.height = readU32(png, at + 12);
    } else if (type == "IDAT") {
      idat.insert(idat.end(), png.begin() + static_cast<std::ptrdiff_t>(at + 8),
                  png.begin() + static_cast<std::ptrdiff_t>(at + 8 + len));
    }
    end = type == "IEND";
    at += 12 + len;
  }
  if (!end || at != png.size()) {
    d.error = "no IEND, or bytes after it";
    return d;
  }
  const std::size_t row_bytes = static_cast<std::size_t>(d.width) * 3U;
  std::vector<std::uint8_t> raw((row_bytes + 1U) * d.height + 1U);  // one spare byte: a longer stream shows
  uLongf raw_len = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &raw_len, idat.data(), static_cast<uLong>(idat.size())) != Z_OK ||
      raw_len != raw.size() - 1U) {
    d.error = "IDAT does not inflate to the image size";
    return d;
  }
  d.rgb.assign(row_bytes * d.height, 0);
  for (std::size_t y = 0; y < d.height; ++y) {
    const std::uint8_t filter = raw[y * (row_bytes + 1U)];
    const std::uint8_t* in = raw.data() + y * (row_bytes + 1U) + 1U;
    std::uint8_t* out = d.rgb.data() + y * row_bytes;
    const std::uint8_t* above = y > 0 ? out - row_bytes : nullptr;
    for (std::size_t i = 0; i < row_bytes; ++i) {
      const int a = i >= 3 ? out[i - 3] : 0;
      const int b = above != nullptr ? above[i] : 0;
      const int c = i >= 3 && above != nullptr ? above[i - 3] : 0;
      int predictor = 0;
      switch (filter) {
        case 0: predictor = 0; break;
        case 1: predictor = a; break;
        case 2: predictor = b; break;
        case 3: predictor = (a + b) / 2; break;
        case 4: predictor = paeth(a, b, c); break;
        default: d.error = "unknown filter type " + std::to_string(filter); return d;
      }
      out[i] = static_cast<std::uint8_t>(in[i] + predictor);
    }
  }
  d.ok = true;
  return d;
}

}  // namespace visnav::test
