// The daemon's log lines (key=value, journald priority prefix) and the sd_notify protocol against a real
// AF_UNIX datagram socket standing in for systemd.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "../../support/alloc_counter.hpp"
#include "visnav/app/daemon.hpp"
#include "visnav/app/event_log.hpp"
#include "visnav/app/sd_notify.hpp"

namespace visnav::app {
namespace {

std::string readAll(int fd) {
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof(buffer));
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
  }
  return text;
}

struct Pipe {
  int fds[2] = {-1, -1};
  Pipe() { EXPECT_EQ(pipe(fds), 0); }
  ~Pipe() {
    for (int fd : fds)
      if (fd >= 0) close(fd);
  }
  std::string drain() {
    close(fds[1]);
    fds[1] = -1;
    return readAll(fds[0]);
  }
};

TEST(EventLog, KeyValueLinesOnATerminal) {
  Pipe p;
  EventLog log(p.fds[1], false);
  log.event(LogLevel::kNotice, "mode_transition", "frame=%d from=%s reason=\"%s\"", 12, "far_range",
            "below 30 m");
  log.event(LogLevel::kError, "stop", "%s", "");
  EXPECT_EQ(log.linesWritten(), 2U);
  const std::string text = p.drain();
  const std::size_t newline = text.find('\n');
  ASSERT_NE(newline, std::string::npos);
  const std::string first = text.substr(0, newline);
  EXPECT_EQ(first.rfind("visnavd t_s=", 0), 0U) << first;
  EXPECT_NE(first.find(" level=notice event=mode_transition frame=12 from=far_range reason=\"below 30 m\""),
            std::string::npos)
      << first;
  const std::string second = text.substr(newline + 1);
  EXPECT_NE(second.find("level=error event=stop\n"), std::string::npos) << second;  // no trailing blank
}

TEST(EventLog, JournalLinesCarryThePriority) {
  Pipe p;
  EventLog log(p.fds[1], true);
  log.event(LogLevel::kWarning, "fault_onset", "fault=%s", "no_frame");
  log.event(LogLevel::kInfo, "start", "x=1");
  EXPECT_EQ(p.drain(), "<4>event=fault_onset fault=no_frame\n<6>event=start x=1\n");
}

TEST(EventLog, DetectsTheJournalStreamFromTheEnvironment) {
  Pipe p;
  struct stat st {};
  ASSERT_EQ(fstat(p.fds[1], &st), 0);
  const std::string matching = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  setenv("JOURNAL_STREAM", matching.c_str(), 1);
  EXPECT_TRUE(isJournalStream(p.fds[1]));
  EXPECT_TRUE(EventLog(p.fds[1]).journal());
  setenv("JOURNAL_STREAM", (std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino + 1)).c_str(), 1);
  EXPECT_FALSE(isJournalStream(p.fds[1]));
  unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(isJournalStream(p.fds[1]));
}

TEST(EventLog, LongLinesAreTruncatedNotOverrun) {
  Pipe p;
  EventLog log(p.fds[1], true);
  const std::string big(3000, 'x');
  log.event(LogLevel::kInfo, "big", "v=%s", big.c_str());
  const std::string text = p.drain();
  EXPECT_EQ(text.size(), EventLog::kLineCapacity - 1);
  EXPECT_EQ(text.back(), '\n');
}

TEST(EventLog, QuotableValues) {
  std::array<char, 8> out{};
  EXPECT_STREQ(quotable("a\"b\nc", out), "a'b c");
  EXPECT_STREQ(quotable("0123456789", out), "0123456");
  EXPECT_STREQ(quotable(nullptr, out), "");
}

TEST(EventLog, WritingALineAllocatesNothing) {
  Pipe p;
  EventLog log(p.fds[1], false);
  log.event(LogLevel::kInfo, "warm", "x=%.3f", 1.5);
  const std::uint64_t before = visnav::test::allocationCount();
  for (int i = 0; i < 50; ++i)
    log.event(LogLevel::kWarning, "fault_onset", "fault=%s frame=%d q=%.6f", faultName(i % kFaultBitCount), i,
              0.25 * i);
  EXPECT_EQ(visnav::test::allocationCount() - before, 0U);
}

/// A pipe whose reader has stopped: the smallest buffer the kernel allows, filled to the brim, so any
/// blocking write on it would never return.
struct StalledPipe : Pipe {
  StalledPipe() {
    fcntl(fds[1], F_SETPIPE_SZ, 4096);
    const int flags = fcntl(fds[1], F_GETFL);
    fcntl(fds[1], F_SETFL, flags | O_NONBLOCK);
    const char fill[256] = {};
    while (write(fds[1], fill, sizeof(fill)) > 0) {
    }
    fcntl(fds[1], F_SETFL, flags);  // the log sees an ordinary blocking fd
  }
};

