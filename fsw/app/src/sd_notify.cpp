#include "visnav/app/sd_notify.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace visnav::app {

SdNotifier::~SdNotifier() { close(); }

void SdNotifier::close() {
  if (m_fd >= 0) ::close(m_fd);
  m_fd = -1;
}

LoadError SdNotifier::initFromEnvironment() {
  std::uint64_t watchdog_usec = 0;
  if (const char* usec = std::getenv("WATCHDOG_USEC")) {
    watchdog_usec = std::strtoull(usec, nullptr, 10);
    // WATCHDOG_PID set for another process (a wrapper started us): the watchdog is not ours to feed.
    if (const char* pid = std::getenv("WATCHDOG_PID"))
      if (std::strtol(pid, nullptr, 10) != static_cast<long>(getpid())) watchdog_usec = 0;
  }
  return init(std::getenv("NOTIFY_SOCKET"), watchdog_usec);
}

LoadError SdNotifier::init(const char* socket_path, std::uint64_t watchdog_usec) {
  close();
  m_watchdog_usec = watchdog_usec;
  if (socket_path == nullptr || socket_path[0] == '\0') return LoadError::success();
  const std::size_t length = std::strlen(socket_path);
  if ((socket_path[0] != '/' && socket_path[0] != '@') || length >= sizeof(m_address.sun_path))
    return LoadError::failure(std::string("NOTIFY_SOCKET '") + socket_path +
                              "' is neither an absolute path nor an abstract name (@...) that fits sun_path");
  m_address = sockaddr_un{};
  m_address.sun_family = AF_UNIX;
  std::memcpy(m_address.sun_path, socket_path, length);
  if (socket_path[0] == '@') m_address.sun_path[0] = '\0';  // abstract namespace: no terminating NUL counted
  m_address_length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + length);
  m_fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (m_fd < 0)
    return LoadError::failure(std::string("NOTIFY_SOCKET: socket(AF_UNIX, SOCK_DGRAM) failed: ") +
                              std::strerror(errno));
  return LoadError::success();
}

bool SdNotifier::notify(const char* message) {
  if (m_fd < 0) return false;
  const ssize_t n = ::sendto(m_fd, message, std::strlen(message), MSG_NOSIGNAL | MSG_DONTWAIT,
                             reinterpret_cast<const sockaddr*>(&m_address), m_address_length);
  if (n < 0) {
    ++m_failures;
    return false;
  }
  ++m_sent;
  return true;
}

bool SdNotifier::sendWithPrefix(const char* prefix, const char* text) {
  char message[256];
  std::snprintf(message, sizeof(message), "%s%s", prefix, text);
  return notify(message);
}

bool SdNotifier::ready(const char* status) { return sendWithPrefix("READY=1\nSTATUS=", status); }

bool SdNotifier::status(const char* status) { return sendWithPrefix("STATUS=", status); }

}  // namespace visnav::app
