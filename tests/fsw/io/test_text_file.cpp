// Bounded file reading and the TOML text guard shared by every loader (issue 13, items 10 and 12).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>

#include "io_test_util.hpp"
#include "visnav/io/text_file.hpp"

namespace visnav::io {
namespace {

using test::makeTempDir;
using test::writeFile;

TEST(TextFile, ReadsARegularFile) {
  const std::string path = writeFile(makeTempDir(), "a.txt", "hello\n");
  std::string text;
  const LoadError e = readTextFile(path, text);
  ASSERT_TRUE(e.ok) << e.message;
  EXPECT_EQ(text, "hello\n");
}

TEST(TextFile, RejectsDevicesFifosDirectoriesAndLinksToThem) {
  const std::string dir = makeTempDir();
  std::string text;
  LoadError e = readTextFile("/dev/zero", text);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("/dev/zero: not a regular file (a character device)"), std::string::npos)
      << e.message;
  ASSERT_EQ(::symlink("/dev/zero", (dir + "model.cao").c_str()), 0);
  e = readTextFile(dir + "model.cao", text);
  EXPECT_NE(e.message.find("not a regular file"), std::string::npos) << e.message;
  ASSERT_EQ(::mkfifo((dir + "fifo.toml").c_str(), 0600), 0);
  e = readTextFile(dir + "fifo.toml", text);  // must not block waiting for a writer
  EXPECT_NE(e.message.find("not a regular file (a FIFO)"), std::string::npos) << e.message;
  e = readTextFile(dir, text);
  EXPECT_NE(e.message.find("not a regular file (a directory)"), std::string::npos) << e.message;
  e = checkRegularFile("/dev/urandom");
  EXPECT_FALSE(e.ok);
}

TEST(TextFile, MissingFileNamesTheErrno) {
  std::string text;
  const LoadError e = readTextFile("/nonexistent/visnav.toml", text);
  EXPECT_EQ(e.message, "/nonexistent/visnav.toml: cannot open: No such file or directory");
}

TEST(TextFile, SizeIsBounded) {
  const std::string path = writeFile(makeTempDir(), "big.txt", std::string(1000, 'x'));
  std::string text;
  EXPECT_TRUE(readTextFile(path, text, 1000).ok);
  const LoadError e = readTextFile(path, text, 999);
  EXPECT_FALSE(e.ok);
  EXPECT_NE(e.message.find("1000 bytes, larger than the limit of 999"), std::string::npos) << e.message;
}

TEST(TomlAscii, OnlyAsciiReachesToml) {
  EXPECT_EQ(checkTomlAscii("f", "\xc3\xa9 = 1\n").message,
            "f:1:1: non-ASCII character (visnav's TOML files are ASCII: toml++ 3.3.0 has undefined behaviour "
            "on some non-ASCII input)");
  EXPECT_EQ(checkTomlAscii("f", "a = 1\n\x7f").message,
            "f:2:1: control character (TOML allows none but tab)");
  const char* good[] = {
      "a = \"x\" # comment\r\n\tb = 'y'\n",
      "a = \"\"\"x\"\"\"\"\nb = 1\n",  // one extra quote before the closing three belongs to the string
      "c = { d = [1], e = { f = 2 } }\na = [\n  [{ x = 1 }],\n  [+1, \"]\"],\n]\n[t]\n[[u]]\n[ \"v\" "
      "]\n",  // arrays at a line start are values
  };
  for (const char* text : good) EXPECT_TRUE(checkTomlAscii("f", text).ok) << text;
  const struct {
    const char* text;
    const char* where;
  } bad[] = {
      // Non-ASCII anywhere, strings and comments included (they were allowed until the fuzzer found the
      // last three entries below inside them).
      {"a = \"\xc3\xa9\" # x\n", "f:1:6:"},
      {"a = 1 # \xc3\xa9\n", "f:1:9:"},
      {"a = '''\n\xc3\xa9\n'''\n", "f:2:1:"},
      {"a = 1\nb\xc3\xa9 = 2\n", "f:2:2:"},
      {"a = \"x\"\xc3\xa9\n", "f:1:8:"},
      {"a = \"\"\"x\"\"\"\xc3\xa9\n", "f:1:12:"},
      {"a = \"unterminated\n\xc3\xa9 = 1\n", "f:2:1:"},  // a basic string ends at the line end
      {"[t\xc3\xa9]\n", "f:1:3:"},
      // Found by fuzz_camera_toml: toml++ 3.3.0's parse_key assumes a key after '[' (undefined behaviour).
      {"[!]\n", "f:1:1:"},
      {"a = 1\n  [[ \x01]]\n", "f:2:6:"},  // a control character
      {"[\n", "f:1:1:"},
      // Found by fuzz_camera_toml: parse_value assumes no '}' where an array expects a value.
      {"a = [}\n", "f:1:6:"},
      // Found by fuzz_camera_toml: a quote inside a bare value opens no string; toml++ scans on past it.
      {"k2 = -zameigA'''era\xef\xb3\xbf'\n", "f:1:20:"},
      {"a = 1\"\xc3\xa9\"\n", "f:1:7:"},
      // Found by fuzz_config: where a key stands, three quotes are an empty key and a quote, not a string.
      {"\"\"\"@\"@\"\"r\n[v\xd2\x92]\n", "f:2:3:"},
      // Found by fuzz_camera_toml: toml++ tests what follows a backslash with its Unicode whitespace tables.
      {"a = [\"\"\"x\\\\\\\xef\xbb\xbd\"\"\"]\n", "f:1:"},
      {"a = \"\"\"x\\  \n  \xc3\xa9\"\"\"\n", "f:2:3:"},
      {"a = \"x\\\xc3\xa9\"\n", "f:1:"},
      {"a = {b = [1, # c\n}]}\n", "f:2:1:"},
      // Found by the long fuzz run of 2026-11-25 (tests/fuzz/corpus/*/regress-long-run-2026-11-25.toml):
      // a NUL inside a bare value then a quote and U+FEFD; three quotes where a key stands, then non-ASCII
      // after a backslash; NULs, quotes and a BOM after an array header. (\x01 stands for the NULs here:
      // a C string ends at a NUL; the corpus files keep them.)
      {"k2 = -\x01\\\\'\\\"\xef\xbb\xbd\n", "f:1:7:"},
      {"\"\"\"@\"@\"\"z\\\xd2\x92jc]\n", "f:1:11:"},
      {"foth = 8\x01\"\"\"[[['\xef\xbb\x9f\n", "f:1:9:"},
  };
  for (const auto& c : bad) {
    const LoadError e = checkTomlAscii("f", c.text);
    EXPECT_FALSE(e.ok) << c.text;
    EXPECT_EQ(e.message.rfind(c.where, 0), 0U) << e.message << " expected " << c.where;
  }
}

}  // namespace
}  // namespace visnav::io
