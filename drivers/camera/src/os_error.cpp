#include "visnav/camera/os_error.hpp"

#include <cstdio>
#include <cstring>

namespace visnav::camera {

// glibc 2.32+ (Debian 12: 2.36): static strings, no locale lookup, unlike strerror().
const char* errnoName(int error_number) {
  const char* name = ::strerrorname_np(error_number);
  return name != nullptr ? name : "E?";
}

const char* errnoText(int error_number) {
  const char* text = ::strerrordesc_np(error_number);
  return text != nullptr ? text : "unknown error";
}

const char* formatOsError(char* out, std::size_t capacity, const char* what, int error_number) {
  if (capacity == 0) return out;
  if (error_number == 0)
    std::snprintf(out, capacity, "%s", what);
  else
    std::snprintf(out, capacity, "%s: %s (%s)", what, errnoName(error_number), errnoText(error_number));
  return out;
}

}  // namespace visnav::camera
