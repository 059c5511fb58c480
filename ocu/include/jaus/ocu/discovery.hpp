// What `jausctl discover` learns about the JAUS system, and which queries it
// asks next (docs/wire-format.md, "Typical OCU sequence"): a subsystem heard
// for the first time is asked for its identification, configuration and
// subsystem list, each node for its identification and configuration, each
// component for its identification and services. Every subsystem in a
// subsystem list is then asked in turn, so an OCU that reaches one node
// learns the subsystems that node knows (it relays to them). Sans-I/O:
// messages in, queries out; the command sends them. Over a lossy link a
// question or its answer may be lost: unanswered() lists the questions asked
// and not answered yet, for the command to ask again.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "jaus/core/header.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::ocu {

struct Identification {
  std::string name;
  std::uint16_t type = 0;
  std::uint8_t authority = 0;
};

struct DiscoveredComponent {
  jaus::Address address;
  std::optional<Identification> identification;
  // What the component itself answered to Query Services, if it did.
  std::optional<std::vector<jaus::msg::ServiceEntry>> own_services;
};

struct DiscoveredNode {
  std::uint8_t id = 0;
  std::optional<Identification> identification;
  std::map<std::pair<std::uint8_t, std::uint8_t>, DiscoveredComponent> components;  // by (component, instance)
  // The node manager's Report Services: one entry per component ID on the node.
  std::map<std::uint16_t, jaus::msg::ServiceEntry> services_by_type;
};

struct DiscoveredSubsystem {
  std::uint8_t id = 0;
  std::optional<Identification> identification;
  std::map<std::uint8_t, DiscoveredNode> nodes;
};

struct DiscoveryQuery {
  enum class Kind { identification, configuration, services, subsystem_list };
  jaus::Address to;
  Kind kind = Kind::identification;
  std::uint8_t field = 0;  // query type (identification) or query field (configuration)
  bool operator==(const DiscoveryQuery&) const = default;
};

class Discovery {
 public:
  // Each component costs two queries and a few hundred bytes: a subsystem
  // that claims more than kMaxComponentsPerSubsystem is not believed, and the
  // whole system is bounded too (memory and traffic whatever peers send).
  // The total allows 64 components in each of the 254 subsystems
  // (bench_scale: a system-wide 1024 cut 170 two-node vehicles short).
  static constexpr std::size_t kMaxComponentsPerSubsystem = 1024;
  static constexpr std::size_t kMaxComponents = 254 * 64;

  // `self` is the OCU: its own node is left out.
  explicit Discovery(jaus::Address self) : self_(self) {}

  // The first query: every node manager that hears it says who it is.
  std::vector<DiscoveryQuery> start();
  // Something came from `source` (a heartbeat, any message).
  std::vector<DiscoveryQuery> heard(const jaus::Address& source);
  // A message addressed to the OCU (the replies).
  std::vector<DiscoveryQuery> received(const jaus::Header& header, std::span<const std::uint8_t> payload,
                                       jaus::wire::Dialect dialect);

  // Every question asked whose answer has not come (a Report Configuration
  // answers both configuration questions of its node manager: it does not
  // say which it answers).
  std::vector<DiscoveryQuery> unanswered() const;

  const std::map<std::uint8_t, DiscoveredSubsystem>& subsystems() const { return subsystems_; }
  std::size_t component_count() const;
  // Components heard of but left out by the bounds above.
  std::size_t components_left_out() const { return components_left_out_; }

  // A component's services: its own answer, else its node manager's entry for its component ID.
  static std::vector<jaus::msg::ServiceEntry> services_of(const DiscoveredNode& node,
                                                          const DiscoveredComponent& component);

 private:
  using Kind = DiscoveryQuery::Kind;
  bool is_self(const jaus::Address& a) const { return a.subsystem == self_.subsystem && a.node == self_.node; }
  DiscoveredNode& node_of(std::uint8_t subsystem, std::uint8_t node);
  const DiscoveredNode* find_node(std::uint8_t subsystem, std::uint8_t node) const;
  void add_node(std::uint8_t subsystem, std::uint8_t node, std::vector<DiscoveryQuery>& out);
  void add_component(const jaus::Address& address, std::vector<DiscoveryQuery>& out);
  std::size_t components_in(std::uint8_t subsystem) const;
  // Asks once per key: a subsystem-wide question is keyed by the subsystem alone.
  void ask(std::vector<DiscoveryQuery>& out, const jaus::Address& to, Kind kind, std::uint8_t field,
           const jaus::Address& key);

  using QuestionKey = std::tuple<jaus::Address, Kind, std::uint8_t>;
  struct Question {
    DiscoveryQuery query;
    bool answered = false;
  };
  void answered(const jaus::Address& key, Kind kind, std::uint8_t field);

  jaus::Address self_;
  std::map<std::uint8_t, DiscoveredSubsystem> subsystems_;
  std::size_t components_left_out_ = 0;
  std::map<QuestionKey, Question> asked_;
};

}  // namespace jaus::ocu
