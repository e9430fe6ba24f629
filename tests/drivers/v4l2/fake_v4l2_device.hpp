// FAKE: an in-process imitation of a V4L2 capture driver behind the V4l2Os seam, for unit tests only. It is
// NOT a kernel driver and proves nothing about one (the vivid/vimc VM tests do that). It emulates the ioctl
// protocol the driver relies on: QUERYCAP, S_FMT/G_FMT (adjusting what it cannot do, like real drivers),
// S_PARM/G_PARM, REQBUFS, QUERYBUF, mmap of real memory, QBUF/DQBUF, STREAMON/OFF, poll readiness, and a
// script for sequence gaps, corrupt frames, EINTR, and the device vanishing (ENODEV) and coming back.
// Frames appear only when the test calls produceFrame(): deterministic, single-threaded, no allocation after
// construction (so the driver's zero-allocation proofs include the fake).
#pragma once

#include <linux/videodev2.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <vector>

#include "visnav/v4l2/v4l2_os.hpp"

namespace visnav::test {

class FakeV4l2Device final : public camera::V4l2Os {
 public:
  static constexpr int kMaxBuffers = 32;
  struct Config {
    const char* path = "/dev/fake-video0";
    std::uint32_t device_caps = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_STREAMING;
    /// Formats offered; an unsupported request is answered with the first (real drivers adjust, not fail).
    std::array<std::uint32_t, 5> formats = {V4L2_PIX_FMT_GREY, V4L2_PIX_FMT_Y10, V4L2_PIX_FMT_Y12,
                                            V4L2_PIX_FMT_Y16, V4L2_PIX_FMT_YUYV};
    int format_count = 5;
    int max_width = 320;  ///< larger requests are clamped (and so refused by the driver)
    int max_height = 240;
    std::uint32_t row_padding_bytes = 0;  ///< bytesperline = width * bytes per pixel + padding
    bool frame_interval_settable = true;
    std::uint32_t min_buffers = 2;
    std::uint32_t max_buffers = 8;
    std::uint32_t timestamp_flags = V4L2_BUF_FLAG_TIMESTAMP_MONOTONIC | V4L2_BUF_FLAG_TSTAMP_SRC_SOE;
    std::int64_t first_timestamp_ns = 1000000000;  ///< timestamp of sequence 0; then + frame interval
    bool fill_pixels = true;  ///< false: frames keep whatever the buffer held (benchmarks)
  };

  explicit FakeV4l2Device(const Config& config);

  // V4l2Os
  int open(const char* path, int flags) override;
  int close(int fd) override;
  int ioctl(int fd, unsigned long request, void* arg) override;
  void* mmap(std::size_t length, int prot, int flags, int fd, off_t offset) override;
  int munmap(void* address, std::size_t length) override;
  int poll(pollfd* fds, nfds_t count, int timeout_ms) override;
  /// The real CLOCK_MONOTONIC until setNowNs() is called; then the test's time (advanceNs()).
  std::int64_t monotonicNs() override;

  // Script.
  /// The sensor finishes a frame: the oldest queued buffer gets it (false when none is queued: the frame is
  /// lost inside the "kernel", as real drivers do, and the sequence still advances).
  bool produceFrame();
  /// The sensor produced `count` frames nobody received (sequence advances).
  void skipFrames(std::uint32_t count) { m_next_sequence += count; }
  void corruptNextFrame() { m_corrupt_next = true; }
  void shortNextFrame() { m_short_next = true; }
  void failNextPollWithEintr() { m_eintr_next = true; }
  /// The next `count` VIDIOC_QBUF calls fail with `error_number` and leave the buffer with the caller
  /// (vivid's inject_vidioc_qbuf_error is one such call with EINVAL).
  void failQbuf(int count, int error_number = EINVAL) {
    m_qbuf_failures = count;
    m_qbuf_errno = error_number;
  }
  /// The next call of `request` (VIDIOC_STREAMON, VIDIOC_REQBUFS, ...) fails with `error_number` (vivid's
  /// inject_vidioc_streamon_error / inject_vidioc_reqbufs_error).
  void failNextIoctl(unsigned long request, int error_number) {
    m_fail_request = request;
    m_fail_errno = error_number;
  }
  /// A fatal streaming error (vivid's inject_fatal_streaming_error, vb2_queue_error): DQBUF/QBUF give EIO
  /// until the stream is stopped.
  void fatalStreamingError() { m_fatal_error = true; }
  void setNowNs(std::int64_t now_ns) { m_now_ns = now_ns; }
  void advanceNs(std::int64_t step_ns) { m_now_ns += step_ns; }
  /// Device vanishes: open() gives ENOENT, calls on an open fd give ENODEV, poll gives POLLERR | POLLHUP.
  void unplug() { m_present = false; }
  /// Device comes back: new opens work, fds from before stay dead; the sequence restarts at 0.
  void replug();
  void setNextSequence(std::uint32_t sequence) { m_next_sequence = sequence; }
  /// From now on the device offers only this format (e.g. different firmware after a replug).
  void offerOnly(std::uint32_t fourcc) {
    m_config.formats[0] = fourcc;
    m_config.format_count = 1;
  }

