// The discovery cases: what a node manager (component 1) reports of its
// subsystem, node and components (RA 3.2/3.3 dynamic configuration, laid out
// in docs/wire-format.md, "Liveness and discovery"; the Part 3 text here predates
// those messages), checked against each other and against what answers.
// Other components answer only for themselves (the core cases check that).
// Nothing here changes the node: the one event created is cancelled.
#include <algorithm>
#include <set>

#include "case_support.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/messages/event_messages.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

constexpr std::uint8_t kNodeManager = 1;

std::string not_a_node_manager(const ComponentUnderTest& component) {
  if (component.address.component == kNodeManager) return {};
  return "not a node manager (component ID 1): only the node manager speaks for its node and subsystem";
}

// Sends `query` to `to` (not necessarily the component under test), waits
// for R from it and records the reply (the runner records only the target's).
template <class R, class Q>
Expected<R> ask_of(CaseContext& c, const Address& to, const Q& query) {
  send(c, to, query);
  auto reply = c.session.await_reply(to, {R::code}, c.reply_timeout);
  if (!reply) return unexpected(reply.error());
  if (to != c.target())
    c.exchange.push_back(Exchanged{false, reply->header, reply->payload, c.session.clock().now() - c.started});
  return decode<R>(c, *reply);
}

std::string identification_level(std::uint8_t type) {
  switch (type) {
    case msg::identification::kSubsystem:
      return "subsystem";
    case msg::identification::kNode:
      return "node";
    case msg::identification::kComponent:
      return "component";
  }
  return "type " + std::to_string(type);
}

CaseOutcome identification_at_each_level(CaseContext& c) {
  std::string seen;
  for (const std::uint8_t type :
       {msg::identification::kSubsystem, msg::identification::kNode, msg::identification::kComponent}) {
    const std::string level = identification_level(type);
    auto report = ask<msg::ReportIdentification>(c, msg::QueryIdentification{{type}});
    if (!report) return fail("Query Identification (" + level + "): " + report.error().message());
    if (report->query_type != type)
      return fail("Query Identification (" + level + ", " + std::to_string(type) + ") answered with query type " +
                  std::to_string(report->query_type));
    // The type ranges (docs/wire-format.md, "Liveness and discovery"): 10001+
    // vehicle, 20001+ OCU, 30001+ other subsystem; 40001+ node.
    if (type == msg::identification::kSubsystem && (report->type < 10001 || report->type > 40000))
      return fail("subsystem type " + std::to_string(report->type) + " is not a subsystem's (10001..40000)");
    if (type == msg::identification::kNode && (report->type < 40001 || report->type > 50000))
      return fail("node type " + std::to_string(report->type) + " is not a node's (40001..50000)");
    seen += (seen.empty() ? "" : ", ") + level + " '" + report->identification + "'";
  }
  return pass(seen);
}

std::string component_text(const Address& a) { return a.to_string(); }

// The components a Report Configuration lists, as addresses on the target's subsystem.
std::set<Address> listed(const msg::ReportConfiguration& report, std::uint8_t subsystem) {
  std::set<Address> out;
  for (const auto& node : report.nodes)
    for (const auto& component : node.components)
      out.insert(Address{subsystem, node.node_id, component.component_id, component.instance});
  return out;
}

std::set<Address> on_node(const std::set<Address>& components, std::uint8_t node) {
  std::set<Address> out;
  for (const auto& a : components)
    if (a.node == node) out.insert(a);
  return out;
}

Expected<msg::ReportConfiguration> configuration(CaseContext& c, std::uint8_t field) {
  return ask<msg::ReportConfiguration>(c, msg::QueryConfiguration{{field}});
}

// Every component of the target's node that answers a Query Component Status
// sent to all of them (S.N.255.255) within the window.
std::set<Address> answering_components(CaseContext& c, rt::Duration window) {
  const Address everyone{c.target().subsystem, c.target().node, Address::kBroadcast, Address::kBroadcast};
  std::set<Address> answered;
  const auto listener = c.session.listen([&](const ocu::Received& r) {
    if (r.header.command_code != msg::ReportComponentStatus::code) return;
    if (r.header.source.subsystem != everyone.subsystem || r.header.source.node != everyone.node) return;
    answered.insert(r.header.source);
    if (r.header.source != c.target())  // the runner records the target's own
      c.exchange.push_back(Exchanged{false, r.header, r.payload, c.session.clock().now() - c.started});
  });
  send(c, everyone, msg::QueryComponentStatus{});
  c.session.run_for(window);
  c.session.unlisten(listener);
  return answered;
}

