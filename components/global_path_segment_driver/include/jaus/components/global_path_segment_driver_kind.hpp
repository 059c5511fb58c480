// The global path segment driver as a component kind (jaus/runtime/component_kind.hpp).
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: path_segment_driver_option_keys() (path_segment_driver.hpp).
const rt::ComponentKind& global_path_segment_driver_kind();

}  // namespace jaus::components
