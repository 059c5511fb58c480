// The hardware interface of the visual sensor: a set of cameras, each a mount
// (pan, tilt, zoom) and an image source. The component (visual_sensor.hpp)
// turns Part 3's percentages into the units below and clamps them to the
// camera's configuration; a backend clamps again and never throws.
//
// Units: pan and tilt in radians (pan positive right, tilt positive up, 0 at
// the camera's home direction), zoom in percent of the lens range (0 widest).
#pragma once

#include <string_view>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/camera_config.hpp"

namespace jaus::components {

// Set Camera Format Options' image format codes this project produces.
namespace image_format {
inline constexpr std::uint8_t kJpeg = 7;
inline constexpr std::uint8_t kPng = 11;
}  // namespace image_format

enum class AxisMode : std::uint8_t { position, rate };

// Position: go to `value` (axis units) at up to the axis' max_rate.
// Rate: move at `value` (axis units per second, signed) until the axis'
// limit or a new command.
struct AxisCommand {
  AxisMode mode = AxisMode::position;
  double value = 0;
  bool operator==(const AxisCommand&) const = default;
};

// An absent axis keeps what it does.
struct MountCommand {
  std::optional<AxisCommand> pan, tilt, zoom;
  bool operator==(const MountCommand&) const = default;
};

struct MountState {
  double pan_rad = 0;
  double tilt_rad = 0;
  double zoom_percent = 0;
  bool moving = false;  // some axis is still going somewhere
};

// What to capture: the format code and the resolution in use.
struct ImageRequest {
  std::uint8_t format = image_format::kPng;
  std::uint16_t width = 320;
  std::uint16_t height = 240;
  std::uint16_t frame_rate_fps = 10;  // a video source's frame period
  int jpeg_quality = 85;              // 1..100, for an encoder that makes JPEG (lowered on a slow link)
};

// One frame: a whole PNG or JPEG file, and the format it really is (a file
// source serves its files as they are).
struct Image {
  std::uint8_t format = image_format::kPng;
  std::uint16_t width = 0;
  std::uint16_t height = 0;
  std::vector<std::uint8_t> data;
};

// One frame's capture as work for another thread (frame_worker.hpp): it holds
// copies of what it needs and shares nothing with its backend that is not
// synchronised, so it may run anywhere, after the backend's state moved on.
using CaptureJob = std::function<Expected<Image>()>;

class Cameras {
 public:
  // Its name among the hardware a host offers a component kind (rt::Backends).
  static constexpr std::string_view kInterface = "cameras";
  static constexpr std::string_view kDescription = "cameras";

  virtual ~Cameras() = default;

  // Every camera, as configured (the component validates IDs).
  virtual const std::vector<CameraConfig>& configs() const = 0;

  // The mount of `camera_id` (unknown IDs are ignored).
  virtual void command_mount(std::uint8_t camera_id, const MountCommand& command) = 0;
  // Safety: stop every axis where it is now (rate motion ends). Idempotent.
  virtual void hold(std::uint8_t camera_id) = 0;
  virtual MountState mount_state(std::uint8_t camera_id) = 0;

  // The frame of `camera_id` now (a source never queues frames).
  virtual Expected<Image> capture(std::uint8_t camera_id, const ImageRequest& request) = 0;
  // The frame of `camera_id` now, captured and encoded by whoever runs the
  // job. By default the frame is captured here, now (a backend whose capture
  // is cheap or cannot leave its thread); the simulated cameras defer it.
  virtual CaptureJob capture_job(std::uint8_t camera_id, const ImageRequest& request) {
    return [image = capture(camera_id, request)] { return image; };
  }
};

}  // namespace jaus::components
