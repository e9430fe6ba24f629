// The seam between the V4L2 driver and the kernel: every OS call the driver makes goes through one V4l2Os.
// realV4l2Os() forwards to the kernel unchanged (POSIX conventions: -1 and errno on failure); tests
// substitute a scripted fake, and the vivid/vimc VM tests run the real one. Kept this thin on purpose: no
// policy here.
#pragma once

#include <poll.h>
#include <sys/types.h>

#include <cstddef>
#include <cstdint>

namespace visnav::camera {

class V4l2Os {
 public:
  virtual ~V4l2Os() = default;
  virtual int open(const char* path, int flags) = 0;
  virtual int close(int fd) = 0;
  /// `request` is a VIDIOC_* code; `arg` the matching struct. Returns -1 with errno set on failure.
  virtual int ioctl(int fd, unsigned long request, void* arg) = 0;
  virtual void* mmap(std::size_t length, int prot, int flags, int fd, off_t offset) = 0;
  virtual int munmap(void* address, std::size_t length) = 0;
  virtual int poll(pollfd* fds, nfds_t count, int timeout_ms) = 0;
  /// CLOCK_MONOTONIC [ns]: deadlines, the dequeue-time timestamp fallback and the reopen back-off (a test
  /// injects its own time here).
  virtual std::int64_t monotonicNs();
};

/// The kernel (process-wide, stateless).
V4l2Os& realV4l2Os();

}  // namespace visnav::camera
