// Binary PGM (P5) reading into a caller-owned buffer and writing. readPgm runs once per replayed frame
// (the replay camera's acquire()): its success path builds no strings and allocates nothing, so it reads
// through a file descriptor and a small stack buffer (fopen would malloc its FILE).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <system_error>

#include "visnav/replay/sequence.hpp"

namespace visnav::replay {
namespace {

struct File {
  std::FILE* f = nullptr;
  ~File() {
    if (f != nullptr) std::fclose(f);
  }
};

// Buffered reading from a descriptor without heap: the header byte by byte, the raster in bulk.
class FdReader {
 public:
  // O_NONBLOCK: a FIFO without a writer must not block the open; the type is checked by regularFile().
  explicit FdReader(const char* path) : m_fd(::open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK)) {}
  ~FdReader() {
    if (m_fd >= 0) ::close(m_fd);
  }
  FdReader(const FdReader&) = delete;
  FdReader& operator=(const FdReader&) = delete;
  bool ok() const { return m_fd >= 0; }
  bool regularFile() const {
    struct stat st {};
    return ::fstat(m_fd, &st) == 0 && S_ISREG(st.st_mode);
  }

  int get() {
    if (m_pos == m_len && !refill()) return EOF;
    return m_buffer[m_pos++];
  }
  /// Reads exactly n bytes (what is buffered first); false when the file ends before.
  bool read(std::uint8_t* out, std::size_t n) {
    const std::size_t buffered = m_len - m_pos < n ? m_len - m_pos : n;
    std::memcpy(out, m_buffer + m_pos, buffered);
    m_pos += buffered;
    std::size_t done = buffered;
    for (int guard = 0; done < n && guard < (1 << 20); ++guard) {
      const ssize_t got = ::read(m_fd, out + done, n - done);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      done += static_cast<std::size_t>(got);
    }
    return done == n;
  }

 private:
  bool refill() {
    for (int attempt = 0; attempt < 16; ++attempt) {
      const ssize_t got = ::read(m_fd, m_buffer, sizeof m_buffer);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      m_pos = 0;
      m_len = static_cast<std::size_t>(got);
      return true;
    }
    return false;
  }

