// How the node and the component that describes it (the node manager) see
// each other: the node knows no concrete component, only these two views.
#pragma once

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
  // Subsystems known to be alive (one address per subsystem, e.g. its node manager).
  virtual std::vector<Address> known_subsystems() const = 0;
};

// A hosted component that wants to hear when the node's set of components
// changes (the node manager: its Report Configuration events). The node
// finds it when the component is added; there is at most one per node.
class ConfigurationObserver {
 public:
  virtual void configuration_changed() = 0;

 protected:
  ~ConfigurationObserver() = default;
};

}  // namespace jaus::rt
