// How the node and the component that describes it (the node manager) see
// each other: the node knows no concrete component, only these two views.
#pragma once

#include <cstdint>
#include <vector>

#include "jaus/core/address.hpp"

namespace jaus::rt {

class Component;

// What the node manager reads of its node.
class NodeDirectory {
 public:
  virtual ~NodeDirectory() = default;
  // Components hosted on this node (the node manager included).
  virtual std::vector<const Component*> local_components() const = 0;
  // Subsystems known to be alive, this one first: one address per subsystem,
  // its node manager (or communicator) heard (Report Subsystem List).
  virtual std::vector<Address> known_subsystems() const = 0;
  // Whether a component with this ID is hosted here (the node manager asks
  // for the communicator, which announces the subsystem to others).
  virtual bool hosts_component(std::uint8_t component_id) const = 0;
};

// A hosted component that wants to hear when the node's set of components
// changes (the node manager: its Report Configuration events). The node
// finds it when the component is added; there is at most one per node.
class ConfigurationObserver {
 public:
  virtual void configuration_changed() = 0;
  // A subsystem was heard for the first time, or fell silent.
  virtual void subsystems_changed() {}

 protected:
  ~ConfigurationObserver() = default;
};

}  // namespace jaus::rt
