// A plugin whose kind's name is a built-in kind's.
#include "broken_plugins.hpp"

namespace {
std::vector<jaus::rt::ComponentKind> kinds() { return {broken::kind("primitive_driver")}; }
}  // namespace

JAUS_COMPONENT_PLUGIN("taken_kind", kinds)