  // Observation.
  int openFds() const { return m_open_fds; }
  int mappedBuffers() const;
  int queuedBuffers() const { return m_queued_count; }
  bool streaming() const { return m_streaming; }
  int pollCalls() const { return m_poll_calls; }
  int lastPollTimeoutMs() const { return m_last_poll_timeout_ms; }
  int ioctlCalls() const { return m_ioctl_calls; }
  int openCalls() const { return m_open_calls; }
  const v4l2_pix_format& format() const { return m_format.fmt.pix; }
  const v4l2_fract& frameInterval() const { return m_interval; }
  std::uint32_t grantedBuffers() const { return m_granted; }

  /// The pattern every produced frame carries at pixel (x, y) of frame `sequence`: 8-bit formats use the low
  /// byte; 16-bit formats the code masked to their depth; YUYV carries it as Y with chroma bytes 0x80 / 0x10.
  static std::uint16_t pattern(std::uint32_t fourcc, std::uint32_t sequence, int x, int y);

 private:
  enum class BufferState : std::uint8_t { kUser, kQueued, kDone };
  bool fdAlive(int fd) const;
  int handleSetFormat(v4l2_format& format);
  int handleRequestBuffers(v4l2_requestbuffers& request);
  int handleQueue(v4l2_buffer& buffer);
  int handleDequeue(v4l2_buffer& buffer);
  void fill(int index, std::uint32_t sequence);

  Config m_config;
  std::vector<std::uint8_t> m_memory;  // all buffers, allocated once in the constructor
  std::size_t m_slot_bytes = 0;
  bool m_present = true;
  int m_generation = 1;  // fds of an earlier generation died with an unplug
  int m_open_fds = 0;
  int m_next_fd = 40;
  std::array<int, 16> m_fd_generation{};
  v4l2_format m_format{};
  v4l2_fract m_interval{1, 30};
  std::uint32_t m_granted = 0;
  std::array<BufferState, kMaxBuffers> m_state{};
  std::array<bool, kMaxBuffers> m_mapped{};
  std::array<std::uint32_t, kMaxBuffers> m_sequence{};
  std::array<std::uint32_t, kMaxBuffers> m_flags{};
  std::array<std::uint32_t, kMaxBuffers> m_bytesused{};
  std::array<int, kMaxBuffers> m_queue{};  // FIFO of queued indices
  int m_queued_count = 0;
  std::array<int, kMaxBuffers> m_done{};  // FIFO of completed indices
  int m_done_count = 0;
  bool m_streaming = false;
  std::uint32_t m_next_sequence = 0;
  bool m_corrupt_next = false;
  bool m_short_next = false;
  bool m_eintr_next = false;
  int m_poll_calls = 0;
  int m_last_poll_timeout_ms = -2;
  int m_ioctl_calls = 0;
  int m_open_calls = 0;
  int m_qbuf_failures = 0;
  int m_qbuf_errno = 0;
  unsigned long m_fail_request = 0;
  int m_fail_errno = 0;
  bool m_fatal_error = false;
  std::int64_t m_now_ns = -1;  // < 0: the real clock
};

}  // namespace visnav::test
