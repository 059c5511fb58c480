// What a node's configuration says of each camera of the visual sensor
// (jausd.yaml `cameras:`; docs/configuration.md). The simulated cameras
// (simulated_cameras.hpp) are built from it; a real backend reads the same
// limits so that the component clamps commands the same way.
#pragma once

#include <cstdint>
#include <string>
#include <iterator>
#include <vector>

namespace jaus::components {

// One axis of a camera mount. Position mode targets are clipped to
// [min, max]; rate mode moves at up to max_rate. An axis with min == max does
// not move (the camera has no such axis).
struct MountAxis {
  double min = 0;
  double max = 0;
  double max_rate = 0;  // per second
  bool movable() const { return max > min && max_rate > 0; }
};

struct CameraConfig {
  std::uint8_t id = 1;          // 1..255
  std::string name = "camera";  // Report Camera Pose, up to 15 characters
  std::string description;      // Report Camera Capabilities, up to 50 characters

  // Where the camera is on the platform (vehicle frame: x forward, y right,
  // z down, metres) and where it looks at pan = tilt = 0 (yaw from the
  // vehicle's x axis, positive right; pitch positive up; radians).
  double x_m = 0, y_m = 0, z_m = 0;
  double home_yaw_rad = 0, home_pitch_rad = 0;

  // The mount: pan (rad, positive right), tilt (rad, positive up), zoom
  // (percent of the lens range: 0 widest, 100 narrowest).
  MountAxis pan;
  MountAxis tilt;
  MountAxis zoom;

  // The lens: the horizontal field of view at zoom 0 and at zoom 100; the
  // vertical one follows from the image's aspect ratio.
  double widest_horizontal_fov_rad = 1.0;
  double narrowest_horizontal_fov_rad = 1.0;

  // Images: the resolution and frame rate in use and what Set Camera
  // Capabilities may choose from.
  std::uint16_t width = 320, height = 240;
  std::uint16_t min_width = 16, min_height = 16, max_width = 1280, max_height = 960;
  std::uint16_t frame_rate_fps = 10, min_frame_rate_fps = 1, max_frame_rate_fps = 30;
  // The image formats it can send (Set Camera Format Options codes: 11 PNG,
  // 7 JPEG), the first in use at start. (From a named array: GCC 12 at -O2
  // warns, wrongly, that an initializer list's array may be uninitialized.)
  static constexpr std::uint8_t kDefaultImageFormats[] = {11, 7};
  std::vector<std::uint8_t> image_formats =
      std::vector<std::uint8_t>(std::begin(kDefaultImageFormats), std::end(kDefaultImageFormats));

  // Where its images come from: a generated, changing test pattern (empty),
  // or the PNG and JPEG files of this directory, in name order, in a loop.
  std::string image_directory;
};

struct VisualSensorConfig {
  std::vector<CameraConfig> cameras;  // at least one; IDs unique
};

}  // namespace jaus::components
