// The component kinds a node host can build, and how one is built from its
// configuration entry. A kind describes itself (rt::ComponentKind,
// jaus/runtime/component_kind.hpp) in its own folder, components/<name>/;
// the host walks the list and never names one. The list is the kinds
// components/ lists (builtin_component_kinds(), generated at build time) and
// those added at run time (add_component_kind: a test's, later a plugin's).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/components/node_manager.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::host {

using ComponentKind = rt::ComponentKind;

// Every kind this process knows, built-in first. Add or remove kinds before
// any host opens or configuration is read (pointers into the list stay valid
// until the next change).
const std::vector<ComponentKind>& component_kinds();
const ComponentKind* find_component_kind(std::string_view name);
// A kind of one's own: an error (invalid_argument) when the name is empty or
// taken, or it cannot make components.
Expected<void> add_component_kind(ComponentKind kind);
bool remove_component_kind(std::string_view name);  // false: no such kind
// What components/ lists (generated from its CMake files).
std::vector<const ComponentKind*> builtin_component_kinds();

// One component a node should host.
struct ComponentSpec {
  std::string kind;       // a registered kind (component_kinds())
  std::uint8_t id = 0;    // component ID, 1..254 (default: the kind's RA ID)
  std::uint8_t instance = 1;
  std::uint8_t authority = 0;
  std::string name;       // Report Identification of the component (default: the kind)
  std::map<std::string, std::string> options;  // kind-specific, keys checked against the kind
  int line = 0;           // where a configuration file declares it (0: not from a file)
  std::map<std::string, int> option_lines;     // where each option is (from a file)
};

// What every component of the node shares, and what the node manager says of it.
struct ComponentSettings {
  rt::ComponentConfig defaults;  // controller timeout, refusals, service connection limits
  components::NodeManagerConfig identity;  // subsystem and node names and types, heartbeat period
};

// The component `spec` asks for, on `node` at (subsystem, node) of the node,
// with `backends`: the hardware (by interface) the kinds that drive or sense
// it need. An error (invalid_argument) when no kind has the name, an option
// is invalid, or the kind needs a backend `backends` lacks.
Expected<std::unique_ptr<rt::Component>> make_component(const ComponentSpec& spec, const ComponentSettings& settings,
                                                        node::Node& node, const rt::Backends& backends = {});
// The kind drives or reads hardware (its `needs`): it follows an emergency
// latch the host keeps. False for a kind nobody knows.
bool has_hardware(std::string_view kind);
// The kind moves hardware (a drive, an arm, camera mounts): with
// emergency_scope vehicle, one Set Emergency holds every such component.
bool moves_hardware(std::string_view kind);

}  // namespace jaus::host
