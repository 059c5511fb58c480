// The local pose sensor as a component kind (jaus/runtime/component_kind.hpp):
// what a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: stale_after_s (sensor_component.hpp). Making one on a pose source
// whose sample has no local position (the vehicle's `local_frame: false`) is
// an error that says so; a source without a sample yet is taken as it comes.
const rt::ComponentKind& local_pose_sensor_kind();

}  // namespace jaus::components
