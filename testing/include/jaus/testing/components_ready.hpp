// Whether every component a node hosts is Ready: what a test waits for
// before it acts (the drivers, for one, wait for the primitive driver's
// specifications), with run_until.
#pragma once

#include <string>
#include <vector>

#include "jaus/runtime/component.hpp"
#include "jaus/runtime/lifecycle.hpp"
#include "jaus/runtime/node_directory.hpp"

namespace jaus::testing {

// The components of `node` not Ready, each as "1.1.33.1 standby"; empty when all are.
inline std::vector<std::string> components_not_ready(const rt::NodeDirectory& node) {
  std::vector<std::string> not_ready;
  for (const rt::Component* c : node.local_components())
    if (c->state() != rt::PrimaryStatus::ready)
      not_ready.push_back(c->address().to_string() + " " + std::string(rt::to_string(c->state())));
  return not_ready;
}

inline bool all_components_ready(const rt::NodeDirectory& node) {
  for (const rt::Component* c : node.local_components())
    if (c->state() != rt::PrimaryStatus::ready) return false;
  return true;
}

}  // namespace jaus::testing
