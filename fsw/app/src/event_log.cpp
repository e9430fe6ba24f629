#include "visnav/app/event_log.hpp"

#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <new>

namespace visnav::app {
namespace {

constexpr int kDrainPollMs = 100;  // the drain thread looks at the stop flag this often while it waits

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

EventLog::EventLog(int fd, bool journal) : m_fd(fd), m_journal(journal), m_start_ns(nowNs()) {
  sem_init(&m_ready, 0, 0);
}

EventLog::~EventLog() {
  stopAsync();
  sem_destroy(&m_ready);
}

double EventLog::elapsedS() const { return static_cast<double>(nowNs() - m_start_ns) * 1e-9; }

void EventLog::event(LogLevel level, const char* event, const char* fields, ...) {
  va_list args;
  va_start(args, fields);
  vevent(level, event, fields, args);
  va_end(args);
}

std::size_t EventLog::format(char* line, LogLevel level, const char* event, const char* fields,
                             va_list args) const {
  int used = m_journal ? std::snprintf(line, kLineCapacity, "<%d>event=%s ", static_cast<int>(level), event)
                       : std::snprintf(line, kLineCapacity, "visnavd t_s=%.3f level=%s event=%s ", elapsedS(),
                                       levelName(level), event);
  if (used < 0) return 0;
  if (static_cast<std::size_t>(used) < kLineCapacity) {
    // `args` is started by event() (or the caller of vevent); clang-analyzer's va_list model loses that.
    // NOLINTNEXTLINE(clang-analyzer-valist.Uninitialized)
    const int more =
        std::vsnprintf(line + used, kLineCapacity - static_cast<std::size_t>(used), fields, args);
    if (more > 0) used += more;
  }
  std::size_t length =
      static_cast<std::size_t>(used) < kLineCapacity - 1 ? static_cast<std::size_t>(used) : kLineCapacity - 2;
  while (length > 0 && line[length - 1] == ' ') --length;  // no trailing blank when there are no fields
  line[length++] = '\n';
  return length;
}

void EventLog::vevent(LogLevel level, const char* event, const char* fields, va_list args) {
  if (m_async.load(std::memory_order_acquire)) {
    const std::lock_guard<std::mutex> lock(m_produce);  // producers only: the drain thread never takes it
    const std::uint64_t head = m_head.load(std::memory_order_relaxed);
    if (head - m_tail.load(std::memory_order_acquire) >= kRingLines) {
      m_dropped.fetch_add(1, std::memory_order_relaxed);  // the reader is behind by a whole ring
      return;
    }
    Line& slot = m_ring[head % kRingLines];
    slot.length = format(slot.text, level, event, fields, args);
    m_head.store(head + 1, std::memory_order_release);
    m_lines.fetch_add(1, std::memory_order_relaxed);
    sem_post(&m_ready);
    return;
  }
  char line[kLineCapacity];
  const std::size_t length = format(line, level, event, fields, args);
  std::size_t written = 0;
  for (int attempt = 0; attempt < 8 && written < length; ++attempt) {  // bounded: short writes, EINTR
    const ssize_t n = write(m_fd, line + written, length - written);
    if (n > 0) written += static_cast<std::size_t>(n);
  }
  if (written < length) m_dropped.fetch_add(1, std::memory_order_relaxed);
  m_lines.fetch_add(1, std::memory_order_relaxed);
}

bool EventLog::startAsync() {
  if (m_async.load(std::memory_order_acquire)) return true;
  if (!m_ring) {
    m_ring.reset(new (std::nothrow) Line[kRingLines]);
    if (!m_ring) return false;
  }
  m_stop.store(false, std::memory_order_release);
  try {
    m_drain = std::thread(&EventLog::drainLoop, this);
  } catch (...) {  // std::system_error: no thread, the log stays synchronous
    return false;
  }
  m_async.store(true, std::memory_order_release);
  return true;
}

void EventLog::stopAsync(std::int64_t flush_ns) {
  if (!m_async.load(std::memory_order_acquire)) return;
  m_stop_deadline_ns = nowNs() + flush_ns;
  m_stop.store(true, std::memory_order_release);
  sem_post(&m_ready);
  if (m_drain.joinable()) m_drain.join();
  const std::lock_guard<std::mutex> lock(m_produce);
  // Lines queued after the drain thread's last look: ours now, with what is left of the same wait.
  while (m_tail.load(std::memory_order_relaxed) != m_head.load(std::memory_order_relaxed))
    drainOne(m_stop_deadline_ns);
  m_async.store(false, std::memory_order_release);
}

bool EventLog::writeLine(const char* text, std::size_t length, std::int64_t deadline_ns) {
  std::size_t written = 0;
  while (written < length) {
    // Wait until the fd takes data: forever (checking the stop flag) in normal running, at most until the
    // deadline while stopping. A line is at most 1 KiB, under PIPE_BUF: POLLOUT on a pipe means it fits.
    if (deadline_ns < 0 && m_stop.load(std::memory_order_acquire)) deadline_ns = m_stop_deadline_ns;
    int wait_ms = kDrainPollMs;
    if (deadline_ns >= 0) {
      const std::int64_t left_ns = deadline_ns - nowNs();
      if (left_ns <= 0) return false;
      wait_ms = static_cast<int>(left_ns < kDrainPollMs * 1000000LL ? left_ns / 1000000 + 1 : kDrainPollMs);
    }
    pollfd p{m_fd, POLLOUT, 0};
    const int ready = poll(&p, 1, wait_ms);
    if (ready == 0 || (ready < 0 && errno == EINTR)) continue;
    if (ready < 0 || (p.revents & (POLLERR | POLLNVAL)) != 0) return false;
    const ssize_t n = write(m_fd, text + written, length - written);
    if (n > 0) {
      written += static_cast<std::size_t>(n);
    } else if (n < 0 && errno != EINTR && errno != EAGAIN) {
      return false;  // EPIPE (reader gone: SIGPIPE is ignored by visnavd), EBADF, ...
    }
  }
  return true;
}

bool EventLog::drainOne(std::int64_t deadline_ns) {
  const std::uint64_t tail = m_tail.load(std::memory_order_relaxed);
  if (tail == m_head.load(std::memory_order_acquire)) return false;
  const Line& slot = m_ring[tail % kRingLines];
  if (!writeLine(slot.text, slot.length, deadline_ns)) m_dropped.fetch_add(1, std::memory_order_relaxed);
  m_tail.store(tail + 1, std::memory_order_release);
  return true;
}

void EventLog::drainLoop() {
  for (;;) {
    const bool stopping = m_stop.load(std::memory_order_acquire);
    if (drainOne(stopping ? m_stop_deadline_ns : -1)) continue;
    if (stopping) return;
    timespec until{};
    clock_gettime(CLOCK_MONOTONIC, &until);
    until.tv_nsec += kDrainPollMs * 1000000L;
    if (until.tv_nsec >= 1000000000L) {
      until.tv_nsec -= 1000000000L;
      ++until.tv_sec;
    }
    sem_clockwait(&m_ready, CLOCK_MONOTONIC, &until);  // a new line, the stop request, or a look again
  }
}

}  // namespace visnav::app
