// LibcameraCamera set-up and teardown: open(), recover(), close(). Streaming is in libcamera_stream.cpp.
#include <libcamera/control_ids.h>
#include <libcamera/formats.h>
#include <sys/mman.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "libcamera_impl.hpp"
#include "visnav/camera/mono_view.hpp"
#include "visnav/camera/os_error.hpp"
#include "visnav/libcamera/libcamera_formats.hpp"

namespace visnav::camera {
namespace {

libcamera::StreamRole roleOf(int role) {
  switch (static_cast<LibcameraRole>(role)) {
    case LibcameraRole::kRaw: return libcamera::StreamRole::Raw;
    case LibcameraRole::kStillCapture: return libcamera::StreamRole::StillCapture;
    case LibcameraRole::kViewfinder: break;
  }
  return libcamera::StreamRole::Viewfinder;
}

/// "ENODEV (No such device)" for -ENODEV (init-time messages).
std::string errorText(int negative_errno) {
  return std::string(errnoName(-negative_errno)) + " (" + errnoText(-negative_errno) + ")";
}

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

}  // namespace

LibcameraCamera::LibcameraCamera(const CameraParams& params) : m_impl(std::make_unique<Impl>(params)) {}

LibcameraCamera::~LibcameraCamera() { close(); }

const CameraCounters& LibcameraCamera::counters() const { return m_impl->counters; }
const char* LibcameraCamera::lastError() const { return m_impl->last_error; }
CameraState LibcameraCamera::state() const { return m_impl->state; }
bool LibcameraCamera::nextEvent(CameraEvent& event) { return m_impl->events.pop(event); }
const std::string& LibcameraCamera::description() const { return m_impl->description; }

LoadError LibcameraCamera::open() {
  Impl& impl = *m_impl;
  if (impl.state != CameraState::kClosed) return LoadError::failure("libcamera: already open");
  if (impl.params.buffer_count < 2 || impl.params.buffer_count > Impl::kMaxRequests)
    return LoadError::failure("libcamera: [camera] buffer_count must be in [2, 32]");
  if (formatCandidates(impl.params.format()).count == 0)
    return LoadError::failure(
        "libcamera: [camera] pixel_format y16 has no libcamera 0.0.3 equivalent "
        "(use grey, y10, y12 or yuyv)");
  impl.counters = CameraCounters{};
  impl.sequence.reset();
  impl.events.clear();
  std::string reason = impl.startManager();
  if (reason.empty()) reason = impl.selectCamera();
  if (reason.empty()) reason = impl.configureStream(true);
  if (reason.empty()) reason = impl.allocateAndMap();
  if (reason.empty()) reason = impl.createRequests();
  if (reason.empty()) reason = impl.start();
  if (!reason.empty()) {
    close();
    return LoadError::failure("libcamera: " + reason);
  }
  impl.changeState(CameraState::kStreaming);
  impl.last_error = "";
  return LoadError::success();
}

bool LibcameraCamera::recover() {
  Impl& impl = *m_impl;
  if (impl.state == CameraState::kStreaming) return true;
  if (impl.state == CameraState::kClosed) {
    impl.last_error = "recover() on a camera that was never opened";
    return false;
  }
  // Lost or retrying: never give up (a flight camera can come back), but space the attempts.
  const std::int64_t now_ns = Impl::nowNs();
  if (!impl.backoff.due(now_ns)) return false;
  impl.stopCamera();
  std::string reason = impl.selectCamera();
  if (reason.empty()) reason = impl.configureStream(false);
  if (reason.empty()) reason = impl.allocateAndMap();
  if (reason.empty()) reason = impl.createRequests();
  if (reason.empty()) reason = impl.start();
  if (!reason.empty()) {
    impl.stopCamera();
    std::snprintf(impl.error_text, sizeof(impl.error_text), "camera not back yet: %s", reason.c_str());
    impl.last_error = impl.error_text;
    impl.backoff.failed(now_ns);
    if (impl.state == CameraState::kLost && impl.backoff.backingOff())
      impl.changeState(CameraState::kRetrying);
    return false;
  }
  impl.last_error = "reopened";
  impl.changeState(CameraState::kStreaming);
  impl.sequence.restart();
  ++impl.counters.recoveries;
  impl.last_error = "";
  return true;
}

void LibcameraCamera::close() {
  Impl& impl = *m_impl;
  impl.stopCamera();
  if (impl.manager) {
    impl.manager->stop();
    impl.manager.reset();
  }
  impl.state = CameraState::kClosed;
}

std::int64_t LibcameraCamera::Impl::nowNs() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1000000000LL + now.tv_nsec;
}

