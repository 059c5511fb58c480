// What makes a set of cameras one the visual sensor can run and report: the
// one source of these rules, next to the cameras' configuration (as the arm's
// are, check_arm_config). jausd's configuration reader reports the same
// error at its line.
#pragma once

#include "jaus/base/expected.hpp"
#include "jaus/components/camera_config.hpp"

namespace jaus::components {

// 1..255 cameras with unique IDs 1..255; a name of 1..15 and a description of
// at most 50 printable ASCII characters (Report Camera Pose's fields); mount
// axes with min <= max and a rate >= 0, zoom within 0..100 percent; a field of
// view with 0 < narrowest <= widest <= 180 degrees; a resolution and a frame
// rate within their ranges; 1..4 image formats, PNG and/or JPEG, once each.
// The error names the first offending camera ("camera 2 (rear): ...").
Expected<void> check_cameras_config(const VisualSensorConfig& config);

}  // namespace jaus::components
