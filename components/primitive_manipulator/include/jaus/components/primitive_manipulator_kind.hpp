// The primitive manipulator as a component kind (jaus/runtime/component_kind.hpp): what
// a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/components/primitive_manipulator.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

const rt::ComponentKind& primitive_manipulator_kind();
// Its options (command_timeout_s); each error names the option.
Expected<PrimitiveManipulatorOptions> primitive_manipulator_options(const rt::KindOptions& options);

}  // namespace jaus::components