// Half a second is ample for a reply on a network; a shorter reply budget wins.
rt::Duration listening_window(const CaseContext& c) {
  return std::min<rt::Duration>(c.reply_timeout, std::chrono::milliseconds(500));
}

CaseOutcome configuration_consistent(CaseContext& c) {
  const Address& self = c.target();
  auto by_node = configuration(c, msg::identification::kNode);
  if (!by_node) return fail("Query Configuration (node): " + by_node.error().message());
  auto by_subsystem = configuration(c, msg::identification::kSubsystem);
  if (!by_subsystem) return fail("Query Configuration (subsystem): " + by_subsystem.error().message());
  const auto node_listed = on_node(listed(*by_node, self.subsystem), self.node);
  const auto subsystem_listed = listed(*by_subsystem, self.subsystem);
  if (!node_listed.contains(self))
    return fail("Report Configuration (node) does not list node " + std::to_string(self.node) +
                " with its node manager " + self.to_string());
  if (on_node(subsystem_listed, self.node) != node_listed)
    return fail("Report Configuration (subsystem) lists node " + std::to_string(self.node) + " with " +
                std::to_string(on_node(subsystem_listed, self.node).size()) + " components, (node) with " +
                std::to_string(node_listed.size()));
  // Everything listed is there...
  for (const Address& component : subsystem_listed) {
    auto status = ask_of<msg::ReportComponentStatus>(c, component, msg::QueryComponentStatus{});
    if (!status)
      return fail("listed in Report Configuration, " + component_text(component) +
                  " does not answer Query Component Status: " + status.error().message());
  }
  // ...and everything there is listed (asked again when missing: a component
  // may have come up after the first report).
  const auto answered = answering_components(c, listening_window(c));
  for (const Address& component : answered) {
    if (node_listed.contains(component)) continue;
    auto again = configuration(c, msg::identification::kNode);
    if (!again) return fail("Query Configuration (node), asked again: " + again.error().message());
    if (!listed(*again, self.subsystem).contains(component))
      return fail(component_text(component) + " answers Query Component Status but Report Configuration (node) " +
                  "does not list it");
  }
  return pass(std::to_string(node_listed.size()) + " components on node " + std::to_string(self.node) + ", " +
              std::to_string(subsystem_listed.size()) + " in the subsystem, each answering; " +
              std::to_string(answered.size()) + " answered a Query Component Status to all, each listed");
}

std::set<std::uint16_t> codes(const std::vector<msg::ServiceMessageEntry>& entries) {
  std::set<std::uint16_t> out;
  for (const auto& e : entries) out.insert(e.command_code);
  return out;
}

const msg::ServiceEntry* entry_of(const msg::ReportServices& report, std::uint8_t component_id) {
  for (const auto& service : report.services)
    if (service.type == component_id) return &service;
  return nullptr;
}

CaseOutcome services_consistent(CaseContext& c) {
  const Address& self = c.target();
  auto node_report = configuration(c, msg::identification::kNode);
  if (!node_report) return fail("Query Configuration (node): " + node_report.error().message());
  auto services = ask<msg::ReportServices>(c, msg::QueryServices{});
  if (!services) return fail("Query Services: " + services.error().message());
  std::size_t compared = 0;
  for (const Address& component : on_node(listed(*node_report, self.subsystem), self.node)) {
    const auto* entry = entry_of(*services, component.component);
    if (!entry)
      return fail("Report Services of the node manager has no entry of type " + std::to_string(component.component) +
                  " for " + component_text(component) + ", listed in Report Configuration");
    if (component == self) continue;
    // A component that answers for itself must say what its node manager says of it.
    send(c, component, msg::QueryServices{});
    auto reply = c.session.await_reply(component, {msg::ReportServices::code}, listening_window(c));
    if (!reply) continue;
    c.exchange.push_back(Exchanged{false, reply->header, reply->payload, c.session.clock().now() - c.started});
    auto own = decode<msg::ReportServices>(c, *reply);
    if (!own) return fail(component_text(component) + ": " + own.error().message());
    const auto* own_entry = entry_of(*own, component.component);
    if (!own_entry && own->services.size() == 1) own_entry = &own->services.front();  // untyped: taken whole
    if (!own_entry)
      return fail(component_text(component) + "'s own Report Services has no entry of type " +
                  std::to_string(component.component));
    if (codes(own_entry->inputs) != codes(entry->inputs) || codes(own_entry->outputs) != codes(entry->outputs))
      return fail(component_text(component) + "'s own Report Services lists " +
                  std::to_string(own_entry->inputs.size()) + " inputs and " +
                  std::to_string(own_entry->outputs.size()) + " outputs, its node manager's entry " +
                  std::to_string(entry->inputs.size()) + " and " + std::to_string(entry->outputs.size()) +
                  " (not the same codes)");
    ++compared;
  }
  return pass(std::to_string(services->services.size()) + " service entries, one for each component listed; " +
              std::to_string(compared) + " components' own Report Services agree");
}

