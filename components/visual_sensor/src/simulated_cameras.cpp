#include "jaus/components/simulated_cameras.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

#include "jaus/components/image_directory.hpp"
#include "jaus/components/test_pattern.hpp"

namespace jaus::components {

namespace {

// One axis of a mount, at `position` since the last advance().
struct AxisMotion {
  MountAxis limits;
  double position = 0;
  AxisMode mode = AxisMode::position;
  double target = 0;  // position mode
  double rate = 0;    // rate mode, units per second

  explicit AxisMotion(const MountAxis& axis) : limits(axis) {
    position = target = limits.movable() ? std::clamp(0.0, limits.min, limits.max) : 0.0;
  }

  void advance(double seconds) {
    if (!limits.movable() || seconds <= 0) return;
    if (mode == AxisMode::position) {
      const double step = limits.max_rate * seconds;
      position = std::abs(target - position) <= step ? target : position + std::copysign(step, target - position);
    } else {
      position = std::clamp(position + rate * seconds, limits.min, limits.max);
    }
  }

  void command(const AxisCommand& c) {
    if (!limits.movable() || !std::isfinite(c.value)) return;
    mode = c.mode;
    if (c.mode == AxisMode::position) {
      target = std::clamp(c.value, limits.min, limits.max);
      rate = 0;
    } else {
      rate = std::clamp(c.value, -limits.max_rate, limits.max_rate);
      target = position;
    }
  }

  void hold() {
    mode = AxisMode::position;
    target = position;
    rate = 0;
  }

  bool moving() const {
    if (mode == AxisMode::position) return position != target;
    return (rate > 0 && position < limits.max) || (rate < 0 && position > limits.min);
  }
};

// A directory read by capture() on the loop and by capture jobs on a worker:
// its listing is cached state, so one reader at a time. Shared with the jobs,
// so a job still queued when the cameras go keeps it alive.
struct LockedDirectory {
  explicit LockedDirectory(std::string path) : directory(std::move(path)) {}
  Expected<Image> frame(std::uint64_t frame) {
    std::lock_guard lock(mutex);
    return directory.frame(frame);
  }
  std::mutex mutex;
  ImageDirectory directory;
};

Error no_camera(std::uint8_t camera_id) {
  return make_error(ErrorCode::invalid_argument, "no camera " + std::to_string(camera_id));
}

}  // namespace

struct SimulatedCameras::Camera {
  explicit Camera(const CameraConfig& c)
      : config(c), pan(c.pan), tilt(c.tilt), zoom(c.zoom) {
    if (!c.image_directory.empty()) directory = std::make_shared<LockedDirectory>(c.image_directory);
  }

  void advance_to(rt::TimePoint now) {
    const double seconds = std::chrono::duration<double>(now - moved_at).count();
    moved_at = now;
    pan.advance(seconds);
    tilt.advance(seconds);
    zoom.advance(seconds);
  }

  const CameraConfig& config;
  AxisMotion pan, tilt, zoom;
  rt::TimePoint moved_at{};
  std::shared_ptr<LockedDirectory> directory;
};

SimulatedCameras::SimulatedCameras(VisualSensorConfig config, const rt::Clock& clock)
    : config_(std::move(config)), clock_(clock), start_(clock.now()) {
  for (const auto& c : config_.cameras) {
    cameras_.push_back(std::make_unique<Camera>(c));
    cameras_.back()->moved_at = start_;
  }
}

SimulatedCameras::~SimulatedCameras() = default;

const std::vector<CameraConfig>& SimulatedCameras::configs() const { return config_.cameras; }

SimulatedCameras::Camera* SimulatedCameras::find(std::uint8_t camera_id) {
  for (auto& camera : cameras_)
    if (camera->config.id == camera_id) {
      camera->advance_to(clock_.now());
      return camera.get();
    }
  return nullptr;
}

void SimulatedCameras::command_mount(std::uint8_t camera_id, const MountCommand& command) {
  Camera* camera = find(camera_id);
  if (!camera) return;
  if (command.pan) camera->pan.command(*command.pan);
  if (command.tilt) camera->tilt.command(*command.tilt);
  if (command.zoom) camera->zoom.command(*command.zoom);
}

void SimulatedCameras::hold(std::uint8_t camera_id) {
  Camera* camera = find(camera_id);
  if (!camera) return;
  camera->pan.hold();
  camera->tilt.hold();
  camera->zoom.hold();
}

MountState SimulatedCameras::mount_state(std::uint8_t camera_id) {
  const Camera* camera = find(camera_id);
  if (!camera) return {};
  return MountState{camera->pan.position, camera->tilt.position, camera->zoom.position,
                    camera->pan.moving() || camera->tilt.moving() || camera->zoom.moving()};
}

std::uint64_t SimulatedCameras::frame_number(std::uint16_t frame_rate_fps) const {
  const auto elapsed = std::max(clock_.now() - start_, rt::Duration::zero());
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(elapsed);
  const auto rest = std::chrono::duration_cast<std::chrono::nanoseconds>(elapsed - seconds);
  // Whole seconds and the rest apart: no overflow however long it runs.
  return static_cast<std::uint64_t>(seconds.count()) * frame_rate_fps +
         static_cast<std::uint64_t>(rest.count()) * frame_rate_fps / 1'000'000'000u;
}

Expected<Image> SimulatedCameras::capture(std::uint8_t camera_id, const ImageRequest& request) {
  return capture_job(camera_id, request)();
}

CaptureJob SimulatedCameras::capture_job(std::uint8_t camera_id, const ImageRequest& request) {
  Camera* camera = find(camera_id);
  if (!camera) return [camera_id]() -> Expected<Image> { return unexpected(no_camera(camera_id)); };
  // The frame number is read here, on the clock's thread: the job is the frame shown now.
  const std::uint64_t frame = frame_number(std::max<std::uint16_t>(request.frame_rate_fps, 1));
  if (camera->directory) return [directory = camera->directory, frame] { return directory->frame(frame); };
  return [request, frame]() -> Expected<Image> {
    if (request.width == 0 || request.height == 0)
      return unexpected(make_error(ErrorCode::invalid_argument, "image size 0"));
    return encode_image(test_pattern(request.width, request.height, frame), request.format, request.jpeg_quality);
  };
}

}  // namespace jaus::components
