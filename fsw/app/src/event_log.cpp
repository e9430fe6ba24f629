#include "visnav/app/event_log.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace visnav::app {
namespace {

std::int64_t nowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

const char* levelName(LogLevel level) {
  switch (level) {
    case LogLevel::kError: return "error";
    case LogLevel::kWarning: return "warning";
    case LogLevel::kNotice: return "notice";
    case LogLevel::kInfo: return "info";
  }
  return "info";
}

}  // namespace

bool isJournalStream(int fd) {
  const char* stream = std::getenv("JOURNAL_STREAM");
  if (stream == nullptr) return false;
  unsigned long long device = 0;
  unsigned long long inode = 0;
  if (std::sscanf(stream, "%llu:%llu", &device, &inode) != 2) return false;
  struct stat st {};
  if (fstat(fd, &st) != 0) return false;
  return static_cast<unsigned long long>(st.st_dev) == device &&
         static_cast<unsigned long long>(st.st_ino) == inode;
}

EventLog::EventLog(int fd) : EventLog(fd, isJournalStream(fd)) {}

EventLog::EventLog(int fd, bool journal) : m_fd(fd), m_journal(journal), m_start_ns(nowNs()) {}

double EventLog::elapsedS() const { return static_cast<double>(nowNs() - m_start_ns) * 1e-9; }

void EventLog::event(LogLevel level, const char* event, const char* fields, ...) {
  va_list args;
  va_start(args, fields);
  vevent(level, event, fields, args);
  va_end(args);
}

void EventLog::vevent(LogLevel level, const char* event, const char* fields, va_list args) {
  char line[kLineCapacity];
  int used = m_journal ? std::snprintf(line, sizeof(line), "<%d>event=%s ", static_cast<int>(level), event)
                       : std::snprintf(line, sizeof(line), "visnavd t_s=%.3f level=%s event=%s ", elapsedS(),
                                       levelName(level), event);
  if (used < 0) return;
  if (static_cast<std::size_t>(used) < sizeof(line)) {
    // `args` is started by event() (or the caller of vevent); clang-analyzer's va_list model loses that.
    // NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized)
    const int more = std::vsnprintf(line + used, sizeof(line) - static_cast<std::size_t>(used), fields, args);
    if (more > 0) used += more;
  }
  std::size_t length =
      static_cast<std::size_t>(used) < sizeof(line) - 1 ? static_cast<std::size_t>(used) : sizeof(line) - 2;
  while (length > 0 && line[length - 1] == ' ') --length;  // no trailing blank when there are no fields
  line[length++] = '\n';
  std::size_t written = 0;
  for (int attempt = 0; attempt < 8 && written < length; ++attempt) {  // bounded: short writes, EINTR
    const ssize_t n = write(m_fd, line + written, length - written);
    if (n > 0) written += static_cast<std::size_t>(n);
  }
  ++m_lines;
}

}  // namespace visnav::app
