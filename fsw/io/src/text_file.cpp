#include "visnav/io/text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace visnav::io {
namespace {

std::string errnoText(int error) { return std::generic_category().message(error); }

const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

LoadError checkStat(const std::string& path, const struct stat& st, std::size_t max_bytes) {
  if (!S_ISREG(st.st_mode))
    return LoadError::failure(path + ": not a regular file (" + fileKind(st.st_mode) + ")");
  if (static_cast<unsigned long long>(st.st_size) > max_bytes)
    return LoadError::failure(path + ": " + std::to_string(st.st_size) + " bytes, larger than the limit of " +
                              std::to_string(max_bytes) + " bytes for an input file");
  return LoadError::success();
}

class Fd {
 public:
  explicit Fd(int fd) : m_fd(fd) {}
  ~Fd() {
    if (m_fd >= 0) ::close(m_fd);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return m_fd; }

 private:
  int m_fd;
};

}  // namespace

LoadError checkRegularFile(const std::string& path, std::size_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return LoadError::failure(path + ": cannot open: " + errnoText(errno));
  return checkStat(path, st, max_bytes);
}

LoadError readTextFile(const std::string& path, std::string& text, std::size_t max_bytes) {
  // O_NONBLOCK: opening a FIFO without a writer would block; the type is checked on the open descriptor
  // (no window between a stat and the open).
  const Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK));
  if (fd.get() < 0) return LoadError::failure(path + ": cannot open: " + errnoText(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) return LoadError::failure(path + ": cannot stat: " + errnoText(errno));
  if (LoadError e = checkStat(path, st, max_bytes); !e.ok) return e;
  std::string content;
  content.resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  // The size is a hint only (a file may change while read): read up to the limit + 1 byte to notice growth.
  while (done <= max_bytes) {
    if (done == content.size()) content.resize(done + 4096 > max_bytes + 1 ? max_bytes + 1 : done + 4096);
    const ssize_t got = ::read(fd.get(), &content[done], content.size() - done);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return LoadError::failure(path + ": read failed: " + errnoText(errno));
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  if (done > max_bytes)
    return LoadError::failure(path + ": larger than the limit of " + std::to_string(max_bytes) +
                              " bytes for an input file");
  content.resize(done);
  text = std::move(content);
  return LoadError::success();
}

LoadError checkTomlAscii(const std::string& path, const std::string& text) {
  // Bytes first: only printable ASCII, tab and line ends reach toml++. Its undefined behaviour on non-ASCII
  // input sits in Unicode tables that strings, escapes, bare values and keys all reach; a guard that allowed
  // non-ASCII inside strings had to follow toml++'s lexer exactly, and the fuzzer kept finding places where
  // it did not (six inputs over two long runs, the last three on 2026-11-25). visnav's files are ASCII.
  {
    int line = 1;
    int column = 0;
    for (const char ch : text) {
      const auto b = static_cast<unsigned char>(ch);
      if (b == '\n') {
        ++line;
        column = 0;
        continue;
      }
      ++column;
      const auto where = [&path, &line, &column] {
        return path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
      };
      if (b >= 0x80U)
        return LoadError::failure(where() +
                                  "non-ASCII character (visnav's TOML files are ASCII: toml++ 3.3.0 "
                                  "has undefined behaviour on some non-ASCII input)");
      if ((b < 0x20U && b != '\t' && b != '\r') || b == 0x7FU)
        return LoadError::failure(where() + "control character (TOML allows none but tab)");
    }
  }
  enum class State { kPlain, kComment, kBasic, kLiteral, kMultiBasic, kMultiLiteral };
  State state = State::kPlain;
  int line = 1;
  int column = 0;
  // Last non-blank character outside strings and comments ('\n' at a line start): a quote opens a string
  // only where one can begin (after = [ { , . or first on a line). Elsewhere it is part of a bare value that
  // toml++ scans on past the quote: a quote after "a = x" followed by U+FCFF reached its unreachable branch.
  char previous = '\n';
  std::string nesting;  // the [ and { of values still open: a "[" first on a line outside all opens a header
  bool line_has_text = false;  // a non-blank character before this one on the line
  const std::size_t n = text.size();
  const auto triple = [&text, n](std::size_t i, char q) {
    return i + 2 < n && text[i] == q && text[i + 1] == q && text[i + 2] == q;
  };
  const auto failAt = [&path, &line](int col, const char* problem) {
    return LoadError::failure(path + ":" + std::to_string(line) + ":" + std::to_string(col) + ": " + problem);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      column = 0;
      line_has_text = false;
      // Comments and single-line strings end at the line end (an unterminated string is toml++'s error).
      if (state == State::kComment || state == State::kBasic || state == State::kLiteral)
        state = State::kPlain;
      if (state == State::kPlain) previous = '\n';
      continue;
    }
    ++column;
    switch (state) {
      case State::kPlain: {
        const bool first_on_line = !line_has_text;
        if (c != ' ' && c != '\t') line_has_text = true;
        if (c == '[' && first_on_line && nesting.empty()) {
          // toml++ 3.3.0 assumes (TOML_ASSERT_ASSUME, undefined behaviour when false) that a table header's
          // first character after '[' or '[[' and blanks starts a key: "[!]" reached it.
          std::size_t k = i + 1;
          if (k < n && text[k] == '[') ++k;
          while (k < n && (text[k] == ' ' || text[k] == '\t')) ++k;
          const char h = k < n ? text[k] : '\0';
          const bool key_start = (h >= 'A' && h <= 'Z') || (h >= 'a' && h <= 'z') || (h >= '0' && h <= '9') ||
                                 h == '_' || h == '-' || h == '"' || h == '\'' || h == ']';
          if (!key_start) return failAt(column, "table header must start with a key ([name] or [\"name\"])");
          break;  // the header's own brackets are not value nesting
        }
        // toml++ 3.3.0 also assumes that a '}' never stands where an array expects a value ("a = [}").
        if (c == '}' && !nesting.empty() && nesting.back() == '[')
          return failAt(column, "'}' inside an array (no inline table is open)");
        if (c == '[' || c == '{') nesting.push_back(c);
        if ((c == ']' || c == '}') && !nesting.empty()) nesting.pop_back();
        const bool string_may_start = previous == '\n' || previous == '=' || previous == '[' ||
                                      previous == '{' || previous == ',' || previous == '.';
        // A multi-line string is a value only: where a key stands, '"""' is an empty key and a quote.
        const bool value_may_start =
            previous == '=' || ((previous == '[' || previous == ',' || previous == '\n') &&
                                !nesting.empty() && nesting.back() == '[');
        if (c != ' ' && c != '\t') previous = c;
        if (c == '#') {
          state = State::kComment;
        } else if ((c == '"' || c == '\'') && !string_may_start) {
          // part of a bare value: stays plain, so what follows it is checked too
        } else if (value_may_start && triple(i, '"')) {
          state = State::kMultiBasic;
          i += 2;
          column += 2;
        } else if (value_may_start && triple(i, '\'')) {
          state = State::kMultiLiteral;
          i += 2;
          column += 2;
        } else if (c == '"') {
          state = State::kBasic;
        } else if (c == '\'') {
          state = State::kLiteral;
        }
        break;
      }
      case State::kComment: break;
      case State::kBasic:
        if (c == '\\' && i + 1 < n && text[i + 1] != '\n') {
          ++i;
          ++column;
        } else if (c == '"') {
          state = State::kPlain;
        }
        break;
      case State::kLiteral:
        if (c == '\'') state = State::kPlain;
        break;
      case State::kMultiBasic:
      case State::kMultiLiteral: {
        const char quote = state == State::kMultiBasic ? '"' : '\'';
        if (state == State::kMultiBasic && c == '\\' && i + 1 < n) {
          if (text[i + 1] == '\n') continue;  // line-ending backslash: the newline is counted next round
          ++i;
          ++column;
        } else if (triple(i, quote)) {
          // Up to two more quotes right before the closing three belong to the string ("""a""""").
          std::size_t run = 3;
          while (run < 5 && i + run < n && text[i + run] == quote) ++run;
          i += run - 1;
          column += static_cast<int>(run) - 1;
          state = State::kPlain;
        }
        break;
      }
    }
  }
  return LoadError::success();
}

}  // namespace visnav::io
