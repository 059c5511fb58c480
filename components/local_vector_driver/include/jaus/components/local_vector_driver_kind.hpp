// The local vector driver as a component kind (jaus/runtime/component_kind.hpp).
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

// Options: those of the global vector driver (global_vector_driver_kind.hpp).
// Needs a pose source.
const rt::ComponentKind& local_vector_driver_kind();

}  // namespace jaus::components
