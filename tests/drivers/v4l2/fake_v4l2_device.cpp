// FAKE V4L2 driver for unit tests (see fake_v4l2_device.hpp): protocol emulation, not a kernel.
#include "fake_v4l2_device.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

namespace visnav::test {
namespace {

constexpr int kFirstFd = 40;
constexpr off_t kOffsetStep = 1 << 20;  // QUERYBUF m.offset of buffer i is i * kOffsetStep (a mmap cookie)

std::uint32_t bytesPerPixel(std::uint32_t fourcc) { return fourcc == V4L2_PIX_FMT_GREY ? 1U : 2U; }

int fail(int error_number) {
  errno = error_number;
  return -1;
}

}  // namespace

FakeV4l2Device::FakeV4l2Device(const Config& config) : m_config(config) {
  m_slot_bytes = (static_cast<std::size_t>(config.max_width) * 2U + config.row_padding_bytes) *
                 static_cast<std::size_t>(config.max_height);
  m_memory.assign(m_slot_bytes * kMaxBuffers, 0);
  m_format.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  v4l2_format initial = m_format;
  initial.fmt.pix.width = static_cast<std::uint32_t>(config.max_width);
  initial.fmt.pix.height = static_cast<std::uint32_t>(config.max_height);
  initial.fmt.pix.pixelformat = config.formats[0];
  handleSetFormat(initial);
}

std::uint16_t FakeV4l2Device::pattern(std::uint32_t fourcc, std::uint32_t sequence, int x, int y) {
  const auto code = static_cast<std::uint32_t>(x * 7 + y * 13) + sequence * 5U;
  switch (fourcc) {
    case V4L2_PIX_FMT_Y10: return static_cast<std::uint16_t>((code * 3U) & 0x3FFU);
    case V4L2_PIX_FMT_Y12: return static_cast<std::uint16_t>((code * 11U) & 0xFFFU);
    case V4L2_PIX_FMT_Y16: return static_cast<std::uint16_t>((code * 257U) & 0xFFFFU);
    default: return static_cast<std::uint16_t>(code & 0xFFU);
  }
}

int FakeV4l2Device::open(const char* path, int /*flags*/) {
  ++m_open_calls;
  if (!m_present || std::strcmp(path, m_config.path) != 0) return fail(ENOENT);
  for (std::size_t slot = 0; slot < m_fd_generation.size(); ++slot) {
    if (m_fd_generation[slot] == 0) {
      m_fd_generation[slot] = m_generation;
      ++m_open_fds;
      return kFirstFd + static_cast<int>(slot);
    }
  }
  return fail(EMFILE);
}

bool FakeV4l2Device::fdAlive(int fd) const {
  const int slot = fd - kFirstFd;
  return slot >= 0 && slot < static_cast<int>(m_fd_generation.size()) &&
         m_fd_generation[static_cast<std::size_t>(slot)] != 0;
}

int FakeV4l2Device::close(int fd) {
  if (!fdAlive(fd)) return fail(EBADF);
  const auto slot = static_cast<std::size_t>(fd - kFirstFd);
  // Like the kernel: closing the streaming fd stops streaming and frees the buffers of the live device.
  if (m_fd_generation[slot] == m_generation && m_present) {
    m_streaming = false;
    m_fatal_error = false;
    m_queued_count = 0;
    m_done_count = 0;
    m_granted = 0;
  }
  m_fd_generation[slot] = 0;
  --m_open_fds;
  return 0;
}

void FakeV4l2Device::replug() {
  m_present = true;
  ++m_generation;
  m_streaming = false;
  m_granted = 0;
  m_queued_count = 0;
  m_done_count = 0;
  m_next_sequence = 0;
}

int FakeV4l2Device::ioctl(int fd, unsigned long request, void* arg) {
  ++m_ioctl_calls;
  if (!fdAlive(fd)) return fail(EBADF);
  if (!m_present || m_fd_generation[static_cast<std::size_t>(fd - kFirstFd)] != m_generation)
    return fail(ENODEV);
  if (m_fail_request != 0 && request == m_fail_request) {
    m_fail_request = 0;
    return fail(m_fail_errno);
  }
  switch (request) {
    case VIDIOC_QUERYCAP: {
      auto& cap = *static_cast<v4l2_capability*>(arg);
      cap = v4l2_capability{};
      std::strncpy(reinterpret_cast<char*>(cap.driver), "fake-v4l2", sizeof(cap.driver) - 1);
      std::strncpy(reinterpret_cast<char*>(cap.card), "FakeV4l2Device", sizeof(cap.card) - 1);
      cap.device_caps = m_config.device_caps;
      cap.capabilities = m_config.device_caps | V4L2_CAP_DEVICE_CAPS;
      return 0;
    }
    case VIDIOC_S_FMT: return handleSetFormat(*static_cast<v4l2_format*>(arg));
    case VIDIOC_G_FMT: *static_cast<v4l2_format*>(arg) = m_format; return 0;
    case VIDIOC_S_PARM:
    case VIDIOC_G_PARM: {
      if (!m_config.frame_interval_settable) return fail(ENOTTY);
      auto& parm = *static_cast<v4l2_streamparm*>(arg);
      if (parm.type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
      if (request == VIDIOC_S_PARM && parm.parm.capture.timeperframe.denominator != 0U)
        m_interval = parm.parm.capture.timeperframe;
      parm.parm.capture.capability = V4L2_CAP_TIMEPERFRAME;
      parm.parm.capture.timeperframe = m_interval;
      return 0;
    }
    case VIDIOC_REQBUFS: return handleRequestBuffers(*static_cast<v4l2_requestbuffers*>(arg));
    case VIDIOC_QUERYBUF: {
      auto& buffer = *static_cast<v4l2_buffer*>(arg);
      if (buffer.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || buffer.index >= m_granted) return fail(EINVAL);
      buffer.memory = V4L2_MEMORY_MMAP;
      buffer.length = m_format.fmt.pix.sizeimage;
      buffer.m.offset = static_cast<std::uint32_t>(static_cast<off_t>(buffer.index) * kOffsetStep);
      buffer.flags = m_config.timestamp_flags;
      return 0;
    }
    case VIDIOC_QBUF:
      if (m_fatal_error && m_streaming) return fail(EIO);
      if (m_qbuf_failures > 0) {
        --m_qbuf_failures;
        return fail(m_qbuf_errno);
      }
      return handleQueue(*static_cast<v4l2_buffer*>(arg));
    case VIDIOC_DQBUF:
      if (m_fatal_error && m_streaming) return fail(EIO);
      return handleDequeue(*static_cast<v4l2_buffer*>(arg));
    case VIDIOC_STREAMON:
      if (*static_cast<int*>(arg) != V4L2_BUF_TYPE_VIDEO_CAPTURE || m_granted == 0U) return fail(EINVAL);
      m_streaming = true;
      return 0;
    case VIDIOC_STREAMOFF:
      if (*static_cast<int*>(arg) != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
      m_streaming = false;
      m_fatal_error = false;
      m_queued_count = 0;
      m_done_count = 0;
      std::fill(m_state.begin(), m_state.end(), BufferState::kUser);
      return 0;
    default: return fail(ENOTTY);
  }
}

int FakeV4l2Device::handleSetFormat(v4l2_format& format) {
  if (format.type != V4L2_BUF_TYPE_VIDEO_CAPTURE) return fail(EINVAL);
  if (m_granted != 0U) return fail(EBUSY);
  v4l2_pix_format& pix = format.fmt.pix;
  const auto* begin = m_config.formats.begin();
  const auto* end = begin + m_config.format_count;
  if (std::find(begin, end, pix.pixelformat) == end) pix.pixelformat = m_config.formats[0];
  pix.width = std::clamp<std::uint32_t>(pix.width, 16U, static_cast<std::uint32_t>(m_config.max_width));
  pix.height = std::clamp<std::uint32_t>(pix.height, 16U, static_cast<std::uint32_t>(m_config.max_height));
  pix.field = V4L2_FIELD_NONE;
  pix.bytesperline = pix.width * bytesPerPixel(pix.pixelformat) + m_config.row_padding_bytes;
  pix.sizeimage = pix.bytesperline * pix.height;
  m_format = format;
  return 0;
}

int FakeV4l2Device::handleRequestBuffers(v4l2_requestbuffers& request) {
  if (request.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || request.memory != V4L2_MEMORY_MMAP) return fail(EINVAL);
  if (m_streaming || mappedBuffers() > 0) return fail(EBUSY);
  m_granted =
      request.count == 0U ? 0U : std::clamp(request.count, m_config.min_buffers, m_config.max_buffers);
  request.count = m_granted;
  std::fill(m_state.begin(), m_state.end(), BufferState::kUser);
  m_queued_count = 0;
  m_done_count = 0;
  return 0;
}

int FakeV4l2Device::handleQueue(v4l2_buffer& buffer) {
  if (buffer.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || buffer.memory != V4L2_MEMORY_MMAP ||
      buffer.index >= m_granted)
    return fail(EINVAL);
  if (m_state[buffer.index] != BufferState::kUser) return fail(EINVAL);  // queued twice
  m_state[buffer.index] = BufferState::kQueued;
  m_queue[static_cast<std::size_t>(m_queued_count++)] = static_cast<int>(buffer.index);
  return 0;
}

int FakeV4l2Device::handleDequeue(v4l2_buffer& buffer) {
  if (buffer.type != V4L2_BUF_TYPE_VIDEO_CAPTURE || buffer.memory != V4L2_MEMORY_MMAP) return fail(EINVAL);
  if (m_done_count == 0) return fail(EAGAIN);  // the driver opens O_NONBLOCK
  const int index = m_done[0];
  std::copy(m_done.begin() + 1, m_done.begin() + m_done_count, m_done.begin());
  --m_done_count;
  const auto slot = static_cast<std::size_t>(index);
  m_state[slot] = BufferState::kUser;
  buffer.index = static_cast<std::uint32_t>(index);
  buffer.sequence = m_sequence[slot];
  buffer.flags = m_flags[slot];
  buffer.bytesused = m_bytesused[slot];
  buffer.field = V4L2_FIELD_NONE;
  // Timestamp of the sequence at the configured interval (num / den seconds per frame).
  const std::int64_t interval_ns = static_cast<std::int64_t>(m_interval.numerator) * 1000000000LL /
                                   static_cast<std::int64_t>(m_interval.denominator);
  const std::int64_t t_ns =
      m_config.first_timestamp_ns + static_cast<std::int64_t>(m_sequence[slot]) * interval_ns;
  buffer.timestamp.tv_sec = static_cast<time_t>(t_ns / 1000000000LL);
  buffer.timestamp.tv_usec = static_cast<suseconds_t>((t_ns % 1000000000LL) / 1000LL);
  return 0;
}

bool FakeV4l2Device::produceFrame() {
  if (!m_present || !m_streaming) return false;
  const std::uint32_t sequence = m_next_sequence++;
  if (m_queued_count == 0) return false;  // no buffer: the frame is dropped in the "kernel"
  const int index = m_queue[0];
  std::copy(m_queue.begin() + 1, m_queue.begin() + m_queued_count, m_queue.begin());
  --m_queued_count;
  fill(index, sequence);
  m_done[static_cast<std::size_t>(m_done_count++)] = index;
  m_state[static_cast<std::size_t>(index)] = BufferState::kDone;
  return true;
}

void FakeV4l2Device::fill(int index, std::uint32_t sequence) {
  const auto slot = static_cast<std::size_t>(index);
  const v4l2_pix_format& pix = m_format.fmt.pix;
  std::uint8_t* base = m_memory.data() + slot * m_slot_bytes;
  if (m_config.fill_pixels)
    std::memset(base, 0xEE, pix.sizeimage);  // padding stays 0xEE: a wrong stride shows
  for (int y = 0; m_config.fill_pixels && y < static_cast<int>(pix.height); ++y) {
    std::uint8_t* row = base + static_cast<std::size_t>(y) * pix.bytesperline;
    for (int x = 0; x < static_cast<int>(pix.width); ++x) {
      const std::uint16_t value = pattern(pix.pixelformat, sequence, x, y);
      if (pix.pixelformat == V4L2_PIX_FMT_GREY) {
        row[x] = static_cast<std::uint8_t>(value);
      } else if (pix.pixelformat == V4L2_PIX_FMT_YUYV) {
        row[2 * x] = static_cast<std::uint8_t>(value);
        row[2 * x + 1] = x % 2 == 0 ? 0x80 : 0x10;  // U, V
      } else {                                      // little-endian 16-bit words
        row[2 * x] = static_cast<std::uint8_t>(value & 0xFFU);
        row[2 * x + 1] = static_cast<std::uint8_t>(value >> 8U);
      }
    }
  }
  m_sequence[slot] = sequence;
  m_flags[slot] = m_config.timestamp_flags | (m_corrupt_next ? V4L2_BUF_FLAG_ERROR : 0U);
  m_bytesused[slot] = m_short_next ? pix.sizeimage / 2U : pix.sizeimage;
  m_corrupt_next = false;
  m_short_next = false;
}

void* FakeV4l2Device::mmap(std::size_t length, int prot, int flags, int fd, off_t offset) {
  if (!fdAlive(fd) || (flags & MAP_SHARED) == 0 || (prot & PROT_READ) == 0 || offset % kOffsetStep != 0) {
    errno = EINVAL;
    return MAP_FAILED;
  }
  const auto index = static_cast<std::size_t>(offset / kOffsetStep);
  if (index >= m_granted || length != m_format.fmt.pix.sizeimage || m_mapped[index]) {
    errno = EINVAL;
    return MAP_FAILED;
  }
  m_mapped[index] = true;
  return m_memory.data() + index * m_slot_bytes;
}

int FakeV4l2Device::munmap(void* address, std::size_t length) {
  const auto* byte = static_cast<std::uint8_t*>(address);
  if (byte < m_memory.data() || length == 0U) return fail(EINVAL);
  const auto offset = static_cast<std::size_t>(byte - m_memory.data());
  const std::size_t index = offset / m_slot_bytes;
  if (offset % m_slot_bytes != 0U || index >= kMaxBuffers || !m_mapped[index]) return fail(EINVAL);
  m_mapped[index] = false;
  return 0;
}

int FakeV4l2Device::mappedBuffers() const {
  return static_cast<int>(std::count(m_mapped.begin(), m_mapped.end(), true));
}

std::int64_t FakeV4l2Device::monotonicNs() {
  return m_now_ns >= 0 ? m_now_ns : camera::V4l2Os::monotonicNs();
}

int FakeV4l2Device::poll(pollfd* fds, nfds_t count, int timeout_ms) {
  ++m_poll_calls;
  m_last_poll_timeout_ms = timeout_ms;
  if (count != 1U) return fail(EINVAL);
  if (m_eintr_next) {
    m_eintr_next = false;
    return fail(EINTR);
  }
  pollfd& p = fds[0];
  p.revents = 0;
  if (!fdAlive(p.fd)) {
    p.revents = POLLNVAL;
  } else if (!m_present || m_fd_generation[static_cast<std::size_t>(p.fd - kFirstFd)] != m_generation) {
    p.revents = POLLERR | POLLHUP;
  } else if (m_done_count > 0) {
    p.revents = POLLIN | POLLRDNORM;
  } else if (!m_streaming) {
    p.revents = POLLERR;
  }
  return p.revents != 0 ? 1 : 0;  // "timeout" at once: the test decides when frames appear
}

}  // namespace visnav::test
