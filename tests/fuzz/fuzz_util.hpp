// Shared by the fuzz targets (tests/fuzz/README.md): the parsers under test take paths, so each input is
// written to a file in a scratch directory of its own process (under $TMPDIR: scripts/fuzz.sh points it
// into build/fuzz), removed again at exit.
#pragma once

#include <stdlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace visnav::fuzz {

class Scratch {
 public:
  Scratch() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/visnav-fuzz-XXXXXX";
    if (mkdtemp(pattern.data()) == nullptr) std::abort();
    m_dir = pattern + "/";
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(m_dir, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  const std::string& dir() const { return m_dir; }

 private:
  std::string m_dir;
};

inline const std::string& scratchDir() {
  static const Scratch scratch;
  return scratch.dir();
}

/// Writes `size` bytes to <scratch>/<name> (truncating) and returns the path.
inline std::string writeFile(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratchDir() + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  return path;
}

inline std::string writeFile(const std::string& name, const std::string& text) {
  return writeFile(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

}  // namespace visnav::fuzz
