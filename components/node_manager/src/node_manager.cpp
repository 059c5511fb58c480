#include "jaus/components/node_manager.hpp"

#include <algorithm>
#include <cmath>

namespace jaus::components {

using namespace rt;

namespace {
constexpr std::uint8_t kNodeManagerComponent = 1;
constexpr std::uint8_t kCommunicatorComponent = 35;

bool supports_events(std::uint16_t report_code) {
  return report_code == msg::ReportConfiguration::code || report_code == msg::ReportSubsystemList::code;
}
}  // namespace

NodeManager::NodeManager(ComponentConfig config, Environment env, const NodeDirectory& directory,
                         NodeManagerConfig nm)
    : Component(std::move(config), std::move(env)), directory_(directory), nm_(std::move(nm)) {
  using namespace msg;
  handle<QueryIdentification>(Access::anyone, false, [this](const Header& h, const QueryIdentification& m) {
    ReportIdentification report;
    report.query_type = m.query_type;
    report.authority = control().own_authority();
    switch (m.query_type) {
      case identification::kSubsystem:
        report.type = nm_.subsystem_type;
        report.identification = nm_.subsystem_name;
        break;
      case identification::kNode:
        report.type = nm_.node_type;
        report.identification = nm_.node_name;
        break;
      case identification::kComponent:
        report.type = 0;
        report.identification = name();
        break;
      default:
        log_repeated("Query Identification of an unknown type not answered", LogLevel::info, [&] {
          return "Query Identification type " + std::to_string(m.query_type) + " from " + h.source.to_string() +
                 " not answered: not a subsystem, node or component query";
        });
        return;
    }
    send(h.source, report);
  });
  handle<QueryConfiguration>(Access::anyone, false, [this](const Header& h, const QueryConfiguration& m) {
    send(h.source, configuration(m.query_field));
  });
  handle<QuerySubsystemList>(Access::anyone, false,
                             [this](const Header& h, const QuerySubsystemList&) { send(h.source, subsystem_list()); });
  handle<QueryServices>(Access::anyone, false, [this](const Header& h, const QueryServices&) { send(h.source, services()); });
  handle<CreateEvent>(Access::anyone, false, [this](const Header& h, const CreateEvent& m) { on_create_event(h, m); });
  handle<CancelEvent>(Access::anyone, false, [this](const Header& h, const CancelEvent& m) { on_cancel_event(h, m); });
}

NodeManager::~NodeManager() {
  if (heartbeat_timer_ != kNoTimer) env().scheduler.cancel(heartbeat_timer_);
  if (subsystem_events_timer_ != kNoTimer) env().scheduler.cancel(subsystem_events_timer_);
  for (auto& [id, e] : events_)
    if (e.timer != kNoTimer) env().scheduler.cancel(e.timer);
}

bool NodeManager::initialize() {
  if (heartbeat_timer_ == kNoTimer && nm_.heartbeat_period > Duration::zero()) heartbeat();
  return true;
}

void NodeManager::heartbeat() {
  // To every node manager of the subsystem and to every component of this node.
  const Address& self = address();
  send(Address{self.subsystem, Address::kBroadcast, kNodeManagerComponent, 1}, msg::ReportHeartbeatPulse{});
  send(Address{self.subsystem, self.node, Address::kBroadcast, Address::kBroadcast}, msg::ReportHeartbeatPulse{});
  // Other subsystems drop what is addressed to this one; without a
  // communicator to announce it, this node does, or they would never hear it
  // (and would drop its control and service connections as silent).
  if (!directory_.hosts_component(kCommunicatorComponent))
    send(Address{Address::kBroadcast, Address::kBroadcast, kNodeManagerComponent, 1}, msg::ReportHeartbeatPulse{});
  heartbeat_timer_ = env().scheduler.call_at(env().clock.now() + nm_.heartbeat_period, [this] { heartbeat(); });
}

msg::ReportConfiguration NodeManager::configuration(std::uint8_t) const {
  // This node manager knows its own node; a subsystem query gets the same
  // single node (other nodes answer for themselves).
  msg::NodeEntry node;
  node.node_id = address().node;
  for (const Component* c : directory_.local_components())
    node.components.push_back({c->address().component, c->address().instance});
  msg::ReportConfiguration report;
  report.nodes.push_back(std::move(node));
  return report;
}

msg::ReportSubsystemList NodeManager::subsystem_list() const {
  msg::ReportSubsystemList report;
  report.subsystems = directory_.known_subsystems();
  return report;
}

msg::ReportServices NodeManager::services() const {
  msg::ReportServices report;
  for (const Component* c : directory_.local_components()) report.services.push_back(c->service_entry());
  return report;
}

void NodeManager::confirm_event(const Address& to, std::uint8_t request_id, std::uint16_t code, std::uint8_t event_id,
                                std::optional<double> rate, std::uint8_t response) {
  msg::ConfirmEventRequest confirm;
  confirm.request_id = request_id;
  confirm.message_code = code;
  confirm.event_id = event_id;
  confirm.confirmed_rate_hz = rate;
  confirm.response_code = response;
  send(to, confirm);
}

bool NodeManager::keeps_state_for(const Address& node) const {
  return Component::keeps_state_for(node) ||
         std::any_of(events_.begin(), events_.end(), [&](const auto& e) { return node.covers(e.second.requester); });
}

void NodeManager::on_create_event(const Header& h, const msg::CreateEvent& m) {
  if (sender_standing() == SenderStanding::unrecorded) {
    // Response 3 (refused; Part 3 defines only 0, the RA 3.3 peers use 3 for
    // a refused connection): the node cannot record the requester, so it
    // could never end the event when the requester goes.
    refuse_for_standing(h, "Create Event");
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt, msg::event_response::kRefused);
  }
  if (!supports_events(m.report_code))
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt,
                         msg::event_response::kMessageNotSupported);
  const bool periodic = m.event_type == 0;
  if (!periodic && m.event_type != 1)
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt, msg::event_response::kInvalidSetup);
  const double requested = m.requested_rate_hz.value_or(0);
  if (periodic && !(requested > 0))
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt, msg::event_response::kInvalidSetup);
  const double rate = std::min(requested, nm_.max_event_rate_hz);
  const auto held = std::count_if(events_.begin(), events_.end(),
                                  [&](const auto& entry) { return entry.second.requester == h.source; });
  if (static_cast<std::size_t>(held) >= nm_.max_events_per_requester)
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt, msg::event_response::kRefused);
  std::uint8_t query_field = msg::identification::kSubsystem;
  if (m.query_message && !m.query_message->empty()) query_field = m.query_message->front();

  std::uint8_t id = 0;
  while (events_.contains(id) && id < 255) ++id;
  if (events_.contains(id))
    return confirm_event(h.source, m.request_id, m.report_code, 0, std::nullopt, msg::event_response::kRefused);
  EventSubscription& e = events_[id];
  e.requester = h.source;
  e.report_code = m.report_code;
  e.event_id = id;
  e.request_id = m.request_id;
  e.query_field = query_field;
  e.periodic = periodic;
  e.rate_hz = rate;
  log_repeated({"events created", kNoteworthyBurst}, LogLevel::info, [&] {
    const char* report =
        m.report_code == msg::ReportConfiguration::code ? "Report Configuration" : "Report Subsystem List";
    return "event " + std::to_string(id) + " (" + report + ", " + (periodic ? "periodic" : "every change") + ") for " +
           h.source.to_string();
  });
  confirm_event(h.source, m.request_id, m.report_code, id, periodic ? std::optional<double>(rate) : std::nullopt,
                msg::event_response::kSuccessful);
  if (periodic) send_event(e);
}

