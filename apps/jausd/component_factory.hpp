// The components jausd can host, made from their configuration entries. A
// new component kind is a registry entry in jausd_config.cpp and a case here.
#pragma once

#include <memory>

#include "jaus/node/node.hpp"
#include "jaus/runtime/component.hpp"
#include "jausd_config.hpp"

namespace jausd {

// Null when the kind is not one this build can make (the configuration
// checks kinds first, so that is a programming error, reported by the caller).
std::unique_ptr<jaus::rt::Component> make_component(const ComponentSpec& spec, const JausdConfig& config,
                                                    jaus::node::Node& node);

}  // namespace jausd
