// Minimal PNG encoder: 8-bit RGB, filter type 0, zlib stream of stored (uncompressed) deflate blocks.
// Plots are small, so size does not matter and no zlib dependency is needed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"

namespace visnav::eval {

/// CRC-32 (ISO 3309 / PNG, polynomial 0xEDB88320), continuing from `crc` (0 to start).
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0U);
/// Adler-32 of zlib (RFC 1950), continuing from `adler` (1 to start).
std::uint32_t adler32(const std::uint8_t* data, std::size_t size, std::uint32_t adler = 1U);

/// Encodes width x height RGB pixels (row-major, 3 bytes each) into a complete PNG file image.
std::vector<std::uint8_t> encodePngRgb(int width, int height, const std::vector<std::uint8_t>& rgb);
LoadError writePngRgb(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace visnav::eval