  int m_fd;
  std::uint8_t m_buffer[256] = {};
  std::size_t m_pos = 0;
  std::size_t m_len = 0;
};

bool isSpace(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// Reads one unsigned header integer, skipping whitespace and '#' comments. Consumes the single whitespace
// character that terminates the number (for maxval this is the one byte before the raster).
bool readHeaderInt(FdReader& in, long& out) {
  int c = in.get();
  for (;;) {
    if (c == '#') {
      while (c != '\n' && c != EOF) c = in.get();
    } else if (isSpace(c)) {
      c = in.get();
    } else {
      break;
    }
  }
  if (c < '0' || c > '9') return false;
  long value = 0;
  while (c >= '0' && c <= '9') {
    value = value * 10 + (c - '0');
    if (value > 1000000000L) return false;
    c = in.get();
  }
  if (!isSpace(c)) return false;
  out = value;
  return true;
}

LoadError fail(const std::string& path, const char* problem) {
  return LoadError::failure(path + ": " + problem);
}

}  // namespace

LoadError readPgm(const std::string& path, std::uint8_t* buffer, std::size_t capacity_bytes, int& width,
                  int& height, int& maxval, int expected_maxval) {
  FdReader in(path.c_str());
  if (!in.ok())
    return LoadError::failure(path + ": cannot open file: " + std::generic_category().message(errno));
  if (!in.regularFile()) return fail(path, "not a regular file");
  if (in.get() != 'P' || in.get() != '5') return fail(path, "not a binary PGM (P5)");
  long w = 0;
  long h = 0;
  long m = 0;
  if (!readHeaderInt(in, w) || !readHeaderInt(in, h) || !readHeaderInt(in, m)) {
    return fail(path, "malformed PGM header");
  }
  if (w <= 0 || h <= 0 || w > 65536 || h > 65536) return fail(path, "invalid PGM width/height");
  if (m <= 0 || m > 65535) return fail(path, "PGM maxval must be in [1, 65535]");
  if (expected_maxval > 0 && m != expected_maxval)
    return LoadError::failure(path + ": PGM maxval " + std::to_string(m) +
                              " differs from the sequence's max_code " + std::to_string(expected_maxval));
  const std::size_t bytes_per_sample = m > 255 ? 2U : 1U;
  const std::size_t samples = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  const std::size_t bytes = samples * bytes_per_sample;
  if (buffer == nullptr || bytes > capacity_bytes)
    return LoadError::failure(path + ": image " + std::to_string(w) + "x" + std::to_string(h) + " with " +
                              std::to_string(bytes_per_sample) + "-byte samples needs " +
                              std::to_string(bytes) + " bytes, the buffer holds " +
                              std::to_string(buffer == nullptr ? 0 : capacity_bytes) +
                              " (is the frame bigger than the camera?)");
  if (!in.read(buffer, bytes)) return fail(path, "truncated PGM raster");
  if (in.get() != EOF) return fail(path, "trailing bytes after the PGM raster");
  if (bytes_per_sample == 2U) {
    // Big-endian on disk -> host order, in place, via memcpy to stay alignment- and aliasing-safe.
    for (std::size_t i = 0; i < samples; ++i) {
      const std::uint8_t* p = buffer + 2U * i;
      const auto value = static_cast<std::uint16_t>((p[0] << 8U) | p[1]);
      std::memcpy(buffer + 2U * i, &value, sizeof value);
    }
  }
  width = static_cast<int>(w);
  height = static_cast<int>(h);
  maxval = static_cast<int>(m);
  return LoadError::success();
}

LoadError writePgm8(const std::string& path, const ImageView8& image) {
  if (image.empty()) return fail(path, "empty image");
  File file;
  file.f = std::fopen(path.c_str(), "wb");
  if (file.f == nullptr) return fail(path, "cannot create file");
  std::fprintf(file.f, "P5\n%d %d\n255\n", image.width(), image.height());
  const auto w = static_cast<std::size_t>(image.width());
  for (int y = 0; y < image.height(); ++y) {
    if (std::fwrite(image.row(y), 1, w, file.f) != w) return fail(path, "write failed");
  }
  if (std::fflush(file.f) != 0) return fail(path, "write failed");
  return LoadError::success();
}

LoadError writePgm16(const std::string& path, const ImageView16& image, std::uint16_t maxval) {
  if (image.empty()) return fail(path, "empty image");
  if (maxval == 0U) return fail(path, "maxval must be >= 1");
  File file;
  file.f = std::fopen(path.c_str(), "wb");
  if (file.f == nullptr) return fail(path, "cannot create file");
  std::fprintf(file.f, "P5\n%d %d\n%u\n", image.width(), image.height(), static_cast<unsigned>(maxval));
  // 16-bit PGM is big-endian; a PGM with maxval < 256 has 1-byte samples, so those are written narrow.
  const bool wide = maxval > 255U;
  std::uint8_t chunk[4096];
  const std::size_t per_chunk = wide ? sizeof chunk / 2U : sizeof chunk;
  for (int y = 0; y < image.height(); ++y) {
    const std::uint16_t* row = image.row(y);
    for (std::size_t x0 = 0; x0 < static_cast<std::size_t>(image.width()); x0 += per_chunk) {
      std::size_t n = static_cast<std::size_t>(image.width()) - x0;
      if (n > per_chunk) n = per_chunk;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint16_t v = row[x0 + i] > maxval ? maxval : row[x0 + i];
        if (wide) {
          chunk[2U * i] = static_cast<std::uint8_t>(v >> 8U);
          chunk[2U * i + 1U] = static_cast<std::uint8_t>(v & 0xFFU);
        } else {
          chunk[i] = static_cast<std::uint8_t>(v);
        }
      }
      const std::size_t bytes = wide ? 2U * n : n;
      if (std::fwrite(chunk, 1, bytes, file.f) != bytes) return fail(path, "write failed");
    }
  }
  if (std::fflush(file.f) != 0) return fail(path, "write failed");
  return LoadError::success();
}

}  // namespace visnav::replay
