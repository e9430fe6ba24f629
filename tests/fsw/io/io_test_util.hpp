// Temporary files for the fsw/io tests.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <string>

namespace visnav::io::test {

/// A fresh directory under gtest's TempDir, one per call.
inline std::string makeTempDir() {
  std::string pattern = ::testing::TempDir() + "visnav_io_XXXXXX";
  const char* dir = mkdtemp(pattern.data());
  EXPECT_NE(dir, nullptr);
  return dir == nullptr ? ::testing::TempDir() : std::string(dir) + "/";
}

inline std::string writeFile(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + name;
  std::ofstream(path) << text;
  return path;
}

inline std::string sourcePath(const std::string& relative) {
  return std::string(VISNAV_SOURCE_DIR) + "/" + relative;
}

/// A bad file's message names the file, the line (0: no line expected) and the problem.
inline void expectError(const std::string& message, const std::string& path, int line,
                        const std::string& word) {
  EXPECT_NE(message.find(path), std::string::npos) << message;
  if (line > 0) {
    EXPECT_NE(message.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << message;
  }
  EXPECT_NE(message.find(word), std::string::npos) << message << "  (expected '" << word << "')";
}

}  // namespace visnav::io::test
