// The `cameras:` and `manipulator:` sections of jausd.yaml: the visual
// sensor's cameras and the primitive manipulator's arm, in the units a user
// writes (degrees, percent) read into the components' own configuration
// (SI units). Errors are thrown as yaml_reader::Failure with their line, like
// every section; the rules are the components' (check_cameras_config,
// check_arm_config), which also check values set in code. docs/configuration.md
// is the reference.
#pragma once

#include "config_reader.hpp"
#include "jaus/components/arm_config.hpp"
#include "jaus/components/camera_config.hpp"
#include "jaus/components/camera_rules.hpp"

namespace jausd {

// The example of the default configuration: a pan-tilt-zoom camera at the
// front and a fixed one at the rear; a six-joint arm.
jaus::components::VisualSensorConfig default_cameras();
jaus::components::ArmConfig default_arm();

void read_cameras(const yaml_reader::Entry& section, jaus::components::VisualSensorConfig& cameras);
void read_manipulator(const yaml_reader::Entry& section, jaus::components::ArmConfig& arm);

}  // namespace jausd
