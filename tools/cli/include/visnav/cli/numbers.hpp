// Numbers given on a ground tool's command line: one parser for every tool, so "--x 1e3x", "--x nan" and
// "--n 1.5" mean the same thing (a usage error) everywhere. Each function reads the whole argument or
// fails, writes `out` only on success, and does not allocate:
//   - no leading whitespace (strtod/strtoll would skip it) and no trailing characters;
//   - parseNumber: finite only ("nan", "inf" and an overflow such as "1e999" are refused); an underflow
//     ("1e-400") is the nearest double, 0 or subnormal, as strtod returns it;
//   - parseInteger / parseUnsigned: base 10 only ("0x10", "3.0", "1e3" are refused), within [min, max];
//     parseUnsigned takes no sign at all (strtoull would wrap "-1" to 2^64 - 1).
// Locale: strtod follows LC_NUMERIC; the tools never call setlocale, so it is "C" and the decimal point is
// '.' whatever the user's LANG says.
#pragma once

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace visnav::cli {

namespace detail {
/// Non-empty and not starting with whitespace: what strtod and strtoll would otherwise skip.
inline bool startsCleanly(const char* text) {
  return text != nullptr && *text != '\0' && std::isspace(static_cast<unsigned char>(*text)) == 0;
}
/// A std::string with an embedded NUL would be cut short by the char* parsers: never a number.
inline bool hasNul(const std::string& text) { return text.find('\0') != std::string::npos; }
}  // namespace detail

/// A finite floating-point number, the whole of `text` ("1e-6", "-2.5", "+3"; not "", " 1", "1x", "nan").
inline bool parseNumber(const char* text, double& out) {
  if (!detail::startsCleanly(text)) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0') return false;
  if (errno == ERANGE && std::isinf(v)) return false;  // overflow: strtod returned +-HUGE_VAL
  if (!std::isfinite(v)) return false;                 // "nan", "inf", "infinity" spelled out
  out = v;
  return true;
}

inline bool parseNumber(const std::string& text, double& out) {
  return !detail::hasNul(text) && parseNumber(text.c_str(), out);
}

/// A base-10 integer in [min, max], the whole of `text` ("42", "-1", "+7"; not "", "3.0", "1e3", "7 ").
inline bool parseInteger(const char* text, long long min, long long max, long long& out) {
  if (!detail::startsCleanly(text)) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || v < min || v > max) return false;
  out = v;
  return true;
}

inline bool parseInteger(const std::string& text, long long min, long long max, long long& out) {
  return !detail::hasNul(text) && parseInteger(text.c_str(), min, max, out);
}

/// An unsigned base-10 integer in [0, max] without a sign (a 64-bit seed); "-1" is refused, not wrapped.
inline bool parseUnsigned(const char* text, unsigned long long max, unsigned long long& out) {
  if (!detail::startsCleanly(text) || *text == '-' || *text == '+') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || v > max) return false;
  out = v;
  return true;
}

inline bool parseUnsigned(const std::string& text, unsigned long long max, unsigned long long& out) {
  return !detail::hasNul(text) && parseUnsigned(text.c_str(), max, out);
}

}  // namespace visnav::cli
