// What jaus-console's core is told at start: the deadman and the periods,
// the rate of the reports it follows, the camera's mount, its version and
// where its events are logged.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "jaus/runtime/component.hpp"

namespace jaus::console {

struct ConsoleOptions {
  std::chrono::milliseconds deadman{250};       // a drive older than this stops
  std::chrono::milliseconds drive_period{50};   // Set Wrench Effort at 20 Hz while held
  std::chrono::milliseconds poll_period{1000};  // Query Component Status/Control of every component
  std::chrono::milliseconds link_period{1000};  // the `link` frame
  double report_rate_hz = 5;                    // pose, velocity, joints, images by service connection
  std::uint8_t camera_id = 1;
  // Set Camera Pose carries percent of the mount's full scale (the larger of
  // |min| and |max|), which no report tells: these are the default jausd
  // camera's (config/jausd.yaml: pan +-170 deg, tilt -30..90 deg).
  double camera_pan_full_scale_deg = 170;
  double camera_tilt_full_scale_deg = 90;
  std::string version;
  jaus::rt::LogFn log;
};

}  // namespace jaus::console
