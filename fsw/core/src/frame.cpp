#include "visnav/core/frame.hpp"

namespace visnav {

const char* toString(PixelFormat format) {
  switch (format) {
    case PixelFormat::kGrey8: return "GREY";
    case PixelFormat::kY10: return "Y10";
    case PixelFormat::kY12: return "Y12";
    case PixelFormat::kY16: return "Y16";
    case PixelFormat::kYuyv: return "YUYV";
  }
  return "unknown";
}

}  // namespace visnav