TEST(EventLog, AsyncLinesArriveInOrder) {
  Pipe p;
  EventLog log(p.fds[1], true);
  ASSERT_TRUE(log.startAsync());
  EXPECT_TRUE(log.async());
  for (int i = 0; i < 20; ++i) log.event(LogLevel::kInfo, "n", "i=%d", i);
  log.stopAsync();
  EXPECT_FALSE(log.async());
  std::string expected;
  for (int i = 0; i < 20; ++i) expected += "<6>event=n i=" + std::to_string(i) + "\n";
  EXPECT_EQ(p.drain(), expected);
  EXPECT_EQ(log.droppedLines(), 0U);
}

TEST(EventLog, AStalledReaderNeverBlocksTheWriterAndLossIsCounted) {
  // With a synchronous write this test would hang in the first event() (ctest's timeout would fail it).
  StalledPipe p;
  EventLog log(p.fds[1], true);
  ASSERT_TRUE(log.startAsync());
  constexpr int kLines = 3000;
  for (int i = 0; i < kLines; ++i) log.event(LogLevel::kWarning, "fault_onset", "frame=%d", i);
  EXPECT_EQ(log.linesWritten(), EventLog::kRingLines);  // the ring is full, the rest is dropped at once
  EXPECT_EQ(log.droppedLines(), kLines - EventLog::kRingLines);
  log.stopAsync(50'000'000);  // the reader never comes back: the queued lines are given up after 50 ms
  EXPECT_EQ(log.droppedLines(), static_cast<std::uint64_t>(kLines));
}

TEST(EventLog, AReaderThatComesBackGetsEveryQueuedLine) {
  StalledPipe p;
  EventLog log(p.fds[1], true);
  ASSERT_TRUE(log.startAsync());
  for (int i = 0; i < 500; ++i) log.event(LogLevel::kInfo, "n", "i=%d", i);  // queued while stalled
  std::string text;
  std::thread reader([&] { text = readAll(p.fds[0]); });
  log.stopAsync(60'000'000'000LL);  // generous: the reader is back, nothing may be lost
  close(p.fds[1]);
  p.fds[1] = -1;
  reader.join();
  EXPECT_EQ(log.droppedLines(), 0U);
  EXPECT_NE(text.find("<6>event=n i=0\n"), std::string::npos);
  EXPECT_NE(text.find("<6>event=n i=499\n"), std::string::npos);
}

TEST(EventLog, AReaderThatIsGoneCostsLinesNotTheProcess) {
  signal(SIGPIPE, SIG_IGN);  // as visnavd does
  Pipe p;
  close(p.fds[0]);
  p.fds[0] = -1;
  EventLog log(p.fds[1], true);
  log.event(LogLevel::kInfo, "sync", "%s", "");  // EPIPE
  ASSERT_TRUE(log.startAsync());
  log.event(LogLevel::kInfo, "async", "%s", "");
  log.stopAsync();
  EXPECT_EQ(log.droppedLines(), 2U);
}

TEST(EventLog, QueuingALineAllocatesNothing) {
  Pipe p;
  std::thread reader([&] {  // discards into a fixed buffer: no allocation of its own
    char buffer[4096];
    while (read(p.fds[0], buffer, sizeof(buffer)) > 0) {
    }
  });
  {
    EventLog log(p.fds[1], false);
    ASSERT_TRUE(log.startAsync());
    log.event(LogLevel::kInfo, "warm", "x=%.3f", 1.5);
    const std::uint64_t before = visnav::test::allocationCount();
    for (int i = 0; i < 200; ++i)
      log.event(LogLevel::kWarning, "fault_onset", "frame=%d q=%.6f", i, 0.25 * i);
    EXPECT_EQ(visnav::test::allocationCount() - before, 0U);
  }
  close(p.fds[1]);
  p.fds[1] = -1;
  reader.join();
}

TEST(FaultNames, OnePerBitBesideTheEnum) {
  EXPECT_STREQ(faultName(bitIndex(kFaultInlierRatio)), "inlier_ratio");
  EXPECT_STREQ(faultName(bitIndex(kFaultNoFrame)), "no_frame");
  EXPECT_STREQ(faultName(bitIndex(kFaultCycleSlip)), "cycle_slip");
  EXPECT_EQ(bitIndex(kFaultCycleSlip), 10);
  EXPECT_STREQ(faultName(bitIndex(kFaultBadFrame)), "bad_frame");
  EXPECT_STREQ(faultName(kFaultBitCount), "unknown");
  EXPECT_STREQ(faultName(-1), "unknown");
  EXPECT_STREQ(stageName(CycleStage::kAcquire), "acquire");
  EXPECT_STREQ(stageName(CycleStage::kHealth), "health");
}

// systemd's side of the protocol: a datagram socket bound at the path NOTIFY_SOCKET names.
class FakeSystemd {
 public:
  explicit FakeSystemd(bool abstract) {
    m_name = (abstract ? "@visnav-notify-" : "/tmp/visnav-notify-") + std::to_string(getpid()) + "-" +
             std::to_string(s_count++);
    m_fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, m_name.c_str(), m_name.size());
    if (abstract) address.sun_path[0] = '\0';
    if (!abstract) unlink(m_name.c_str());
    const auto length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + m_name.size());
    EXPECT_EQ(bind(m_fd, reinterpret_cast<const sockaddr*>(&address), length), 0) << std::strerror(errno);
  }
  ~FakeSystemd() {
    close(m_fd);
    if (m_name[0] == '/') unlink(m_name.c_str());
  }
  const std::string& name() const { return m_name; }
  /// Next datagram, or "" when none is waiting.
  std::string receive() {
    char buffer[512];
    const ssize_t n = recv(m_fd, buffer, sizeof(buffer), MSG_DONTWAIT);
    return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string();
  }
  /// Takes the next datagram without keeping it (no allocation). False when none is waiting.
  bool discard() {
    char buffer[512];
    return recv(m_fd, buffer, sizeof(buffer), MSG_DONTWAIT) > 0;
  }

 private:
  static inline int s_count = 0;
  std::string m_name;
  int m_fd = -1;
};

