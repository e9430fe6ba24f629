// Error text with the errno spelled out, for the live drivers: "VIDIOC_DQBUF: EIO (Input/output error)".
// Written into a caller's fixed buffer (no allocation, no locale, thread-safe), so it may run on the cycle
// path.
#pragma once

#include <cstddef>

namespace visnav::camera {

/// Symbolic name of `error_number` ("EIO"), or "E?" for a number glibc does not know.
const char* errnoName(int error_number);
/// Description of `error_number` ("Input/output error"), or "unknown error".
const char* errnoText(int error_number);

/// Writes "`what`: ENAME (text)" into `out` (truncated to `capacity`, always terminated); just `what` when
/// `error_number` is 0. Returns `out`.
const char* formatOsError(char* out, std::size_t capacity, const char* what, int error_number);

/// The same with a negative errno as libcamera returns it (-ENODEV).
inline const char* formatNegativeError(char* out, std::size_t capacity, const char* what,
                                       int negative_errno) {
  return formatOsError(out, capacity, what, -negative_errno);
}

}  // namespace visnav::camera
