// The velocity state sensor (component 42): the platform's linear velocity and
// rotational rates in its body frame (Query/Report Velocity State), from a
// PoseSource. Presence, service connections and staleness as every sensor
// (sensor_component.hpp).
#pragma once

#include "jaus/components/sensor_component.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

class VelocityStateSensor final : public SensorComponent {
 public:
  VelocityStateSensor(rt::ComponentConfig config, rt::Environment env, PoseSource& source, SensorOptions options = {});

  // The report of a sample, with every field it has.
  static msg::ReportVelocityState velocity_state(const PoseSample& sample);
};

}  // namespace jaus::components
