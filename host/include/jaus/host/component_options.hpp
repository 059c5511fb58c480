// The options of each component kind, read from a ComponentSpec's text
// values (a configuration file's `options:` map) into the component's own
// options struct. One reader per kind, used by make_component() and by
// configuration readers that check a file before anything is built.
#pragma once

#include <optional>
#include <string>

#include "jaus/components/global_pose_sensor.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/components/primitive_manipulator.hpp"
#include "jaus/components/visual_sensor.hpp"
#include "jaus/components/sensor_component.hpp"
#include "jaus/host/component_kinds.hpp"

namespace jaus::host {

// Each error (invalid_argument) names the option, what it must be and what it was.
Expected<components::PrimitiveDriverOptions> primitive_driver_options(const ComponentSpec& spec);
Expected<components::GlobalPoseSensorOptions> global_pose_sensor_options(const ComponentSpec& spec);
Expected<components::SensorOptions> velocity_state_sensor_options(const ComponentSpec& spec);
Expected<components::VisualSensorOptions> visual_sensor_options(const ComponentSpec& spec);
Expected<components::PrimitiveManipulatorOptions> primitive_manipulator_options(const ComponentSpec& spec);

// The first problem with the spec's options, or nothing; `line` is the
// option's line when the spec came from a file and knows it.
struct OptionProblem {
  std::string what;
  int line = 0;
};
std::optional<OptionProblem> check_component_options(const ComponentSpec& spec);

}  // namespace jaus::host
