// The global waypoint driver as a component kind (jaus/runtime/component_kind.hpp).
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: the MobilityDriver's (primitive_driver, command_rate_hz,
// pose_stale_after_s) and lookahead_m, arrival_tolerance_m,
// travel_speed_mps, max_deceleration_mps2, max_waypoints
// (waypoint_driver_options.hpp; docs/components.md).
const rt::ComponentKind& global_waypoint_driver_kind();

}  // namespace jaus::components
