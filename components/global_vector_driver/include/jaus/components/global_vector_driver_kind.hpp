// The global vector driver as a component kind (jaus/runtime/component_kind.hpp).
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: primitive_driver, command_rate_hz, pose_stale_after_s
// (mobility_driver.hpp), heading_tolerance_rad, heading_kp/ki/kd,
// speed_kp/ki/kd (vector_driver.hpp). Needs a pose source.
const rt::ComponentKind& global_vector_driver_kind();

}  // namespace jaus::components
