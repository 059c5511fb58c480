// The node manager (component 1, instance 1): the node's face to discovery
// (RA 3.2/3.3 dynamic configuration, docs/wire-format.md). It sends Report
// Heartbeat Pulse at a configured rate to (subsystem, 255, 1, 1) and
// (subsystem, node, 255, 255), and to (255, 255, 1, 1) when the node hosts no
// communicator (which otherwise announces the subsystem to other subsystems),
// so a node is always heard across subsystems. It answers Query
// Identification, Configuration, Subsystem List (this subsystem and every
// other one the node has heard, until it falls silent) and Services, and
// keeps Create Event subscriptions to Report Configuration and Report
// Subsystem List, sending an Event on every change (or periodically).
// A Create Event from a sender the node could not record (its tables full)
// is refused (Confirm Event Request, response 3) and stored nowhere: nothing
// would end it when the sender goes (issue 28). Observers may subscribe.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/messages/communications_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/messages/event_messages.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/node_directory.hpp"

namespace jaus::components {

struct NodeManagerConfig {
  // What a host offers the node's components (rt::Backends): the node's identity.
  static constexpr std::string_view kInterface = "node_identity";
  static constexpr std::string_view kDescription = "the node's identity";

  rt::Duration heartbeat_period = std::chrono::seconds(1);
  std::string subsystem_name = "jaus-node";
  std::uint16_t subsystem_type = 10001;  // 10001+ vehicle, 20001+ OCU, 30001+ other
  std::string node_name = "node";
  std::uint16_t node_type = 40001;
  // Create Event: a periodic event is confirmed at most at this rate (Report
  // Configuration changes rarely), and each requester holds at most this many.
  double max_event_rate_hz = 10;
  std::size_t max_events_per_requester = 4;
};

class NodeManager final : public rt::Component, public rt::ConfigurationObserver {
 public:
  NodeManager(rt::ComponentConfig config, rt::Environment env, const rt::NodeDirectory& directory, NodeManagerConfig nm);
  ~NodeManager() override;

  // The node added or removed a component: subscribers get an Event.
  void configuration_changed() override;
  // A subsystem was found or lost: subscribers to the subsystem list get an
  // Event, at most max_event_rate_hz (a flood of new sources is one Event).
  void subsystems_changed() override;
  std::size_t event_subscriptions() const { return events_.size(); }
  // Adds its event subscribers to what the component base keeps state for.
  bool keeps_state_for(const Address& node) const override;

 protected:
  bool initialize() override;
  // A requester that is gone gets no more events.
  void requester_lost(const Address& peer) override;

 private:
  struct EventSubscription {
    Address requester;
    std::uint16_t report_code = 0;  // Report Configuration or Report Subsystem List
    std::uint8_t event_id = 0;
    std::uint8_t request_id = 0;
    std::uint8_t query_field = msg::identification::kSubsystem;
    bool periodic = false;
    double rate_hz = 0;
    std::uint8_t sequence = 0;
    rt::TimerId timer = rt::kNoTimer;
  };

  void heartbeat();
  msg::ReportConfiguration configuration(std::uint8_t query_field) const;
  msg::ReportServices services() const;
  msg::ReportSubsystemList subsystem_list() const;
  void send_subsystem_list_events();
  void on_create_event(const Header& h, const msg::CreateEvent& m);
  void on_cancel_event(const Header& h, const msg::CancelEvent& m);
  void send_event(EventSubscription& e);
  void confirm_event(const Address& to, std::uint8_t request_id, std::uint16_t code, std::uint8_t event_id,
                     std::optional<double> rate, std::uint8_t response);

  const rt::NodeDirectory& directory_;
  NodeManagerConfig nm_;
  rt::TimerId heartbeat_timer_ = rt::kNoTimer;
  rt::TimerId subsystem_events_timer_ = rt::kNoTimer;  // change events held back by the rate limit
  std::optional<rt::TimePoint> last_subsystem_events_;
  std::map<std::uint8_t, EventSubscription> events_;  // by event ID
};

}  // namespace jaus::components
