// The primitive driver as a component kind (jaus/runtime/component_kind.hpp): what
// a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/components/primitive_driver.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

const rt::ComponentKind& primitive_driver_kind();
// Its options (command_timeout_s, stop_brake_percent); each error names the option.
Expected<PrimitiveDriverOptions> primitive_driver_options(const rt::KindOptions& options);

}  // namespace jaus::components
