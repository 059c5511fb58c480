// Node managers broken on purpose, each in a way a discovery case must catch,
// each on a node of its own (subsystem 10 + its flaw's number, node 1, on a
// memory network) with one more component that answers
// (component 50, "worker"). Otherwise each answers as a node manager should:
// identification at every level, configuration, services, subsystem list,
// and an Event to each Create Event subscriber when the node changes.
#pragma once

#include <map>
#include <memory>

#include "jaus/messages/all.hpp"
#include "memory_node.hpp"
#include "jaus/runtime/node_directory.hpp"

namespace jaus::conform::test {

enum class NodeManagerFlaw {
  identifies_every_level_as_component,  // Report Identification always says query type 4
  omits_answering_component,            // Report Configuration leaves out the worker, which answers
  omits_service_entry,                  // Report Services has no entry for the worker
  lists_silent_subsystem,               // Report Subsystem List names subsystem 9, where nothing answers
  never_confirms_event,                 // Create Event gets no Confirm Event Request
  events_after_cancel,                  // Cancel Event is confirmed but the Events go on
};

inline constexpr std::uint8_t kWorkerComponent = 50;
inline const Address kSilentSubsystemManager{9, 1, 1, 1};

inline std::uint8_t subsystem_of(NodeManagerFlaw flaw) {
  return static_cast<std::uint8_t>(10 + static_cast<int>(flaw));
}
inline Address broken_manager(NodeManagerFlaw flaw) { return Address{subsystem_of(flaw), 1, 1, 1}; }

// A component with only the core services: something that answers.
class Worker final : public rt::Component {
 public:
  Worker(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {}
};

class BrokenNodeManager final : public rt::Component, public rt::ConfigurationObserver {
 public:
  BrokenNodeManager(rt::ComponentConfig config, rt::Environment env, const rt::NodeDirectory& directory,
                    NodeManagerFlaw flaw)
      : Component(std::move(config), std::move(env)), directory_(directory), flaw_(flaw) {
    using namespace msg;
    handle<QueryIdentification>(Access::anyone, false, [this](const Header& h, const QueryIdentification& m) {
      const std::uint16_t type = m.query_type == identification::kSubsystem ? 10001
                                 : m.query_type == identification::kNode    ? 40001
                                                                            : 0;
      const std::uint8_t said =
          flaw_ == NodeManagerFlaw::identifies_every_level_as_component ? identification::kComponent : m.query_type;
      send(h.source, ReportIdentification{{said, 0, type, "broken"}});
    });
    handle<QueryConfiguration>(Access::anyone, false,
                               [this](const Header& h, const QueryConfiguration&) { send(h.source, configuration()); });
    handle<QuerySubsystemList>(Access::anyone, false, [this](const Header& h, const QuerySubsystemList&) {
      ReportSubsystemList list;
      list.subsystems = directory_.known_subsystems();
      if (flaw_ == NodeManagerFlaw::lists_silent_subsystem) list.subsystems.push_back(kSilentSubsystemManager);
      send(h.source, list);
    });
    handle<QueryServices>(Access::anyone, false, [this](const Header& h, const QueryServices&) {
      ReportServices report;
      for (const Component* c : directory_.local_components())
        if (flaw_ != NodeManagerFlaw::omits_service_entry || c->address().component != kWorkerComponent)
          report.services.push_back(c->service_entry());
      send(h.source, report);
    });
    handle<CreateEvent>(Access::anyone, false, [this](const Header& h, const CreateEvent& m) {
      if (flaw_ == NodeManagerFlaw::never_confirms_event) return;
      const std::uint8_t id = next_event_id_++;
      subscribers_[id] = h.source;
      ConfirmEventRequest confirm;
      confirm.request_id = m.request_id;
      confirm.message_code = m.report_code;
      confirm.event_id = id;
      send(h.source, confirm);
    });
    handle<CancelEvent>(Access::anyone, false, [this](const Header& h, const CancelEvent& m) {
      const std::uint8_t id = m.event_id.value_or(0);
      ConfirmEventRequest confirm;
      confirm.request_id = m.request_id;
      confirm.message_code = m.message_code.value_or(0);
      confirm.event_id = id;
      send(h.source, confirm);
      if (flaw_ != NodeManagerFlaw::events_after_cancel) subscribers_.erase(id);
    });
  }

  void configuration_changed() override {
    std::vector<std::uint8_t> payload(kMaxPayloadSize);
    const auto size = wire::encode_payload(configuration(), payload);
    if (!size) return;
    for (const auto& [id, requester] : subscribers_) {
      msg::Event event;
      event.event_id = id;
      event.report_code = msg::ReportConfiguration::code;
      event.sequence_number = sequence_[id]++;
      event.report_message.assign(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(*size));
      send(requester, event);
    }
  }

 private:
  msg::ReportConfiguration configuration() const {
    msg::NodeEntry node{address().node, {}};
    for (const Component* c : directory_.local_components())
      if (flaw_ != NodeManagerFlaw::omits_answering_component || c->address().component != kWorkerComponent)
        node.components.push_back({c->address().component, c->address().instance});
    return msg::ReportConfiguration{{{node}}};
  }

  const rt::NodeDirectory& directory_;
  NodeManagerFlaw flaw_;
  std::uint8_t next_event_id_ = 0;
  std::map<std::uint8_t, Address> subscribers_;  // by event ID
  std::map<std::uint8_t, std::uint8_t> sequence_;
};

class BrokenDiscoveryNode {
 public:
  BrokenDiscoveryNode(rt::VirtualTime& time, testing::MemoryNetwork& network, NodeManagerFlaw flaw)
      : node_(time, network, node_config(flaw)) {
    node_.emplace<BrokenNodeManager>("broken node manager", 1, node_.node(), flaw);
    node_.emplace<Worker>("worker", kWorkerComponent);
  }
  node::Node& node() { return node_.node(); }

 private:
  static node::NodeConfig node_config(NodeManagerFlaw flaw) {
    node::NodeConfig config;
    config.subsystem = subsystem_of(flaw);
    config.node = 1;
    return config;
  }

  test_support::MemoryNode node_;
};

}  // namespace jaus::conform::test
