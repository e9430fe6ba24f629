// visnav/cli/numbers.hpp: the one parser of the ground tools' numeric arguments. Whole argument or nothing,
// finite, base-10 integers within their range, and `out` untouched on a refusal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "visnav/cli/numbers.hpp"

namespace visnav::cli {
namespace {

constexpr double kUntouched = -12345.0;
constexpr long long kUntouchedInt = -777;
constexpr long long kMin = std::numeric_limits<long long>::min();
constexpr long long kMax = std::numeric_limits<long long>::max();

/// "a" NUL "b": a std::string that the char* parsers would read as "a" alone.
std::string withNul(const char* a, const char* b) { return std::string(a) + '\0' + b; }

bool number(const char* text, double& out) {
  out = kUntouched;
  return parseNumber(text, out);
}

bool refusedNumber(const char* text) {
  double out = kUntouched;
  const bool ok = parseNumber(text, out);
  EXPECT_EQ(out, kUntouched) << "'" << text << "' changed the output on a refusal";
  return !ok;
}

bool refusedInteger(const char* text, long long min = kMin, long long max = kMax) {
  long long out = kUntouchedInt;
  const bool ok = parseInteger(text, min, max, out);
  EXPECT_EQ(out, kUntouchedInt) << "'" << text << "' changed the output on a refusal";
  return !ok;
}

TEST(CliNumbers, NumberAcceptsPlainAndScientificNotation) {
  double x = 0.0;
  ASSERT_TRUE(number("0", x));
  EXPECT_EQ(x, 0.0);
  ASSERT_TRUE(number("1e-6", x));
  EXPECT_EQ(x, 1e-6);
  ASSERT_TRUE(number("-2.5", x));
  EXPECT_EQ(x, -2.5);
  ASSERT_TRUE(number("+3", x));
  EXPECT_EQ(x, 3.0);
  ASSERT_TRUE(number(".5", x));
  EXPECT_EQ(x, 0.5);
  ASSERT_TRUE(number("750", x));
  EXPECT_EQ(x, 750.0);
  ASSERT_TRUE(number("1.7976931348623157e308", x));  // DBL_MAX itself is no overflow
  EXPECT_EQ(x, std::numeric_limits<double>::max());
}

TEST(CliNumbers, NumberRefusesEmptyBlanksAndTrailingCharacters) {
  EXPECT_TRUE(refusedNumber(nullptr));
  EXPECT_TRUE(refusedNumber(""));
  EXPECT_TRUE(refusedNumber(" "));
  EXPECT_TRUE(refusedNumber(" 1"));  // strtod alone would skip the blank
  EXPECT_TRUE(refusedNumber("\t1"));
  EXPECT_TRUE(refusedNumber("\n1"));
  EXPECT_TRUE(refusedNumber("1 "));
  EXPECT_TRUE(refusedNumber("1x"));
  EXPECT_TRUE(refusedNumber("1e3x"));
  EXPECT_TRUE(refusedNumber("1e"));
  EXPECT_TRUE(refusedNumber("x"));
  EXPECT_TRUE(refusedNumber("-"));
  EXPECT_TRUE(refusedNumber("."));
  EXPECT_TRUE(refusedNumber("1,5"));  // the "C" locale's decimal point is '.'
  EXPECT_TRUE(refusedNumber("1.5.2"));
}

TEST(CliNumbers, NumberRefusesNonFiniteAndOverflow) {
  EXPECT_TRUE(refusedNumber("nan"));
  EXPECT_TRUE(refusedNumber("NAN"));
  EXPECT_TRUE(refusedNumber("-nan"));
  EXPECT_TRUE(refusedNumber("nan(123)"));
  EXPECT_TRUE(refusedNumber("inf"));
  EXPECT_TRUE(refusedNumber("-inf"));
  EXPECT_TRUE(refusedNumber("Infinity"));
  EXPECT_TRUE(refusedNumber("1e999"));
  EXPECT_TRUE(refusedNumber("-1e999"));
  EXPECT_TRUE(refusedNumber("1.8e308"));
}

TEST(CliNumbers, NumberUnderflowIsTheNearestDouble) {
  double x = kUntouched;
  ASSERT_TRUE(number("1e-400", x));  // strtod: ERANGE, 0; a tolerance that small is 0
  EXPECT_EQ(x, 0.0);
  ASSERT_TRUE(number("-1e-400", x));
  EXPECT_EQ(x, 0.0);
  ASSERT_TRUE(number("4e-320", x));  // subnormal
  EXPECT_GT(x, 0.0);
  EXPECT_LT(x, std::numeric_limits<double>::min());
}

TEST(CliNumbers, NumberStringOverloadIsTheSame) {
  double x = kUntouched;
  ASSERT_TRUE(parseNumber(std::string("0.25"), x));
  EXPECT_EQ(x, 0.25);
  x = kUntouched;
  EXPECT_FALSE(parseNumber(std::string(""), x));
  EXPECT_FALSE(parseNumber(std::string("1x"), x));
  EXPECT_FALSE(parseNumber(std::string("nan"), x));
  EXPECT_FALSE(parseNumber(withNul("1", "5"), x));  // not read as "1"
  EXPECT_EQ(x, kUntouched);
}

TEST(CliNumbers, IntegerAcceptsBase10WithinRange) {
  long long n = 0;
  ASSERT_TRUE(parseInteger("42", 0, 100, n));
  EXPECT_EQ(n, 42);
  ASSERT_TRUE(parseInteger("-1", -1, 1023, n));
  EXPECT_EQ(n, -1);
  ASSERT_TRUE(parseInteger("+7", 0, 10, n));
  EXPECT_EQ(n, 7);
  ASSERT_TRUE(parseInteger("010", 0, 100, n));  // base 10, not octal
  EXPECT_EQ(n, 10);
  ASSERT_TRUE(parseInteger("9223372036854775807", kMin, kMax, n));
  EXPECT_EQ(n, kMax);
  ASSERT_TRUE(parseInteger("-9223372036854775808", kMin, kMax, n));
  EXPECT_EQ(n, kMin);
}

TEST(CliNumbers, IntegerRangeLimitsAreInclusive) {
  long long n = 0;
  EXPECT_TRUE(parseInteger("1", 1, 1000000000, n));
  EXPECT_TRUE(parseInteger("1000000000", 1, 1000000000, n));
  EXPECT_TRUE(refusedInteger("0", 1, 1000000000));
  EXPECT_TRUE(refusedInteger("1000000001", 1, 1000000000));
  EXPECT_TRUE(refusedInteger("-3", 1, 1000000000));
  EXPECT_TRUE(parseInteger("232", 0, 232, n));
  EXPECT_TRUE(refusedInteger("233", 0, 232));
  EXPECT_TRUE(refusedInteger("-1", 0, 232));
  EXPECT_TRUE(parseInteger("4294967295", 1, 0xFFFFFFFFLL, n));
  EXPECT_EQ(n, 4294967295LL);
  EXPECT_TRUE(refusedInteger("-4294967295", 1, 0xFFFFFFFFLL));  // strtoull would wrap this to 1
}

TEST(CliNumbers, IntegerRefusesFractionsExponentsAndJunk) {
  EXPECT_TRUE(refusedInteger(nullptr));
  EXPECT_TRUE(refusedInteger(""));
  EXPECT_TRUE(refusedInteger(" 3"));
  EXPECT_TRUE(refusedInteger("3 "));
  EXPECT_TRUE(refusedInteger("3.0"));
  EXPECT_TRUE(refusedInteger("1.5"));
  EXPECT_TRUE(refusedInteger("1e3"));
  EXPECT_TRUE(refusedInteger("10x"));
  EXPECT_TRUE(refusedInteger("0x10"));
  EXPECT_TRUE(refusedInteger("nan"));
  EXPECT_TRUE(refusedInteger("inf"));
  EXPECT_TRUE(refusedInteger("-"));
  EXPECT_TRUE(refusedInteger("+"));
}

TEST(CliNumbers, IntegerRefusesOverflow) {
  EXPECT_TRUE(refusedInteger("9223372036854775808"));  // LLONG_MAX + 1: ERANGE, not clamped
  EXPECT_TRUE(refusedInteger("-9223372036854775809"));
  EXPECT_TRUE(refusedInteger("99999999999999999999"));
  long long n = kUntouchedInt;
  EXPECT_FALSE(parseInteger(std::string("99999999999999999999"), 0, kMax, n));
  EXPECT_FALSE(parseInteger(withNul("5", "0"), 0, kMax, n));
  EXPECT_EQ(n, kUntouchedInt);
  ASSERT_TRUE(parseInteger(std::string("50"), 0, kMax, n));
  EXPECT_EQ(n, 50);
}

TEST(CliNumbers, UnsignedTakesTheWhole64BitsAndNoSign) {
  constexpr unsigned long long kU64Max = std::numeric_limits<std::uint64_t>::max();
  unsigned long long u = 0;
  ASSERT_TRUE(parseUnsigned("18446744073709551615", kU64Max, u));
  EXPECT_EQ(u, kU64Max);
  ASSERT_TRUE(parseUnsigned("0", kU64Max, u));
  EXPECT_EQ(u, 0u);
  u = 99;
  EXPECT_FALSE(parseUnsigned("18446744073709551616", kU64Max, u));  // overflow
  EXPECT_FALSE(parseUnsigned("-1", kU64Max, u));                    // strtoull: 2^64 - 1
  EXPECT_FALSE(parseUnsigned("+1", kU64Max, u));
  EXPECT_FALSE(parseUnsigned(" 1", kU64Max, u));
  EXPECT_FALSE(parseUnsigned(" -1", kU64Max, u));
  EXPECT_FALSE(parseUnsigned("1.0", kU64Max, u));
  EXPECT_FALSE(parseUnsigned("", kU64Max, u));
  EXPECT_FALSE(parseUnsigned("11", 10, u));
  EXPECT_FALSE(parseUnsigned(withNul("1", "1"), kU64Max, u));
  EXPECT_EQ(u, 99u);
  ASSERT_TRUE(parseUnsigned(std::string("10"), 10, u));
  EXPECT_EQ(u, 10u);
}

}  // namespace
}  // namespace visnav::cli