CaseOutcome subsystem_list(CaseContext& c) {
  const Address& self = c.target();
  auto report = ask<msg::ReportSubsystemList>(c, msg::QuerySubsystemList{});
  if (!report) return fail("Query Subsystem List: " + report.error().message());
  const auto& entries = report->subsystems;
  if (std::none_of(entries.begin(), entries.end(), [&](const Address& a) { return a.subsystem == self.subsystem; }))
    return fail("Report Subsystem List (" + std::to_string(entries.size()) + " entries) does not list subsystem " +
                std::to_string(self.subsystem) + ", its own");
  std::string others;
  for (const Address& entry : entries) {
    if (entry.subsystem == c.session.self().subsystem) continue;  // the runner's own: it answers itself
    // A node manager speaks for its subsystem; another entry (a
    // communicator heard) answers for itself.
    const std::uint8_t type =
        entry.component == kNodeManager ? msg::identification::kSubsystem : msg::identification::kComponent;
    auto id = ask_of<msg::ReportIdentification>(c, entry, msg::QueryIdentification{{type}});
    if (!id)
      return fail("listed in Report Subsystem List, " + entry.to_string() + " does not answer Query Identification (" +
                  identification_level(type) + "): " + id.error().message());
    if (id->query_type != type)
      return fail(entry.to_string() + " answered Query Identification (" + identification_level(type) +
                  ") with query type " + std::to_string(id->query_type));
    if (entry.subsystem != self.subsystem) others += " " + entry.to_string() + " '" + id->identification + "'";
  }
  return pass(std::to_string(entries.size()) + " subsystems, its own among them, each answering" +
              (others.empty() ? std::string() : ";" + others));
}

