#include "visnav/eval/png_writer.hpp"

#include <algorithm>
#include <array>
#include <fstream>

namespace visnav::eval {
namespace {

std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256U; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0U ? 0xEDB88320U ^ (c >> 1U) : c >> 1U;
    table[n] = c;
  }
  return table;
}

void putU32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24U));
  out.push_back(static_cast<std::uint8_t>(v >> 16U));
  out.push_back(static_cast<std::uint8_t>(v >> 8U));
  out.push_back(static_cast<std::uint8_t>(v));
}

// Chunk = length, type, data, CRC over type + data.
void putChunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  putU32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t type_pos = out.size();
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(type[i]));
  out.insert(out.end(), data.begin(), data.end());
  putU32(out, crc32(out.data() + type_pos, out.size() - type_pos));
}

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> kTable = makeCrcTable();
  std::uint32_t c = crc ^ 0xFFFFFFFFU;
  for (std::size_t i = 0; i < size; ++i) c = kTable[(c ^ data[i]) & 0xFFU] ^ (c >> 8U);
  return c ^ 0xFFFFFFFFU;
}

std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t adler) {
  std::uint32_t a = adler & 0xFFFFU;
  std::uint32_t b = adler >> 16U;
  for (std::size_t i = 0; i < size; ++i) {
    a = (a + data[i]) % 65521U;
    b = (b + a) % 65521U;
  }
  return (b << 16U) | a;
}

std::vector<std::uint8_t> encodePngRgb(int width, int height, const std::vector<std::uint8_t>& rgb) {
  // Raw scanlines, each prefixed by filter type 0 (none).
  const std::size_t row_bytes = static_cast<std::size_t>(width) * 3U;
  std::vector<std::uint8_t> raw;
  raw.reserve((row_bytes + 1U) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    raw.push_back(0U);
    const auto begin = rgb.begin() + static_cast<std::ptrdiff_t>(row_bytes * static_cast<std::size_t>(y));
    raw.insert(raw.end(), begin, begin + static_cast<std::ptrdiff_t>(row_bytes));
  }
  // zlib: CMF/FLG (deflate, 32 KiB window, check bits), stored blocks of <= 65535 bytes, Adler-32.
  std::vector<std::uint8_t> z{0x78U, 0x01U};
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(65535U, raw.size() - pos);
    const bool last = pos + len == raw.size();
    z.push_back(last ? 1U : 0U);  // BFINAL, BTYPE = 00 (stored)
    z.push_back(static_cast<std::uint8_t>(len & 0xFFU));
    z.push_back(static_cast<std::uint8_t>(len >> 8U));
    z.push_back(static_cast<std::uint8_t>(~len & 0xFFU));
    z.push_back(static_cast<std::uint8_t>((~len >> 8U) & 0xFFU));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos),
             raw.begin() + static_cast<std::ptrdiff_t>(pos + len));
    pos += len;
  } while (pos < raw.size());
  putU32(z, adler32(raw.data(), raw.size()));

  std::vector<std::uint8_t> png{0x89U, 'P', 'N', 'G', '\r', '\n', 0x1AU, '\n'};
  std::vector<std::uint8_t> ihdr;
  putU32(ihdr, static_cast<std::uint32_t>(width));
  putU32(ihdr, static_cast<std::uint32_t>(height));
  ihdr.insert(ihdr.end(),
              {8U, 2U, 0U, 0U, 0U});  // bit depth 8, colour type RGB, deflate, filter 0, no interlace
  putChunk(png, "IHDR", ihdr);
  putChunk(png, "IDAT", z);
  putChunk(png, "IEND", {});
  return png;
}

LoadError writePngRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * height * 3U)
    return LoadError::failure(path + ": invalid image size for PNG output");
  const std::vector<std::uint8_t> png = encodePngRgb(width, height, rgb);
  std::ofstream out(path, std::ios::binary);
  if (!out) return LoadError::failure(path + ": cannot open for writing");
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  if (!out) return LoadError::failure(path + ": write failed");
  return LoadError::success();
}

}  // namespace visnav::eval
