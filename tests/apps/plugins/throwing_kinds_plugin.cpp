// A plugin whose kinds function throws.
#include <stdexcept>

#include "broken_plugins.hpp"

namespace {
std::vector<jaus::rt::ComponentKind> kinds() { throw std::runtime_error("no odometer board found"); }
}  // namespace

JAUS_COMPONENT_PLUGIN("throwing_kinds", kinds)