// Create Event for Report Configuration on every change is confirmed; any
// Event while it holds carries the confirmed ID and this node's
// configuration; Cancel Event is confirmed and ends it. The runner cannot
// change a node's components: the Event is checked only if one comes.
CaseOutcome configuration_event(CaseContext& c) {
  constexpr std::uint8_t kCreateRequest = 0x51;
  constexpr std::uint8_t kCancelRequest = 0x52;
  const Address& self = c.target();
  struct Heard {
    msg::Event event;
    bool after_cancel = false;
  };
  std::vector<Heard> events;
  bool cancelled = false;
  std::string undecodable;
  const auto listener = c.session.listen([&](const ocu::Received& r) {
    if (r.header.source != self) return;
    // Marked here, not when the wait returns: an Event in the same burst as
    // the confirmation is after it.
    if (r.header.command_code == msg::ConfirmEventRequest::code) {
      auto confirm = decode<msg::ConfirmEventRequest>(c, r);
      if (confirm && confirm->request_id == kCancelRequest && confirm->response_code == 0) cancelled = true;
      return;
    }
    if (r.header.command_code != msg::Event::code) return;
    auto event = decode<msg::Event>(c, r);
    if (!event) {
      undecodable = event.error().message();
      return;
    }
    events.push_back({*event, cancelled});
  });
  struct Unlisten {
    ocu::OcuSession& session;
    ocu::OcuSession::ListenerId id;
    ~Unlisten() { session.unlisten(id); }
  } unlisten{c.session, listener};

  msg::CreateEvent create;
  create.request_id = kCreateRequest;
  create.report_code = msg::ReportConfiguration::code;
  create.event_type = 1;  // every change
  create.query_message = std::vector<std::uint8_t>{msg::identification::kNode};
  send(c, create);
  auto reply = await(c, {msg::ConfirmEventRequest::code});
  if (!reply) return fail("Create Event (Report Configuration, every change): " + reply.error().message());
  auto confirm = decode<msg::ConfirmEventRequest>(c, *reply);
  if (!confirm) return fail(confirm.error().message());
  const std::uint8_t event_id = confirm->event_id;
  auto cancel = [&] {
    msg::CancelEvent m;
    m.request_id = kCancelRequest;
    m.message_code = msg::ReportConfiguration::code;
    m.event_id = event_id;
    send(c, m);
  };
  if (confirm->response_code != 0)
    return fail("Confirm Event Request response " + std::to_string(confirm->response_code));
  if (confirm->request_id != kCreateRequest || confirm->message_code != msg::ReportConfiguration::code) {
    cancel();
    return fail("Confirm Event Request for request " + std::to_string(confirm->request_id) + ", code " +
                std::to_string(confirm->message_code) + ": not the Create Event's (request " +
                std::to_string(kCreateRequest) + ", code 0x4B01)");
  }
  c.session.run_for(c.reply_timeout);  // a change now would be sent
  const std::size_t while_held = events.size();

  cancel();
  auto cancel_reply = await(c, {msg::ConfirmEventRequest::code});
  if (!cancel_reply) return fail("Cancel Event " + std::to_string(event_id) + ": " + cancel_reply.error().message());
  auto cancel_confirm = decode<msg::ConfirmEventRequest>(c, *cancel_reply);
  if (!cancel_confirm) return fail(cancel_confirm.error().message());
  if (cancel_confirm->response_code != 0)
    return fail("Cancel Event " + std::to_string(event_id) + " confirmed with response " +
                std::to_string(cancel_confirm->response_code));
  c.session.run_for(listening_window(c));

  if (!undecodable.empty()) return fail("an Event does not decode: " + undecodable);
  std::optional<std::uint8_t> last_sequence;
  for (const auto& [event, after_cancel] : events) {
    if (event.event_id != event_id) continue;  // another requester's (never sent to us) or an old one
    if (after_cancel) return fail("Event " + std::to_string(event_id) + " still sent after Cancel Event was confirmed");
    if (event.report_code != msg::ReportConfiguration::code)
      return fail("Event " + std::to_string(event_id) + " carries code " + std::to_string(event.report_code) +
                  ", not Report Configuration");
    msg::ReportConfiguration report{};
    if (auto decoded = wire::decode_payload_into(event.report_message, report, c.session.options().dialect); !decoded)
      return fail("the Event's Report Configuration does not decode: " + decoded.error().message());
    if (!listed(report, self.subsystem).contains(self))
      return fail("the Event's Report Configuration does not list the node manager " + self.to_string());
    if (last_sequence && event.sequence_number != static_cast<std::uint8_t>(*last_sequence + 1))
      return fail("Event sequence numbers " + std::to_string(*last_sequence) + " then " +
                  std::to_string(event.sequence_number));
    last_sequence = event.sequence_number;
  }
  const std::string confirmed =
      "Create Event confirmed (event " + std::to_string(event_id) + "), Cancel Event confirmed";
  if (while_held == 0)
    return pass(confirmed + "; no configuration change while it listened: the Event itself not checked");
  return pass(confirmed + "; " + std::to_string(while_held) +
              " Events on change, each Report Configuration listing this node, none after Cancel");
}

}  // namespace

std::span<const ConformanceCase> discovery_cases() {
  static const std::vector<ConformanceCase> list{
      {"discovery.identification",
       "answers Query Identification for its subsystem (2), node (3) and itself (4), each with the type asked",
       "RA 3.3 Code 2B00h Query Identification, Code 4B00h Report Identification; docs/wire-format.md: "
       "Liveness and discovery",
       not_a_node_manager, identification_at_each_level},
      {"discovery.configuration",
       "Report Configuration (subsystem and node) lists this node and its components; each listed answers, each "
       "answering is listed",
       "RA 3.3 Code 2B01h Query Configuration, Code 4B01h Report Configuration; docs/wire-format.md: Liveness and "
       "discovery",
       not_a_node_manager, configuration_consistent},
      {"discovery.services",
       "Report Services has an entry for each component configured, and agrees with each component's own",
       "RA 3.3 Code 2B03h Query Services, Code 4B03h Report Services (type = component ID); docs/wire-format.md: "
       "Liveness and discovery",
       not_a_node_manager, services_consistent},
      {"discovery.subsystem_list", "Report Subsystem List includes this subsystem, and every entry answers",
       "RA 3.3 Code 2B02h Query Subsystem List, Code 4B02h Report Subsystem List; docs/wire-format.md: Liveness and "
       "discovery",
       not_a_node_manager, subsystem_list},
      {"discovery.change_event",
       "Create Event for Report Configuration (every change) is confirmed, its Events carry the configuration, Cancel "
       "Event ends it",
       "RA 3.3 Code 01F0h Create Event, 01F2h Cancel Event, 01F3h Confirm Event Request, 41F1h Event; "
       "docs/wire-format.md: Liveness and discovery",
       not_a_node_manager, configuration_event},
  };
  return list;
}

}  // namespace jaus::conform