void LibcameraCamera::Impl::setError(const char* what, int negative_errno) {
  last_error = formatNegativeError(error_text, sizeof(error_text), what, negative_errno);
}

void LibcameraCamera::Impl::changeState(CameraState to) {
  const std::int64_t now_ns = nowNs();
  const CameraState from = state;
  state = to;
  if (to == CameraState::kLost) backoff.start(now_ns, params.recovery_attempts);
  if (from == CameraState::kClosed) return;  // open(): the start line says so
  events.push(stateChangeEvent(from, to, now_ns, backoff, 0U, last_error));
}

std::string LibcameraCamera::Impl::startManager() {
  manager = std::make_unique<libcamera::CameraManager>();
  const int result = manager->start();
  if (result < 0) return "CameraManager::start failed: " + errorText(result);
  return {};
}

std::string LibcameraCamera::Impl::selectCamera() {
  const std::vector<std::shared_ptr<libcamera::Camera>> cameras = manager->cameras();
  std::string available;
  for (const auto& candidate : cameras)
    available += (available.empty() ? "'" : ", '") + candidate->id() + "'";
  if (available.empty())
    available = "none (libcamera " + libcamera::CameraManager::version() +
                " sees no camera: check `cam --list`, the sensor driver and /dev/media*)";
  if (params.device.empty()) {
    if (cameras.empty()) return "no camera found; available: " + available;
    camera = cameras.front();
  } else {
    camera = manager->get(params.device);
    if (!camera)
      return "no camera with id '" + params.device + "' ([camera] device); available: " + available;
  }
  camera_id = camera->id();
  const int result = camera->acquire();
  if (result < 0)
    return "camera '" + camera_id + "' cannot be acquired (in use by another process?): " + errorText(result);
  camera_acquired = true;
  disconnected = false;
  camera->requestCompleted.connect(this, &Impl::onRequestCompleted);
  camera->disconnected.connect(this, &Impl::onDisconnected);
  return {};
}

std::string LibcameraCamera::Impl::configureStream(bool first_open) {
  const libcamera::StreamRole role = roleOf(params.libcamera_role);
  const char* role_name = toString(static_cast<LibcameraRole>(params.libcamera_role));
  configuration = camera->generateConfiguration({role});
  if (!configuration || configuration->empty())
    return "camera '" + camera_id + "' offers no " + role_name + " stream ([camera] libcamera_role)";
  libcamera::StreamConfiguration& stream_config = configuration->at(0);
  const libcamera::Size size(static_cast<unsigned int>(params.width_px),
                             static_cast<unsigned int>(params.height_px));
  FormatCandidates candidates = formatCandidates(params.format());
  if (!first_open) {  // the device must come back as it was
    candidates.formats[0] = format;
    candidates.count = 1;
  }
  std::string tried;
  for (int i = 0; i < candidates.count; ++i) {
    const LibcameraFormat candidate = candidates.formats[static_cast<std::size_t>(i)];
    const LibcameraFormatInfo& info = formatInfo(candidate);
    const libcamera::PixelFormat wanted = libcamera::PixelFormat::fromString(info.name);
    stream_config.pixelFormat = wanted;
    stream_config.size = size;
    stream_config.bufferCount = static_cast<unsigned int>(params.buffer_count);
    const libcamera::CameraConfiguration::Status status = configuration->validate();
    if (status == libcamera::CameraConfiguration::Invalid || stream_config.pixelFormat != wanted) {
      tried += std::string(tried.empty() ? "" : ", ") + info.name;
      continue;
    }
    if (stream_config.size != size)
      return "camera '" + camera_id + "' cannot deliver " + sizeText(params.width_px, params.height_px) +
             " in " + wanted.toString() + " (it adjusted to " + stream_config.size.toString() +
             "); set [camera] width_px/height_px to a supported size (cam -c ID --list-properties, cam -I)";
    if (stream_config.bufferCount > static_cast<unsigned int>(kMaxRequests))
      return "camera '" + camera_id + "' insists on more than 32 buffers";
    if (first_open && i > 0)
      description = std::string("requested ") + toString(static_cast<PixelFormat>(params.pixel_format)) +
                    " is not offered, using " + wanted.toString() + "; ";
    else
      description.clear();
    format = candidate;
    const int result = camera->configure(configuration.get());
    if (result < 0) return "Camera::configure failed: " + errorText(result);
    stream = stream_config.stream();
    stride_bytes = stream_config.stride;
    if (stride_bytes <
            static_cast<std::size_t>(params.width_px) * static_cast<std::size_t>(info.bytes_per_pixel) ||
        (info.source == LumaSource::kInPlace16 && stride_bytes % 2U != 0U))
      return "camera reported a row stride too small or odd for " + wanted.toString();
    if (info.source == LumaSource::kYuyv || info.source == LumaSource::kPackedRgb)
      luma.assign(static_cast<std::size_t>(params.width_px) * static_cast<std::size_t>(params.height_px), 0);
    description += "camera '" + camera_id + "' " + role_name + " " + wanted.toString() + " " +
                   stream_config.size.toString() + " stride " + std::to_string(stride_bytes) + ", " +
                   std::to_string(stream_config.bufferCount) + " buffers";
    return {};
  }
  std::string offered;
  for (const libcamera::PixelFormat& pixel_format : stream_config.formats().pixelformats())
    offered += (offered.empty() ? "" : ", ") + pixel_format.toString();
  return "camera '" + camera_id + "' " + role_name + " stream offers none of " + tried + " at " +
         sizeText(params.width_px, params.height_px) +
         "; it offers: " + (offered.empty() ? "nothing" : offered) + " (try another [camera] libcamera_role)";
}

