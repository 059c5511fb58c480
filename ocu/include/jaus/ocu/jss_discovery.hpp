// Discovering a JSS system the way JSS clients do (docs/jss.md, "Discovery"; fkie IOP's
// DiscoveryClient): Query Identification (type 2, subsystem) to every
// subsystem, resent every identification_period until a subsystem answers;
// then, for each subsystem that answered, Query Configuration (nodes and
// components), Query Service List (core v1.1; Query Services, v1.0, when it
// is not answered), Query Identification type 4 for each component's name
// and type 3 of each node (asked of its discovery component, else its first).
// The result is typed: subsystems, nodes, components with names and service
// URIs. Bounded whatever peers send.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/ocu/jss_session.hpp"

namespace jaus::ocu {

struct JssService {
  std::string uri;  // "urn:jaus:jss:mobility:PrimitiveDriver"
  std::uint8_t major = 0;
  std::uint8_t minor = 0;
  bool operator==(const JssService&) const = default;
};

struct JssComponent {
  jss::JssId id;
  std::string name;           // Report Identification type 4; empty when not answered
  std::uint8_t instance = 0;  // 0 for JSS components (legacy RA components list theirs)
  std::vector<JssService> services;
  // Whether it has `uri` (any version); "PrimitiveDriver" matches the full URI's last part.
  bool has(std::string_view uri) const;
};

struct JssNode {
  std::uint8_t id = 0;
  std::string name;  // Report Identification type 3 (asked of a component of the node); empty when not answered
  std::vector<JssComponent> components;
};

struct JssSubsystem {
  std::uint16_t id = 0;
  std::string name;              // Report Identification type 2
  std::uint16_t type = 0;        // 10001 vehicle, 20001 OCU, ...
  jss::JssId discovery;          // who answered (the Discovery service)
  bool services_listed = false;  // Query Service List or Query Services answered
  std::vector<JssNode> nodes;
  // The components with `uri` (see JssComponent::has), in ID order.
  std::vector<const JssComponent*> with(std::string_view uri) const;
};

struct JssSystem {
  std::vector<JssSubsystem> subsystems;  // in ID order; our own subsystem left out
  std::size_t components_left_out = 0;   // beyond the bounds
  const JssSubsystem* find(std::uint16_t subsystem) const;
  const JssComponent* find(const jss::JssId& component) const;
};

struct JssDiscoveryOptions {
  // Where Query Identification goes: every subsystem, or one.
  jss::JssId target = kJssBroadcast;
  // Query Identification again this often until a subsystem answers (IOP: 5 s).
  rt::Duration identification_period = std::chrono::seconds(5);
  // After the first answer, other subsystems are listened for this long.
  rt::Duration gather = std::chrono::milliseconds(500);
  // No subsystem answered within this: an error.
  rt::Duration timeout = std::chrono::seconds(6);
  // Each follow-up query (resent every 250 ms) is given this long.
  rt::Duration query_timeout = std::chrono::seconds(1);
  bool component_names = true;  // Query Identification type 4 to each component
  std::size_t max_subsystems = 64;
  std::size_t max_components_per_subsystem = 1024;
};

// Errors: timeout ("no JSS subsystem answered Query Identification within
// 6 s"), interrupted. A subsystem that answers its identification but not a
// later query is still in the result, with what it did answer.
Expected<JssSystem> discover_jss(JssSession& session, const JssDiscoveryOptions& options = {});

}  // namespace jaus::ocu
