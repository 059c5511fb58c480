// The visual sensor as a component kind (jaus/runtime/component_kind.hpp): what
// a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/components/visual_sensor.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

const rt::ComponentKind& visual_sensor_kind();
// Its options (image_connections_per_requester); each error names the option.
Expected<VisualSensorOptions> visual_sensor_options(const rt::KindOptions& options);

}  // namespace jaus::components