std::string LibcameraCamera::Impl::allocateAndMap() {
  allocator = std::make_unique<libcamera::FrameBufferAllocator>(camera);
  const int result = allocator->allocate(stream);
  if (result < 0) return "FrameBufferAllocator::allocate failed: " + errorText(result);
  const auto& buffers = allocator->buffers(stream);
  if (buffers.size() < 2U || buffers.size() > static_cast<std::size_t>(kMaxRequests))
    return "the camera allocated " + std::to_string(buffers.size()) + " buffers (need 2 to 32)";
  const std::size_t needed = firstPlaneBytes(format, params.width_px, params.height_px, stride_bytes);
  mappings.assign(buffers.size(), Mapping{});
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    const std::vector<libcamera::FrameBuffer::Plane>& planes = buffers[i]->planes();
    if (planes.empty()) return "a frame buffer has no planes";
    const libcamera::FrameBuffer::Plane& plane = planes.front();
    const std::size_t offset =
        plane.offset == libcamera::FrameBuffer::Plane::kInvalidOffset ? 0U : plane.offset;
    if (plane.length < needed) return "a frame buffer is shorter than the image";
    // Map the dmabuf from its start (mmap offsets must be page aligned; plane offsets need not be).
    const std::size_t length = offset + plane.length;
    void* address = ::mmap(nullptr, length, PROT_READ, MAP_SHARED, plane.fd.get(), 0);
    if (address == MAP_FAILED) return "mmap of a frame buffer failed: " + errorText(-errno);
    mappings[i] = Mapping{address, length, static_cast<const std::uint8_t*>(address) + offset};
  }
  return {};
}

std::string LibcameraCamera::Impl::createRequests() {
  const auto& buffers = allocator->buffers(stream);
  requests.clear();
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    std::unique_ptr<libcamera::Request> request = camera->createRequest(i);
    if (!request) return "Camera::createRequest failed";
    const int result = request->addBuffer(stream, buffers[i].get());
    if (result < 0) return "Request::addBuffer failed: " + errorText(result);
    requests.push_back(std::move(request));
  }
  return {};
}

std::string LibcameraCamera::Impl::start() {
  libcamera::ControlList controls(camera->controls());
  if (camera->controls().count(&libcamera::controls::FrameDurationLimits) != 0U) {
    const auto frame_us = static_cast<std::int64_t>(std::llround(1e6 / params.fps_hz));
    controls.set(libcamera::controls::FrameDurationLimits, {frame_us, frame_us});
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    completed_head = 0;
    completed_count = 0;
  }
  const int result = camera->start(&controls);
  if (result < 0) return "Camera::start failed: " + errorText(result);
  camera_started = true;
  for (const auto& request : requests) {
    const int queued = camera->queueRequest(request.get());
    if (queued < 0) return "Camera::queueRequest failed: " + errorText(queued);
  }
  return {};
}

void LibcameraCamera::Impl::stopCamera() {
  if (camera_started) camera->stop();  // completes the pending requests as cancelled (on this thread)
  camera_started = false;
  {
    std::lock_guard<std::mutex> lock(mutex);
    completed_head = 0;
    completed_count = 0;
  }
  if (camera) {
    camera->requestCompleted.disconnect(this);
    camera->disconnected.disconnect(this);
  }
  requests.clear();  // before the buffers they point to
  for (const Mapping& mapping : mappings) ::munmap(mapping.address, mapping.length);
  mappings.clear();
  if (allocator) allocator->free(stream);
  allocator.reset();
  configuration.reset();
  stream = nullptr;
  if (camera_acquired) camera->release();
  camera_acquired = false;
  camera.reset();
  held = -1;
  parked.fill(false);
  parked_count = 0;
  parked_rounds = 0;
}

}  // namespace visnav::camera
