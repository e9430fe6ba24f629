// V4l2Camera setup and teardown: open(), recover(), close(). Streaming is in v4l2_stream.cpp.
#include "visnav/v4l2/v4l2_camera.hpp"

#include <fcntl.h>
#include <linux/videodev2.h>
#include <sys/mman.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "v4l2_detail.hpp"
#include "visnav/camera/mono_view.hpp"
#include "visnav/camera/os_error.hpp"

namespace visnav::camera {
namespace {
constexpr const char* kFormatAdjusted = "the device adjusted the requested format";
constexpr const char* kFormatChanged = "the device came back with a different format";
}  // namespace

V4l2Camera::V4l2Camera(const CameraParams& params, V4l2Os& os)
    : m_params(params), m_os(os), m_format(static_cast<PixelFormat>(params.pixel_format)) {}

V4l2Camera::~V4l2Camera() { close(); }

LoadError V4l2Camera::open() {
  if (m_state != CameraState::kClosed)
    return LoadError::failure("v4l2 " + m_params.device + ": already open");
  if (m_params.device.empty()) return LoadError::failure("v4l2: [camera] device is empty (e.g. /dev/video0)");
  if (m_params.buffer_count < 2 || m_params.buffer_count > kMaxBuffers)
    return LoadError::failure("v4l2: [camera] buffer_count must be in [2, 32]");
  if (m_format == PixelFormat::kYuyv)
    m_luma.assign(static_cast<std::size_t>(m_params.width_px) * static_cast<std::size_t>(m_params.height_px),
                  0);
  m_counters = CameraCounters{};
  m_sequence.reset();
  m_events.clear();
  if (const char* reason = setUp(true)) return LoadError::failure(describeFailure(reason));
  changeState(CameraState::kStreaming, m_os.monotonicNs());
  m_last_error = "";
  return LoadError::success();
}

bool V4l2Camera::recover() {
  if (m_state == CameraState::kStreaming) return true;
  if (m_state == CameraState::kClosed) {
    m_last_error = "recover() on a camera that was never opened";
    return false;
  }
  // Lost or retrying: never give up (a flight camera can come back), but space the attempts.
  const std::int64_t now_ns = m_os.monotonicNs();
  if (!m_backoff.due(now_ns)) return false;
  if (const char* reason = setUp(false)) {
    setError(reason, m_last_errno);
    m_backoff.failed(now_ns);
    if (m_state == CameraState::kLost && m_backoff.backingOff()) changeState(CameraState::kRetrying, now_ns);
    return false;
  }
  m_last_error = "reopened";
  changeState(CameraState::kStreaming, now_ns);
  m_sequence.restart();  // the driver restarts its count; frame.sequence continues
  ++m_counters.recoveries;
  m_last_error = "";
  return true;
}

void V4l2Camera::close() {
  if (m_state == CameraState::kClosed) return;
  tearDown();
  m_held = -1;
  m_state = CameraState::kClosed;
}

void V4l2Camera::setError(const char* what, int error_number) {
  m_last_error = formatOsError(m_error_text, sizeof(m_error_text), what, error_number);
}

void V4l2Camera::changeState(CameraState to, std::int64_t now_ns) {
  const CameraState from = m_state;
  m_state = to;
  if (to == CameraState::kLost) m_backoff.start(now_ns, m_params.recovery_attempts);
  if (from == CameraState::kClosed) return;  // open(): the start line says so
  m_events.push(stateChangeEvent(from, to, now_ns, m_backoff, static_cast<std::uint32_t>(m_pending_count),
                                 m_last_error));
}

const char* V4l2Camera::setUp(bool first_open) {
  m_last_errno = 0;
  m_info = V4l2StreamInfo{};
  m_fd = m_os.open(m_params.device.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
  if (m_fd < 0) {
    m_last_errno = errno;
    return "cannot open the device node (check [camera] device and that the driver is loaded: "
           "v4l2-ctl --list-devices)";
  }
  const char* reason = queryCapabilities();
  if (reason == nullptr) reason = negotiateFormat(first_open);
  if (reason == nullptr) reason = setFrameInterval();
  if (reason == nullptr) reason = mapRing();
  if (reason == nullptr) {
    // A refused buffer is parked like one refused in release(): the first acquire() queues it again.
    for (int i = 0; i < m_ring_size && reason == nullptr; ++i) {
      if (queueBuffer(i)) continue;
      if (v4l2detail::isDeviceGone(m_last_errno))
        reason = "VIDIOC_QBUF of a fresh buffer";
      else
        parkBuffer(i, "VIDIOC_QBUF of a fresh buffer", m_last_errno);
    }
    if (reason == nullptr && m_ring_size - m_pending_count < kMinDriverBuffers)
      reason = "VIDIOC_QBUF refused the fresh buffers";
  }
  if (reason == nullptr) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (m_os.ioctl(m_fd, VIDIOC_STREAMON, &type) < 0) {
      m_last_errno = errno;
      reason = "VIDIOC_STREAMON";
    }
  }
  if (reason != nullptr) tearDown();
  return reason;
}

const char* V4l2Camera::queryCapabilities() {
  v4l2_capability cap{};
  if (m_os.ioctl(m_fd, VIDIOC_QUERYCAP, &cap) < 0) {
    m_last_errno = errno;
    return m_last_errno == ENOTTY ? "not a V4L2 device (VIDIOC_QUERYCAP refused)" : "VIDIOC_QUERYCAP";
  }
  const std::uint32_t caps =
      (cap.capabilities & V4L2_CAP_DEVICE_CAPS) != 0U ? cap.device_caps : cap.capabilities;
  static_assert(sizeof(m_info.driver) <= sizeof(cap.driver) && sizeof(m_info.card) <= sizeof(cap.card));
  std::memcpy(m_info.driver, cap.driver, sizeof(m_info.driver) - 1);
  std::memcpy(m_info.card, cap.card, sizeof(m_info.card) - 1);
  if ((caps & V4L2_CAP_VIDEO_CAPTURE) == 0U)
    return (caps & V4L2_CAP_VIDEO_CAPTURE_MPLANE) != 0U
               ? "multi-planar capture device: only single-planar V4L2 capture is supported"
               : "not a video capture device (no V4L2_CAP_VIDEO_CAPTURE; is this a metadata or output node?)";
  if ((caps & V4L2_CAP_STREAMING) == 0U) return "the device has no streaming I/O (V4L2_CAP_STREAMING)";
  return nullptr;
}

const char* V4l2Camera::negotiateFormat(bool first_open) {
  v4l2_format format{};
  format.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  format.fmt.pix.width = static_cast<std::uint32_t>(m_params.width_px);
  format.fmt.pix.height = static_cast<std::uint32_t>(m_params.height_px);
  format.fmt.pix.pixelformat = v4l2detail::fourccOf(m_format);
  format.fmt.pix.field = V4L2_FIELD_NONE;
  if (m_os.ioctl(m_fd, VIDIOC_S_FMT, &format) < 0) {
    m_last_errno = errno;
    return m_last_errno == EBUSY ? "VIDIOC_S_FMT: device busy (another process is streaming from it?)"
                                 : "VIDIOC_S_FMT";
  }
  const v4l2_pix_format& pix = format.fmt.pix;
  m_info.fourcc = pix.pixelformat;
  m_info.bytes_per_line = pix.bytesperline;
  m_info.image_bytes = pix.sizeimage;
  m_info.width = pix.width;
  m_info.height = pix.height;
  // Drivers adjust what they cannot do instead of failing: accept only exactly what was asked for (the
  // calibration and the estimators assume this size; a silent format change would misread the bytes).
  if (pix.pixelformat != v4l2detail::fourccOf(m_format) || static_cast<int>(pix.width) != m_params.width_px ||
      static_cast<int>(pix.height) != m_params.height_px)
    return first_open ? kFormatAdjusted : kFormatChanged;
  if (pix.field != V4L2_FIELD_NONE && pix.field != V4L2_FIELD_ANY)
    return "interlaced field order: only progressive (V4L2_FIELD_NONE) frames are supported";
  const std::size_t row_bytes =
      static_cast<std::size_t>(m_params.width_px) * static_cast<std::size_t>(bytesPerPixel(m_format));
  if (pix.bytesperline < row_bytes || (bytesPerPixel(m_format) == 2 && pix.bytesperline % 2U != 0U))
    return "the driver reported a row stride (bytesperline) too small or odd for the format";
  if (pix.sizeimage < minimumBufferBytes(m_format, m_params.width_px, m_params.height_px, pix.bytesperline))
    return "the driver reported an image size (sizeimage) smaller than height * bytesperline";
  return nullptr;
}

const char* V4l2Camera::setFrameInterval() {
  v4l2_streamparm parm{};
  parm.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  // 1 / fps as a fraction: exact for whole rates, to 1/1000 Hz otherwise.
  const double fps = m_params.fps_hz;
  const bool whole = std::fabs(fps - std::round(fps)) < 1e-9;
  parm.parm.capture.timeperframe.numerator = whole ? 1U : 1000U;
  parm.parm.capture.timeperframe.denominator =
      static_cast<std::uint32_t>(std::lround(whole ? fps : fps * 1000.0));
  m_info.frame_interval_set = false;
  m_info.interval_numerator = 0;
  m_info.interval_denominator = 0;
  if (m_os.ioctl(m_fd, VIDIOC_S_PARM, &parm) < 0) {
    m_last_errno = errno;
    if (v4l2detail::isDeviceGone(m_last_errno)) return "VIDIOC_S_PARM";
    m_last_errno = 0;  // not settable (ENOTTY/EINVAL): the sensor runs at its own rate, noted in streamInfo()
    return nullptr;
  }
  m_info.frame_interval_set = (parm.parm.capture.capability & V4L2_CAP_TIMEPERFRAME) != 0U;
  m_info.interval_numerator = parm.parm.capture.timeperframe.numerator;
  m_info.interval_denominator = parm.parm.capture.timeperframe.denominator;
  return nullptr;
}

const char* V4l2Camera::mapRing() {
  v4l2_requestbuffers request{};
  request.count = static_cast<std::uint32_t>(m_params.buffer_count);
  request.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
  request.memory = V4L2_MEMORY_MMAP;
  if (m_os.ioctl(m_fd, VIDIOC_REQBUFS, &request) < 0) {
    m_last_errno = errno;
    return m_last_errno == EBUSY ? "VIDIOC_REQBUFS: buffers busy (another process is streaming?)"
                                 : "VIDIOC_REQBUFS (mmap streaming)";
  }
  if (request.count < 2U) return "the driver granted fewer than 2 buffers";
  if (request.count > static_cast<std::uint32_t>(kMaxBuffers))
    return "the driver insisted on more than 32 buffers";
  m_info.buffer_count = static_cast<int>(request.count);
  const std::size_t needed =
      minimumBufferBytes(m_format, m_params.width_px, m_params.height_px, m_info.bytes_per_line);
  for (std::uint32_t i = 0; i < request.count; ++i) {
    v4l2_buffer buffer{};
    buffer.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buffer.memory = V4L2_MEMORY_MMAP;
    buffer.index = i;
    if (m_os.ioctl(m_fd, VIDIOC_QUERYBUF, &buffer) < 0) {
      m_last_errno = errno;
      return "VIDIOC_QUERYBUF";
    }
    if (buffer.length < needed) return "a driver buffer is shorter than the image";
    void* start = m_os.mmap(buffer.length, PROT_READ, MAP_SHARED, m_fd, static_cast<off_t>(buffer.m.offset));
    if (start == MAP_FAILED) {
      m_last_errno = errno;
      return "mmap of a driver buffer";
    }
    m_ring[i].start = static_cast<const std::uint8_t*>(start);
    m_ring[i].length = buffer.length;
    m_ring_size = static_cast<int>(i) + 1;
  }
  return nullptr;
}

void V4l2Camera::tearDown() {
  if (m_fd >= 0) {
    int type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    m_os.ioctl(m_fd, VIDIOC_STREAMOFF, &type);  // fails on a vanished device; closing frees the ring anyway
  }
  for (int i = 0; i < m_ring_size; ++i) {
    m_os.munmap(const_cast<std::uint8_t*>(m_ring[i].start), m_ring[i].length);
    m_ring[i] = Slot{};
  }
  m_ring_size = 0;
  m_parked.fill(false);
  m_pending_count = 0;
  m_requeue_rounds = 0;
  if (m_fd >= 0) m_os.close(m_fd);
  m_fd = -1;
}

std::string V4l2Camera::describeFailure(const char* reason) const {
  char text[CameraEvent::kTextCapacity];
  std::string message =
      "v4l2 " + m_params.device + ": " + formatOsError(text, sizeof(text), reason, m_last_errno);
  if (reason == kFormatAdjusted || reason == kFormatChanged) {
    message += ": asked for " + v4l2detail::fourccText(v4l2detail::fourccOf(m_format)) + " " +
               std::to_string(m_params.width_px) + "x" + std::to_string(m_params.height_px) +
               ", the device offers " + v4l2detail::fourccText(m_info.fourcc) + " " +
               std::to_string(m_info.width) + "x" + std::to_string(m_info.height) +
               " (list what it supports: v4l2-ctl -d " + m_params.device + " --list-formats-ext)";
  }
  return message;
}

}  // namespace visnav::camera
