#include "visnav/camera/mono_view.hpp"

namespace visnav::camera {

int bytesPerPixel(PixelFormat format) { return format == PixelFormat::kGrey8 ? 1 : 2; }

std::uint16_t maxCode(PixelFormat format) {
  switch (format) {
    case PixelFormat::kGrey8:
    case PixelFormat::kYuyv: return 255;
    case PixelFormat::kY10: return 1023;
    case PixelFormat::kY12: return 4095;
    case PixelFormat::kY16: return 65535;
  }
  return 255;
}

bool isZeroCopy(PixelFormat format) { return format != PixelFormat::kYuyv; }

std::size_t minimumBufferBytes(PixelFormat format, int width, int height, std::size_t stride_bytes) {
  if (width <= 0 || height <= 0) return 0;
  const auto row_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(bytesPerPixel(format));
  return stride_bytes * static_cast<std::size_t>(height - 1) + row_bytes;
}

MonoImage viewInPlace(PixelFormat format, const void* data, int width, int height, std::size_t stride_bytes) {
  const auto stride = static_cast<std::ptrdiff_t>(stride_bytes);
  if (format == PixelFormat::kGrey8)
    return MonoImage::from8(ImageView8(static_cast<const std::uint8_t*>(data), width, height, stride));
  if (format == PixelFormat::kYuyv) return MonoImage{};
  return MonoImage::from16(ImageView16(static_cast<const std::uint16_t*>(data), width, height, stride),
                           maxCode(format));
}

MonoImage extractLumaYuyv(const std::uint8_t* yuyv, int width, int height, std::size_t stride_bytes,
                          std::uint8_t* luma) {
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = yuyv + stride_bytes * static_cast<std::size_t>(y);
    std::uint8_t* dst = luma + static_cast<std::size_t>(width) * static_cast<std::size_t>(y);
    for (int x = 0; x < width; ++x) dst[x] = src[2 * x];  // Y0 U Y1 V: luma in the even bytes
  }
  return MonoImage::from8(ImageView8(luma, width, height));
}

MonoImage extractLumaRgb(const std::uint8_t* rgb, int width, int height, std::size_t stride_bytes,
                         const PackedRgbLayout& layout, std::uint8_t* luma) {
  const auto step = static_cast<std::size_t>(layout.bytes_per_pixel);
  const auto r = static_cast<std::size_t>(layout.red);
  const auto g = static_cast<std::size_t>(layout.green);
  const auto b = static_cast<std::size_t>(layout.blue);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = rgb + stride_bytes * static_cast<std::size_t>(y);
    std::uint8_t* dst = luma + static_cast<std::size_t>(width) * static_cast<std::size_t>(y);
    for (int x = 0; x < width; ++x, src += step)
      dst[x] = static_cast<std::uint8_t>((77U * src[r] + 150U * src[g] + 29U * src[b] + 128U) >> 8U);
  }
  return MonoImage::from8(ImageView8(luma, width, height));
}

}  // namespace visnav::camera
