// The node manager as a component kind (jaus/runtime/component_kind.hpp): what
// a node host needs to know of it, in this folder only.
#pragma once

#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

const rt::ComponentKind& node_manager_kind();

}  // namespace jaus::components
