// The local waypoint driver as a component kind (jaus/runtime/component_kind.hpp).
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: as the global waypoint driver's (waypoint_driver_options.hpp).
// Making one on a pose source known to have no local frame is an error.
const rt::ComponentKind& local_waypoint_driver_kind();

}  // namespace jaus::components
