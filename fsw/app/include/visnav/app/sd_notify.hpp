// The systemd notification protocol (sd_notify(3)), which is small enough to speak without libsystemd: one
// datagram of "KEY=value\n..." text to the AF_UNIX socket named by $NOTIFY_SOCKET (a path, or '@' for the
// abstract namespace). visnavd sends READY=1 when the loop starts, WATCHDOG=1 every cycle (a unit with
// WatchdogSec= restarts a hung daemon), STATUS= lines on mode changes and STOPPING=1 at the end. Without
// $NOTIFY_SOCKET every call is a no-op. The socket is created at init; a notification is one sendto() from a
// caller's stack buffer: no allocation, never blocks (MSG_DONTWAIT).
#pragma once

#include <sys/socket.h>
#include <sys/un.h>

#include <cstdint>

#include "visnav/core/status.hpp"

namespace visnav::app {

class SdNotifier {
 public:
  SdNotifier() = default;
  ~SdNotifier();
  SdNotifier(const SdNotifier&) = delete;
  SdNotifier& operator=(const SdNotifier&) = delete;

  /// Reads $NOTIFY_SOCKET, $WATCHDOG_USEC and $WATCHDOG_PID. Inactive (not an error) when unset.
  LoadError initFromEnvironment();
  /// `socket_path`: "/path" or "@abstract" (nullptr or empty: inactive). `watchdog_usec` 0: no watchdog.
  LoadError init(const char* socket_path, std::uint64_t watchdog_usec);

  bool active() const { return m_fd >= 0; }
  /// systemd's watchdog interval [us] (0 when the unit has none or it is meant for another process).
  std::uint64_t watchdogUsec() const { return m_watchdog_usec; }

  /// Sends `message` as is (e.g. "READY=1\nSTATUS=running"). False when inactive or the send failed
  /// (counted).
  bool notify(const char* message);
  bool ready(const char* status);
  bool watchdog() { return notify("WATCHDOG=1"); }
  bool status(const char* status);
  bool stopping() { return notify("STOPPING=1"); }

  std::uint64_t sent() const { return m_sent; }
  std::uint64_t failures() const { return m_failures; }
  void close();

 private:
  bool sendWithPrefix(const char* prefix, const char* text);

  int m_fd = -1;
  sockaddr_un m_address{};
  socklen_t m_address_length = 0;
  std::uint64_t m_watchdog_usec = 0;
  std::uint64_t m_sent = 0;
  std::uint64_t m_failures = 0;
};

}  // namespace visnav::app
