// The global pose sensor as a component kind (jaus/runtime/component_kind.hpp): what
// a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/components/global_pose_sensor.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

const rt::ComponentKind& global_pose_sensor_kind();
// Its options (stale_after_s, local_pose); each error names the option.
Expected<GlobalPoseSensorOptions> global_pose_sensor_options(const rt::KindOptions& options);

}  // namespace jaus::components
