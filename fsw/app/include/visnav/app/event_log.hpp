// Structured log lines of visnavd on stderr, one event per line as key=value pairs:
//     visnavd t_s=12.400 level=info event=mode_transition frame=62 from=far_range to=acquisition reason="..."
// Under systemd (JOURNAL_STREAM names this stderr) each line starts with the syslog priority "<N>" instead,
// which journald turns into the entry's priority (and strips). A line is formatted into a stack buffer: no
// allocation, no stdio lock.
//
// Where a line goes: until startAsync(), straight to the fd with write(2) (init, --check, tests). After it,
// into a ring of kRingLines lines sized at construction, which a drain thread writes out: a journald or pipe
// that stops reading then never blocks the cycle. A line that finds the ring full is dropped and counted
// (droppedLines()); so is one the drain thread could not write (EPIPE, or the bounded wait at stop ran out).
#pragma once

#include <semaphore.h>

#include <array>
#include <atomic>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

namespace visnav::app {

enum class LogLevel : int { kError = 3, kWarning = 4, kNotice = 5, kInfo = 6 };

class EventLog {
 public:
  static constexpr std::size_t kLineCapacity = 1024;
  /// Lines the ring holds: at 5 Hz and 5 lines per cycle, about 40 s of a stalled reader.
  static constexpr std::size_t kRingLines = 1024;
  /// stopAsync(): longest wait for a stalled reader to take the lines still in the ring.
  static constexpr std::int64_t kStopFlushNs = 2'000'000'000;

  /// `fd`: where lines go (2 = stderr). `journal`: use "<N>" priority prefixes; by default when the
  /// JOURNAL_STREAM environment variable names the device and inode of `fd` (systemd's convention).
  explicit EventLog(int fd = 2);
  EventLog(int fd, bool journal);
  ~EventLog();
  EventLog(const EventLog&) = delete;
  EventLog& operator=(const EventLog&) = delete;

  /// One line: the `event` name, then `fields` (printf format producing "key=value ..." text).
  void event(LogLevel level, const char* event, const char* fields, ...)
      __attribute__((format(printf, 4, 5)));
  void vevent(LogLevel level, const char* event, const char* fields, va_list args)
      __attribute__((format(printf, 4, 0)));

  /// From now on lines go through the ring and the drain thread (init time: starts the thread). False when
  /// the thread could not start (lines then stay synchronous).
  bool startAsync();
  /// Drains the ring (waiting at most `flush_ns` for the reader), stops the thread; lines are synchronous
  /// again. Called by the destructor.
  void stopAsync(std::int64_t flush_ns = kStopFlushNs);
  bool async() const { return m_async.load(std::memory_order_acquire); }

  /// Seconds since the log was created on CLOCK_MONOTONIC (the t_s field).
  double elapsedS() const;
  bool journal() const { return m_journal; }
  /// Lines accepted (written, or queued for the drain thread).
  std::uint64_t linesWritten() const { return m_lines.load(std::memory_order_relaxed); }
  /// Lines lost: the ring was full, or the fd refused them (closed pipe, stalled past the stop flush).
  std::uint64_t droppedLines() const { return m_dropped.load(std::memory_order_relaxed); }

 private:
  struct Line {
    std::size_t length = 0;
    char text[kLineCapacity];
  };
  std::size_t format(char* line, LogLevel level, const char* event, const char* fields, va_list args) const;
  bool writeLine(const char* text, std::size_t length, std::int64_t deadline_ns);
  void drainLoop();
  bool drainOne(std::int64_t deadline_ns);

  int m_fd;
  bool m_journal;
  std::int64_t m_start_ns;
  std::atomic<std::uint64_t> m_lines{0};
  std::atomic<std::uint64_t> m_dropped{0};
  // Ring: producers (serialised by m_produce) advance m_head, the drain thread advances m_tail.
  std::unique_ptr<Line[]> m_ring;
  std::atomic<std::uint64_t> m_head{0};
  std::atomic<std::uint64_t> m_tail{0};
  std::mutex m_produce;
  sem_t m_ready{};
  std::atomic<bool> m_async{false};
  std::atomic<bool> m_stop{false};
  std::int64_t m_stop_deadline_ns = 0;
  std::thread m_drain;
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
