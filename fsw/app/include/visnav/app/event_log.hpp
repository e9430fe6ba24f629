// Structured log lines of visnavd on stderr, one event per line as key=value pairs:
//     visnavd t_s=12.400 level=info event=mode_transition frame=62 from=far_range to=acquisition reason="..."
// Under systemd (JOURNAL_STREAM names this stderr) each line starts with the syslog priority "<N>" instead,
// which journald turns into the entry's priority (and strips). A line is formatted into a stack buffer and
// written with one write(2): no allocation, no stdio lock, so it may be called from the cycle. Lines longer
// than the buffer are truncated.
#pragma once

#include <array>
#include <cstdarg>
#include <cstddef>
#include <cstdint>

namespace visnav::app {

enum class LogLevel : int { kError = 3, kWarning = 4, kNotice = 5, kInfo = 6 };

class EventLog {
 public:
  static constexpr std::size_t kLineCapacity = 1024;

  /// `fd`: where lines go (2 = stderr). `journal`: use "<N>" priority prefixes; by default when the
  /// JOURNAL_STREAM environment variable names the device and inode of `fd` (systemd's convention).
  explicit EventLog(int fd = 2);
  EventLog(int fd, bool journal);

  /// One line: the `event` name, then `fields` (printf format producing "key=value ..." text).
  void event(LogLevel level, const char* event, const char* fields, ...)
      __attribute__((format(printf, 4, 5)));
  void vevent(LogLevel level, const char* event, const char* fields, va_list args)
      __attribute__((format(printf, 4, 0)));

  /// Seconds since the log was created on CLOCK_MONOTONIC (the t_s field).
  double elapsedS() const;
  bool journal() const { return m_journal; }
  std::uint64_t linesWritten() const { return m_lines; }

 private:
  int m_fd;
  bool m_journal;
  std::int64_t m_start_ns;
  std::uint64_t m_lines = 0;
};

/// True when JOURNAL_STREAM ("device:inode") names the file `fd` is open on.
bool isJournalStream(int fd);

/// Copies `text` for use inside a double-quoted value: '"' becomes '\'', control characters become ' '.
/// Always NUL-terminates; truncates.
template <std::size_t N>
const char* quotable(const char* text, std::array<char, N>& out) {
  std::size_t i = 0;
  for (; text != nullptr && text[i] != '\0' && i + 1 < N; ++i) {
    const char c = text[i];
    out[i] = c == '"' ? '\'' : (static_cast<unsigned char>(c) < 0x20 ? ' ' : c);
  }
  out[i] = '\0';
  return out.data();
}

}  // namespace visnav::app