TEST(SdNotify, SpeaksTheProtocolOnAPathAndAnAbstractSocket) {
  for (bool abstract : {false, true}) {
    FakeSystemd systemd(abstract);
    SdNotifier notifier;
    ASSERT_TRUE(notifier.init(systemd.name().c_str(), 2'000'000).ok);
    ASSERT_TRUE(notifier.active());
    EXPECT_EQ(notifier.watchdogUsec(), 2'000'000U);
    EXPECT_TRUE(notifier.ready("running, mode far_range"));
    EXPECT_TRUE(notifier.watchdog());
    EXPECT_TRUE(notifier.status("mode near_range since frame 80"));
    EXPECT_TRUE(notifier.stopping());
    EXPECT_EQ(systemd.receive(), "READY=1\nSTATUS=running, mode far_range");
    EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
    EXPECT_EQ(systemd.receive(), "STATUS=mode near_range since frame 80");
    EXPECT_EQ(systemd.receive(), "STOPPING=1");
    EXPECT_EQ(systemd.receive(), "");
    EXPECT_EQ(notifier.sent(), 4U);
  }
}

TEST(SdNotify, FromTheEnvironment) {
  FakeSystemd systemd(false);
  setenv("NOTIFY_SOCKET", systemd.name().c_str(), 1);
  setenv("WATCHDOG_USEC", "3000000", 1);
  setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  SdNotifier notifier;
  ASSERT_TRUE(notifier.initFromEnvironment().ok);
  EXPECT_EQ(notifier.watchdogUsec(), 3'000'000U);
  EXPECT_TRUE(notifier.watchdog());
  EXPECT_EQ(systemd.receive(), "WATCHDOG=1");
  setenv("WATCHDOG_PID", "1", 1);  // the watchdog belongs to another process
  ASSERT_TRUE(notifier.initFromEnvironment().ok);
  EXPECT_EQ(notifier.watchdogUsec(), 0U);
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
  ASSERT_TRUE(notifier.initFromEnvironment().ok);
  EXPECT_FALSE(notifier.active());
  EXPECT_FALSE(notifier.watchdog());  // no-op without systemd
}

TEST(SdNotify, RejectsUnusableSocketNames) {
  SdNotifier notifier;
  EXPECT_FALSE(notifier.init("relative/path", 0).ok);
  EXPECT_FALSE(notifier.init(std::string(200, '/').c_str(), 0).ok);
  ASSERT_TRUE(notifier.init("/tmp/visnav-no-such-socket", 0).ok);  // nobody listening: sends fail, counted
  EXPECT_FALSE(notifier.watchdog());
  EXPECT_EQ(notifier.failures(), 1U);
}

TEST(SdNotify, NotifyingAllocatesNothing) {
  FakeSystemd systemd(true);
  SdNotifier notifier;
  ASSERT_TRUE(notifier.init(systemd.name().c_str(), 0).ok);
  const std::uint64_t before = visnav::test::allocationCount();
  for (int i = 0; i < 100; ++i) {
    notifier.watchdog();
    notifier.status("mode far_range since frame 1");
    EXPECT_TRUE(systemd.discard());
    EXPECT_TRUE(systemd.discard());
  }
  EXPECT_EQ(visnav::test::allocationCount() - before, 0U);
}

}  // namespace
}  // namespace visnav::app
