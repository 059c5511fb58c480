// The component kinds a node host can build, and how one is built from its
// configuration entry. A new component kind is one registry line in
// component_kinds.cpp (name, RA 3.x component ID, option keys) and one case
// in make_component(); configuration readers check kinds and options here.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/components/camera.hpp"
#include "jaus/components/drive.hpp"
#include "jaus/components/manipulator_arm.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/components/pose_source.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::host {

struct ComponentKind {
  std::string_view name;
  std::uint8_t default_id;  // RA 3.x component ID
  std::vector<std::string_view> options;
};
std::span<const ComponentKind> component_kinds();
const ComponentKind* find_component_kind(std::string_view name);

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

// The hardware a node's vehicle components drive and read: the host's
// simulated vehicle, cameras and arm by default (a Clearpath platform's
// backends in bridge/ otherwise).
struct VehicleBackends {
  components::Drive* drive = nullptr;
  components::PoseSource* pose = nullptr;
  components::Cameras* cameras = nullptr;
  components::ManipulatorArm* arm = nullptr;
};

// What every component of the node shares, and what the node manager says of it.
struct ComponentSettings {
  rt::ComponentConfig defaults;  // controller timeout, refusals, service connection limits
  components::NodeManagerConfig identity;  // subsystem and node names and types, heartbeat period
};

// The component `spec` asks for, on `node` at (subsystem, node) of the node,
// on `vehicle` for the kinds that drive or sense it. An error
// (invalid_argument) when this build cannot make the kind, an option is
// invalid, or the kind needs a backend `vehicle` lacks.
Expected<std::unique_ptr<rt::Component>> make_component(const ComponentSpec& spec, const ComponentSettings& settings,
                                                        node::Node& node, const VehicleBackends& vehicle = {});
// The hardware a kind drives or reads (the host then makes its simulation).
enum class Hardware { none, vehicle, cameras, arm };
Hardware hardware_of(std::string_view kind);
bool needs_vehicle(std::string_view kind);  // hardware_of(kind) == Hardware::vehicle
// The kind moves hardware (a drive, an arm, camera mounts): with
// emergency_scope vehicle, one Set Emergency holds every such component.
bool moves_hardware(std::string_view kind);

}  // namespace jaus::host