void NodeManager::requester_lost(const Address& peer) {
  for (auto it = events_.begin(); it != events_.end();) {
    if (!peer.covers(it->second.requester)) {
      ++it;
      continue;
    }
    if (it->second.timer != kNoTimer) env().scheduler.cancel(it->second.timer);
    log_repeated({"events ended", kNoteworthyBurst}, LogLevel::info, [&] {
      return "event " + std::to_string(it->first) + " for " + it->second.requester.to_string() +
             " ended: requester gone";
    });
    it = events_.erase(it);
  }
}

void NodeManager::on_cancel_event(const Header& h, const msg::CancelEvent& m) {
  for (auto it = events_.begin(); it != events_.end(); ++it) {
    const bool same_id = !m.event_id || *m.event_id == it->first;
    if (it->second.requester == h.source && same_id) {
      if (it->second.timer != kNoTimer) env().scheduler.cancel(it->second.timer);
      confirm_event(h.source, m.request_id, it->second.report_code, it->first, std::nullopt,
                    msg::event_response::kSuccessful);
      events_.erase(it);
      return;
    }
  }
  log_repeated("Cancel Event matching no event", LogLevel::info,
               [&] { return "Cancel Event from " + h.source.to_string() + " matches no event"; });
}

void NodeManager::send_event(EventSubscription& e) {
  e.timer = kNoTimer;
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = e.report_code == msg::ReportSubsystemList::code
                        ? wire::encode_payload(subsystem_list(), payload)
                        : wire::encode_payload(configuration(e.query_field), payload);
  if (!size) return;
  msg::Event event;
  event.event_id = e.event_id;
  event.report_code = e.report_code;
  event.sequence_number = e.sequence++;
  event.report_message.assign(payload.begin(), payload.begin() + static_cast<std::ptrdiff_t>(*size));
  send(e.requester, event);
  if (e.periodic) {
    const auto period = Duration(static_cast<Duration::rep>(std::llround(1e9 / e.rate_hz)));
    const std::uint8_t id = e.event_id;
    e.timer = env().scheduler.call_at(env().clock.now() + period, [this, id] {
      if (auto it = events_.find(id); it != events_.end()) send_event(it->second);
    });
  }
}

void NodeManager::configuration_changed() {
  for (auto& [id, e] : events_)
    if (!e.periodic && e.report_code == msg::ReportConfiguration::code) send_event(e);
}

void NodeManager::subsystems_changed() {
  if (subsystem_events_timer_ != kNoTimer) return;  // the held-back Event will carry this change too
  const auto spacing = nm_.max_event_rate_hz > 0
                           ? Duration(static_cast<Duration::rep>(std::llround(1e9 / nm_.max_event_rate_hz)))
                           : Duration::zero();
  const TimePoint now = env().clock.now();
  if (!last_subsystem_events_ || now >= *last_subsystem_events_ + spacing) return send_subsystem_list_events();
  subsystem_events_timer_ = env().scheduler.call_at(*last_subsystem_events_ + spacing, [this] {
    subsystem_events_timer_ = kNoTimer;
    send_subsystem_list_events();
  });
}

void NodeManager::send_subsystem_list_events() {
  for (auto& [id, e] : events_) {
    if (e.periodic || e.report_code != msg::ReportSubsystemList::code) continue;
    send_event(e);
    last_subsystem_events_ = env().clock.now();  // the rate limit counts Events sent, not changes
  }
}

}  // namespace jaus::components
