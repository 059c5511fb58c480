// JSS core services (AS5710, core v1.1; docs/jss.md, "Core services"): discovery, access
// control (confirm codes, timeout, preemption), management (Resume/Standby,
// emergencies held per client), liveness and events, each asked of a
// component that lists the service.
#include <algorithm>
#include <set>

#include "jss_case_support.hpp"

namespace jaus::conform {
namespace {

using namespace jss_detail;
using namespace std::chrono_literals;
namespace m = jss::msg;

std::string id_text(const jss::JssId& id) { return id.to_string(); }
std::string seconds_text(rt::Duration d) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f s", std::chrono::duration<double>(d).count());
  return text;
}

// --- discovery ----------------------------------------------------------

CaseOutcome jss_identification(JssCaseContext& c) {
  send(c, m::QueryIdentification{{4}});
  auto reply = await_from(c, c.session, {m::ReportIdentification::code});
  if (!reply) {
    if (!c.component.has("Discovery"))
      return skip("it lists no Discovery service and did not answer (only Discovery must)");
    return fail(reply.error().message());
  }
  auto report = decode<m::ReportIdentification>(*reply);
  if (!report) return fail(report.error().message());
  if (report->query_type != 4) return fail("Report Identification type " + std::to_string(report->query_type) + ", not 4");
  return pass("Report Identification type 4, '" + report->identification + "'");
}

CaseOutcome discovery_identification(JssCaseContext& c) {
  std::string seen;
  for (const std::uint8_t type : {std::uint8_t{2}, std::uint8_t{3}}) {
    auto report = ask<m::ReportIdentification>(c, m::QueryIdentification{{type}});
    if (!report) return fail("type " + std::to_string(type) + ": " + report.error().message());
    if (report->query_type != type)
      return fail("asked type " + std::to_string(type) + ", answered type " + std::to_string(report->query_type));
    const auto kind = report->type;
    if (type == 2 && !(kind >= 10001 && kind < 40001))
      return fail("the subsystem's type " + std::to_string(kind) + " is no subsystem's (10001, 20001, 30001)");
    if (type == 3 && kind != 40001) return fail("the node's type " + std::to_string(kind) + " is not NODE (40001)");
    seen += (seen.empty() ? "" : ", ") + std::string(type == 2 ? "subsystem '" : "node '") + report->identification +
            "' (" + std::to_string(kind) + ")";
  }
  return pass(seen);
}

using UriSet = std::set<std::pair<std::uint8_t, std::string>>;  // (component ID, "uri major.minor")

std::string entry_text(const std::string& uri, std::uint8_t major, std::uint8_t minor) {
  return uri + " " + std::to_string(major) + "." + std::to_string(minor);
}

CaseOutcome discovery_services(JssCaseContext& c) {
  // Every component of its node, both ways: Report Services (v1.0) and Report Service List (v1.1).
  m::QueryServices all_services;
  all_services.nodes.push_back(m::QueryServicesNode{jss::JssId::kAll, {jss::JssId::kAll}});
  auto services = ask<m::ReportServices>(c, all_services);
  if (!services) return fail("Query Services: " + services.error().message());
  UriSet by_services;
  bool core_everywhere = true;
  std::string missing_core;
  for (const auto& node : services->nodes) {
    if (node.node_id != c.target().node) continue;
    for (const auto& component : node.components) {
      bool transport = false;
      for (const auto& s : component.services) {
        by_services.insert({component.component_id, entry_text(s.uri, s.major_version, s.minor_version)});
        transport = transport || s.uri == "urn:jaus:jss:core:Transport";
      }
      if (!transport) {
        core_everywhere = false;
        missing_core += " " + std::to_string(component.component_id);
      }
    }
  }
  if (by_services.empty()) return fail("Report Services lists no component of node " + std::to_string(c.target().node));
  if (!core_everywhere) return fail("components without urn:jaus:jss:core:Transport in Report Services:" + missing_core);
  m::QueryServiceList all_list;
  m::ServiceListQueryNode every_node{jss::JssId::kAll, {m::ServiceListQueryComponent{jss::JssId::kAll, std::nullopt}}};
  all_list.subsystems.push_back(m::ServiceListQuerySubsystem{jss::JssId::kAllSubsystems, {every_node}});
  auto list = ask<m::ReportServiceList>(c, all_list);
  if (!list) return fail("Query Service List: " + list.error().message());
  UriSet by_list;
  for (const auto& subsystem : list->subsystems) {
    if (subsystem.subsystem_id != c.target().subsystem) continue;
    for (const auto& node : subsystem.nodes) {
      if (node.node_id != c.target().node) continue;
      for (const auto& component : node.components)
        for (const auto& s : component.services)
          by_list.insert({component.component_id, entry_text(s.uri, s.major_version, s.minor_version)});
    }
  }
  if (by_list != by_services) {
    std::string only_services, only_list;
    for (const auto& e : by_services)
      if (!by_list.count(e)) only_services += " " + std::to_string(e.first) + ":" + e.second;
    for (const auto& e : by_list)
      if (!by_services.count(e)) only_list += " " + std::to_string(e.first) + ":" + e.second;
    return fail("Report Services and Report Service List differ; only in Report Services:" + only_services +
                "; only in Report Service List:" + only_list);
  }
  std::set<std::uint8_t> components;
  for (const auto& e : by_services) components.insert(e.first);
  return pass(std::to_string(components.size()) + " components, " + std::to_string(by_services.size()) +
              " services, the same in Report Services and Report Service List, Transport on each");
}

CaseOutcome discovery_configuration(JssCaseContext& c) {
  auto configuration = ask<m::ReportConfiguration>(c, m::QueryConfiguration{{3}});
  if (!configuration) return fail("Query Configuration (node): " + configuration.error().message());
  std::set<std::uint8_t> listed;
  for (const auto& node : configuration->nodes) {
    if (node.node_id != c.target().node) continue;
    for (const auto& component : node.components) {
      if (component.instance_id != 0)
        return fail("component " + std::to_string(component.component_id) + " listed with instance " +
                    std::to_string(component.instance_id) + " (0 for JSS components)");
      listed.insert(component.component_id);
    }
  }
  if (!listed.count(c.target().component))
    return fail("Report Configuration does not list the discovery component itself (" + id_text(c.target()) + ")");
  // Every component discovery found on this node is listed.
  std::string missing;
  if (c.node_components)
    for (const auto& other : *c.node_components)
      if (other.id.subsystem == c.target().subsystem && other.id.node == c.target().node &&
          !listed.count(other.id.component))
        missing += " " + id_text(other.id);
  if (!missing.empty()) return fail("components with services, not in Report Configuration:" + missing);
  auto subsystem = ask<m::ReportConfiguration>(c, m::QueryConfiguration{{2}});
  if (!subsystem) return fail("Query Configuration (subsystem): " + subsystem.error().message());
  const bool node_there = std::any_of(subsystem->nodes.begin(), subsystem->nodes.end(),
                                      [&](const auto& n) { return n.node_id == c.target().node; });
  if (!node_there) return fail("the subsystem's Report Configuration does not list node " + std::to_string(c.target().node));
  return pass(std::to_string(listed.size()) + " components on node " + std::to_string(c.target().node) +
              ", instance 0 each, the node in the subsystem's configuration");
}

// --- liveness -----------------------------------------------------------

CaseOutcome jss_heartbeat(JssCaseContext& c) {
  auto report = ask<m::ReportHeartbeatPulse>(c, m::QueryHeartbeatPulse{});
  if (!report) return fail(report.error().message());
  return pass("Report Heartbeat Pulse");
}

// --- access control -----------------------------------------------------

CaseOutcome control_round_trip(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return fail("Request Control at its own authority " + std::to_string(authority) + ": " + held.what());
  auto control = control_of(c);
  if (!control) return fail("Query Control: " + control.error().message());
  if (control->controller != c.session.self() || control->authority != authority)
    return fail("Report Control gives " + id_text(control->controller) + " at " + std::to_string(control->authority) +
                ", not the runner (" + id_text(c.session.self()) + ") at " + std::to_string(authority));
  held.forget();
  send(c, m::ReleaseControl{});
  auto reject = await_from(c, c.session, {m::RejectControl::code});
  if (!reject) return fail("Release Control: no Reject Control: " + reject.error().message());
  auto code = decode<m::RejectControl>(*reject);
  if (!code) return fail(code.error().message());
  if (code->response_code != kControlReleased)
    return fail("Release Control answered Reject Control " + std::to_string(code->response_code) + ", not 0");
  control = control_of(c);
  if (!control) return fail("Query Control: " + control.error().message());
  if (control->controller.is_valid()) return fail("still controlled by " + id_text(control->controller) + " after release");
  return pass("Confirm Control 0, reported as controller at " + std::to_string(authority) +
              ", released with Reject Control 0");
}

CaseOutcome control_insufficient_authority(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  if (authority == 0) return skip("its authority is 0: no lower authority to ask with");
  JssControlHeld held(c, c.session, static_cast<std::uint8_t>(authority - 1));
  if (held.granted()) return fail("control granted at " + std::to_string(authority - 1) + ", below its authority " +
                                  std::to_string(authority));
  if (held.what() != "Confirm Control 2")
    return fail("at " + std::to_string(authority - 1) + ": " + held.what() + ", not Confirm Control 2");
  auto control = control_of(c);
  if (!control) return fail("Query Control: " + control.error().message());
  if (control->controller.is_valid()) return fail("controlled by " + id_text(control->controller) + " after the refusal");
  return pass("Confirm Control 2 (INSUFFICIENT_AUTHORITY) at " + std::to_string(authority - 1) + ", nobody controls it");
}

// Control held without a word for longer than the timeout is lost.
CaseOutcome control_timeout(JssCaseContext& c) {
  auto timeout = ask<m::ReportTimeout>(c, m::QueryTimeout{});
  if (!timeout) return fail("Query Timeout: " + timeout.error().message());
  if (timeout->timeout_s == 0) return skip("Report Timeout 0: it never times its controller out");
  if (timeout->timeout_s > 20) return skip("Report Timeout " + std::to_string(timeout->timeout_s) + " s: too long to wait out");
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  const auto t = std::chrono::seconds(timeout->timeout_s);
  // Kept by asking again within the timeout...
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  bool rejected = false;
  const auto listener = c.session.listen([&](const ocu::JssReceived& r) {
    rejected = rejected || (r.source() == c.target() && r.message_id() == m::RejectControl::code);
  });
  for (int i = 0; i < 4 && !rejected; ++i) {
    c.session.run_until([&] { return rejected; }, t / 2);
    held.renew();
    (void)await_from(c, c.session, {m::ConfirmControl::code});
  }
  if (rejected) {
    c.session.unlisten(listener);
    held.forget();
    return fail("lost control while asking again every " + std::to_string(timeout->timeout_s) + "/2 s");
  }
  // ...and lost after the timeout in silence.
  const auto silent_since = c.session.clock().now();
  c.session.run_until([&] { return rejected; }, t + t / 2 + 1s);
  c.session.unlisten(listener);
  held.forget();
  const double after = std::chrono::duration<double>(c.session.clock().now() - silent_since).count();
  if (!rejected) return fail("no Reject Control within 1.5 timeouts + 1 s of silence");
  auto control = control_of(c);
  if (!control) return fail("Query Control: " + control.error().message());
  if (control->controller == c.session.self()) return fail("Reject Control came, but Report Control still names the runner");
  char text[160];
  std::snprintf(text, sizeof(text), "Report Timeout %u s: kept over %u renewals, Reject Control %.1f s into silence",
                timeout->timeout_s, 4u, after);
  return pass(text);
}

// The second client holds control at `authority`; `then` runs with it held.
template <class Then>
CaseOutcome with_second_controlling(JssCaseContext& c, std::uint8_t authority, Then then) {
  auto second = c.second();
  if (!second) return fail(second.error().message());
  JssControlHeld held(c, **second, authority);
  if (!held.granted()) return skip("the second client is not granted control at " + std::to_string(authority) + ": " +
                                   held.what());
  return then(**second, held);
}

CaseOutcome control_preemption(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  if (authority == 255) return skip("its authority is 255: nothing can preempt");
  return with_second_controlling(c, authority, [&](ocu::JssSession& second, JssControlHeld& second_held) {
    const auto higher = static_cast<std::uint8_t>(authority + 1);
    Heard rejects(c, second, m::RejectControl::code);
    JssControlHeld mine(c, c.session, higher);
    if (!mine.granted()) return fail("the runner at " + std::to_string(higher) + " over the second client at " +
                                     std::to_string(authority) + ": " + mine.what() + ", not Confirm Control 0");
    auto reject = rejects.first(c.reply_timeout);
    if (!reject) return fail("the old controller got no Reject Control within " + seconds_text(c.reply_timeout));
    second_held.forget();
    auto code = decode<m::RejectControl>(*reject);
    if (!code) return fail(code.error().message());
    if (code->response_code != kControlReleased)
      return fail("the old controller got Reject Control " + std::to_string(code->response_code) + ", not 0");
    auto control = control_of(c);
    if (!control) return fail("Query Control: " + control.error().message());
    if (control->controller != c.session.self() || control->authority != higher)
      return fail("Report Control gives " + id_text(control->controller) + " at " + std::to_string(control->authority));
    return pass("taken at " + std::to_string(higher) + " from the second client at " + std::to_string(authority) +
                ", which got Reject Control 0");
  });
}

CaseOutcome control_other_refused(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  return with_second_controlling(c, authority, [&](ocu::JssSession& second, JssControlHeld&) {
    JssControlHeld mine(c, c.session, authority);
    if (mine.granted()) return fail("granted at " + std::to_string(authority) + " while the second client held it at the same authority");
    if (mine.what() != "Confirm Control 2")
      return fail("at the controller's authority: " + mine.what() + ", not Confirm Control 2");
    auto control = control_of(c);
    if (!control) return fail("Query Control: " + control.error().message());
    if (control->controller != second.self()) return fail("Report Control gives " + id_text(control->controller) + ", not the second client");
    return pass("Confirm Control 2 at the controller's authority " + std::to_string(authority) + ", its controller stays");
  });
}

CaseOutcome control_release_by_other(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  return with_second_controlling(c, authority, [&](ocu::JssSession& second, JssControlHeld&) {
    send(c, m::ReleaseControl{});
    pause(c, 300ms);
    auto control = control_of(c);
    if (!control) return fail("Query Control: " + control.error().message());
    if (control->controller != second.self())
      return fail("after a non-controller's Release Control, Report Control gives " + id_text(control->controller));
    return pass("Release Control from a non-controller moved nothing");
  });
}

// --- management ---------------------------------------------------------

CaseOutcome management_status(JssCaseContext& c) {
  auto report = ask<m::ReportStatus>(c, m::QueryStatus{});
  if (!report) return fail(report.error().message());
  const auto status = static_cast<std::uint8_t>(report->status & 0x0F);
  if (status > 5) return fail("status " + std::to_string(status) + ": JSS defines 0..5");
  return pass("Report Status " + status_name(status));
}

CaseOutcome management_standby_resume(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (*found != kReady && *found != kStandby) return skip("it is " + status_name(*found) + ", not Ready or Standby");
  JssControlHeld held(c, c.session, authority);
  if (!held.granted()) return skip("control not granted: " + held.what());
  const std::uint8_t other = *found == kReady ? kStandby : kReady;
  if (auto moved = bring_to(c, other); !moved) return fail(moved.error().message());
  if (auto back = bring_to(c, *found); !back) return fail(back.error().message());
  return pass(status_name(*found) + " -> " + status_name(other) + " -> " + status_name(*found) + " by its controller");
}

// Resume from a non-controller, with the component in its controller's
// Standby, changes nothing. (Standby from a non-controller is not judged:
// it only makes the vehicle safer, and our node takes it from anyone,
// docs/safety.md.)
CaseOutcome management_non_controller_ignored(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  const std::uint8_t authority = uncontrolled.authority;
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (*found != kReady && *found != kStandby) return skip("it is " + status_name(*found) + ", not Ready or Standby");
  return with_second_controlling(c, authority, [&](ocu::JssSession& second, JssControlHeld&) {
    send_from(c, second, c.target(), m::Standby{});
    pause(c, 300ms);
    auto before = status_of(c);
    send(c, m::Resume{});  // the runner is no controller
    pause(c, 300ms);
    auto now = status_of(c);
    if (*found == kReady) send_from(c, second, c.target(), m::Resume{});
    pause(c, 200ms);
    if (!before) return fail(before.error().message());
    if (*before != kStandby) return skip("its controller's Standby left it " + status_name(*before));
    if (!now) return fail(now.error().message());
    if (*now != kStandby) return fail("Resume from a non-controller moved it to " + status_name(*now));
    return pass("Resume from a non-controller: still Standby");
  });
}

CaseOutcome management_emergency(JssCaseContext& c) {
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (*found != kReady && *found != kStandby) return skip("it is " + status_name(*found) + ", not Ready or Standby");
  send(c, m::SetEmergency{{1}}, jss::JudpPriority::safety_critical);
  pause(c, 200ms);
  auto during = status_of(c);
  send(c, m::ClearEmergency{{1}});
  pause(c, 200ms);
  auto after = status_of(c);
  if (!during) return fail(during.error().message());
  if (*during != kEmergency) return fail("Set Emergency: " + status_name(*during) + ", not Emergency");
  if (!after) return fail(after.error().message());
  if (*after != *found) return fail("Clear Emergency by its setter: " + status_name(*after) + ", not " + status_name(*found));
  return pass(status_name(*found) + " -> Emergency -> " + status_name(*after));
}

CaseOutcome management_emergency_other_client(JssCaseContext& c) {
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (*found != kReady && *found != kStandby) return skip("it is " + status_name(*found) + ", not Ready or Standby");
  auto second = c.second();
  if (!second) return fail(second.error().message());
  send(c, m::SetEmergency{{1}}, jss::JudpPriority::safety_critical);
  pause(c, 200ms);
  send_from(c, **second, c.target(), m::ClearEmergency{{1}});
  pause(c, 300ms);
  auto after_other = status_of(c);
  send(c, m::ClearEmergency{{1}});
  pause(c, 200ms);
  auto after_own = status_of(c);
  if (!after_other) return fail(after_other.error().message());
  if (*after_other != kEmergency)
    return fail("the runner's emergency, cleared by the second client: " + status_name(*after_other));
  if (!after_own) return fail(after_own.error().message());
  if (*after_own != *found) return fail("cleared by the runner: " + status_name(*after_own) + ", not " + status_name(*found));
  return pass("the second client's Clear Emergency left it in Emergency; the runner's returned it to " +
              status_name(*after_own));
}

// --- events -------------------------------------------------------------

jss::codec::TaggedValue codec_tag(std::uint8_t tag, std::uint32_t value) { return jss::codec::TaggedValue{tag, value}; }

constexpr std::uint8_t kPeriodic = 0;
constexpr std::uint8_t kEveryChange = 1;

// The query an event is made of: Query Status where it has Management, else Query Heartbeat Pulse.
std::vector<std::uint8_t> event_query(const JssComponentUnderTest& component, std::uint16_t* report_id) {
  if (component.has("Management")) {
    *report_id = m::ReportStatus::code;
    return jss::encode_contents(m::QueryStatus{});
  }
  *report_id = m::ReportHeartbeatPulse::code;
  return jss::encode_contents(m::QueryHeartbeatPulse{});
}

// Every Event from the target while it listens.
struct EventLog {
  struct Heard {
    std::uint8_t event_id;
    std::uint8_t sequence;
    std::vector<std::uint8_t> report;
    rt::TimePoint at;
  };
  std::vector<Heard> events;
  ocu::JssSession& session;
  ocu::JssSession::ListenerId id;
  EventLog(JssCaseContext& c) : session(c.session) {
    const jss::JssId target = c.target();
    id = session.listen([this, target](const ocu::JssReceived& r) {
      if (r.source() != target || r.message_id() != m::Event::code) return;
      if (auto e = jss::decode_contents<m::Event>(r.contents))
        events.push_back({e->event_id, e->sequence_number, e->report_message, session.clock().now()});
    });
  }
  ~EventLog() { session.unlisten(id); }
  std::size_t count(std::uint8_t event_id) const {
    return std::count_if(events.begin(), events.end(), [&](const Heard& h) { return h.event_id == event_id; });
  }
};

Expected<m::ConfirmEventRequest> create_event(JssCaseContext& c, std::uint8_t request_id, std::uint8_t type,
                                              double rate_hz, std::vector<std::uint8_t> query) {
  send(c, m::CreateEvent{{request_id, type, rate_hz, std::move(query)}});
  auto reply = await_from(c, c.session, {m::ConfirmEventRequest::code, m::RejectEventRequest::code});
  if (!reply) return unexpected(reply.error());
  if (reply->message_id() == m::RejectEventRequest::code) {
    auto reject = decode<m::RejectEventRequest>(*reply);
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "Reject Event Request" + (reject && reject->response_code
                                                               ? " " + std::to_string(*reject->response_code)
                                                               : std::string())));
  }
  auto confirm = decode<m::ConfirmEventRequest>(*reply);
  if (!confirm) return unexpected(confirm.error());
  if (confirm->request_id != request_id)
    return unexpected(make_error(ErrorCode::malformed, "Confirm Event Request for request " +
                                                           std::to_string(confirm->request_id) + ", not " +
                                                           std::to_string(request_id)));
  return confirm;
}

// Cancel Event and its confirmation.
Expected<void> cancel_event(JssCaseContext& c, std::uint8_t event_id) {
  send(c, m::CancelEvent{m::cancel_event_by_id(9, event_id)});
  auto reply = await_from(c, c.session, {m::ConfirmEventRequest::code, m::RejectEventRequest::code});
  if (!reply) return unexpected(reply.error());
  if (reply->message_id() != m::ConfirmEventRequest::code)
    return unexpected(make_error(ErrorCode::invalid_argument, "Cancel Event rejected"));
  return {};
}

CaseOutcome events_periodic(JssCaseContext& c) {
  std::uint16_t report_id = 0;
  auto query = event_query(c.component, &report_id);
  EventLog log(c);
  auto confirm = create_event(c, 1, kPeriodic, 5.0, query);
  if (!confirm) return fail("Create Event (periodic, 5 Hz): " + confirm.error().message());
  const double rate = confirm->confirmed_rate_hz.value_or(0);
  const auto id = confirm->event_id;
  if (!(rate > 0 && rate <= 5.1)) {
    (void)cancel_event(c, id);
    return fail("confirmed rate " + std::to_string(rate) + " Hz, not within (0, 5]");
  }
  const auto from = c.session.clock().now();
  pause(c, 2s);
  std::vector<EventLog::Heard> heard;
  for (const auto& e : log.events)
    if (e.event_id == id && e.at >= from) heard.push_back(e);
  auto cancelled = cancel_event(c, id);
  const auto cancelled_at = c.session.clock().now();
  pause(c, 600ms);
  const auto late = std::count_if(log.events.begin(), log.events.end(), [&](const EventLog::Heard& e) {
    return e.event_id == id && e.at > cancelled_at + 300ms;
  });
  const double expected = rate * 2;
  if (heard.size() < expected / 2 || heard.size() > expected * 1.5 + 1)
    return fail(std::to_string(heard.size()) + " Events in 2 s at a confirmed " + std::to_string(rate) + " Hz");
  for (std::size_t i = 1; i < heard.size(); ++i)
    if (static_cast<std::uint8_t>(heard[i - 1].sequence + 1) != heard[i].sequence)
      return fail("Event sequence numbers " + std::to_string(heard[i - 1].sequence) + " then " +
                  std::to_string(heard[i].sequence));
  for (const auto& e : heard)
    if (jss::message_id_of(e.report) != report_id)
      return fail("an Event carries message " + std::to_string(jss::message_id_of(e.report)) + ", not the query's report");
  if (!cancelled) return fail("Cancel Event: " + cancelled.error().message());
  if (late > 0) return fail(std::to_string(late) + " Events after Cancel Event was confirmed");
  char text[160];
  std::snprintf(text, sizeof(text), "confirmed %.2f Hz, %zu Events in 2 s, sequence numbers up by one; cancelled", rate,
                heard.size());
  return pass(text);
}

CaseOutcome events_every_change(JssCaseContext& c) {
  const auto uncontrolled = free_target(c);
  if (uncontrolled.outcome) return *uncontrolled.outcome;
  auto found = status_of(c);
  if (!found) return fail(found.error().message());
  if (*found != kReady && *found != kStandby) return skip("it is " + status_name(*found) + ", not Ready or Standby");
  EventLog log(c);
  auto confirm = create_event(c, 2, kEveryChange, 0, jss::encode_contents(m::QueryStatus{}));
  if (!confirm) return fail("Create Event (every change, Query Status): " + confirm.error().message());
  const auto id = confirm->event_id;
  pause(c, 300ms);  // an Event at creation is allowed; what counts is the one after the change
  const auto before = log.count(id);
  std::string outcome;
  bool changed_seen = false;
  const std::uint8_t other = *found == kReady ? kStandby : kReady;
  {
    JssControlHeld held(c, c.session, uncontrolled.authority);
    if (!held.granted()) {
      (void)cancel_event(c, id);
      return skip("control not granted: " + held.what());
    }
    if (auto moved = bring_to(c, other); !moved) outcome = moved.error().message();
    pause(c, 500ms);
    for (std::size_t i = before; i < log.events.size(); ++i) {
      if (log.events[i].event_id != id) continue;
      auto report = jss::decode_contents<m::ReportStatus>(log.events[i].report);
      changed_seen = changed_seen || (report && (report->status & 0x0F) == other);
    }
    (void)bring_to(c, *found);
  }  // control released before the Cancel Event
  auto cancelled = cancel_event(c, id);
  if (!outcome.empty()) return fail(outcome);
  if (!changed_seen)
    return fail("no Event with Report Status " + status_name(other) + " within 0.5 s of the change (" +
                std::to_string(log.count(id) - before) + " Events after it)");
  if (!cancelled) return fail("Cancel Event: " + cancelled.error().message());
  return pass("an Event with Report Status " + status_name(other) + " after the change; cancelled");
}

m::QueryEvents all_events() { return m::QueryEvents{{codec_tag(m::events_filter::kAll, 0)}}; }
m::QueryEvents event_of(std::uint8_t id) { return m::QueryEvents{{codec_tag(m::events_filter::kEventId, id)}}; }

CaseOutcome events_query_and_timeout(JssCaseContext& c) {
  std::uint16_t report_id = 0;
  auto query = event_query(c.component, &report_id);
  auto confirm = create_event(c, 3, kPeriodic, 1.0, query);
  if (!confirm) return fail("Create Event (periodic, 1 Hz): " + confirm.error().message());
  const auto id = confirm->event_id;
  auto listed = ask<m::ReportEvents>(c, all_events());
  auto by_id = ask<m::ReportEvents>(c, event_of(id));
  auto timeout = ask<m::ReportEventTimeout>(c, m::QueryEventTimeout{});
  auto cancelled = cancel_event(c, id);
  auto after = ask<m::ReportEvents>(c, event_of(id));
  auto lists = [&](const m::ReportEvents& r) {
    return std::any_of(r.events.begin(), r.events.end(), [&](const auto& e) {
      return e.event_id == id && e.event_type == kPeriodic && jss::message_id_of(e.query_message) == jss::message_id_of(query);
    });
  };
  if (!listed) return fail("Query Events (all): " + listed.error().message());
  if (!lists(*listed)) return fail("Report Events (all) does not list event " + std::to_string(id) + " with its query");
  if (!by_id) return fail("Query Events (event " + std::to_string(id) + "): " + by_id.error().message());
  if (!lists(*by_id)) return fail("Report Events for event " + std::to_string(id) + " does not list it");
  if (!timeout) return fail("Query Event Timeout: " + timeout.error().message());
  if (!cancelled) return fail("Cancel Event: " + cancelled.error().message());
  if (after && lists(*after)) return fail("Report Events still lists event " + std::to_string(id) + " after Cancel Event");
  return pass("Report Events lists event " + std::to_string(id) + " (all, by ID), not after its cancel; event timeout " +
              std::to_string(timeout->timeout_min) + " min");
}

CaseOutcome events_unsupported_rejected(JssCaseContext& c) {
  // A query message ID no service defines (0x2FF0), and an event ID never handed out.
  const std::vector<std::uint8_t> unknown_query{0xF0, 0x2F};
  auto created = create_event(c, 4, kPeriodic, 1.0, unknown_query);
  if (created) {
    (void)cancel_event(c, created->event_id);
    return fail("Create Event on an unknown query (2FF0h) was confirmed");
  }
  const std::string create_refusal = created.error().message();
  if (create_refusal.rfind("Reject Event Request", 0) != 0) return fail("Create Event on 2FF0h: " + create_refusal);
  auto listed = ask<m::ReportEvents>(c, all_events());
  std::uint8_t unused = 254;
  if (listed)
    while (std::any_of(listed->events.begin(), listed->events.end(), [&](const auto& e) { return e.event_id == unused; }))
      --unused;
  send(c, m::CancelEvent{m::cancel_event_by_id(5, unused)});
  auto reply = await_from(c, c.session, {m::ConfirmEventRequest::code, m::RejectEventRequest::code});
  if (!reply) return fail("Cancel Event of unknown event " + std::to_string(unused) + ": " + reply.error().message());
  if (reply->message_id() != m::RejectEventRequest::code)
    return fail("Cancel Event of unknown event " + std::to_string(unused) + " was confirmed");
  return pass("Create Event on 2FF0h: " + create_refusal + "; Cancel Event of unknown event " + std::to_string(unused) +
              " rejected");
}

// --- the suite ----------------------------------------------------------

std::string unless_discovery(const JssComponentUnderTest& c) { return unless_has(c, "Discovery"); }
std::string unless_access_control(const JssComponentUnderTest& c) { return unless_has(c, "AccessControl"); }
std::string unless_management(const JssComponentUnderTest& c) { return unless_has(c, "Management"); }
std::string unless_events(const JssComponentUnderTest& c) { return unless_has(c, "Events"); }
std::string unless_liveness(const JssComponentUnderTest& c) { return unless_has(c, "Liveness"); }
std::string unless_events_and_management(const JssComponentUnderTest& c) {
  if (auto why = unless_events(c); !why.empty()) return why;
  return unless_management(c);
}

JssConformanceCase core_case(std::string_view id, std::string_view title, std::string_view reference,
                        std::function<std::string(const JssComponentUnderTest&)> not_applicable,
                        std::function<CaseOutcome(JssCaseContext&)> run) {
  return JssConformanceCase{id, title, reference, std::move(not_applicable), std::move(run)};
}

}  // namespace

std::span<const JssConformanceCase> jss_core_cases() {
  static const std::vector<JssConformanceCase> cases{
      core_case("jss.identification", "Query Identification (component) is answered with Report Identification type 4",
           "AS5710 Discovery; docs/jss.md: Discovery", nullptr, jss_identification),
      core_case("jss.discovery.identification",
           "Query Identification types 2 and 3 are answered with the type asked, a subsystem's and a node's",
           "AS5710 Discovery; docs/jss.md: Discovery", unless_discovery, discovery_identification),
      core_case("jss.discovery.services",
           "Report Services and Report Service List list the same services for the node's components, Transport on each",
           "AS5710 Discovery 1.1; docs/jss.md: Discovery, What is supported", unless_discovery, discovery_services),
      core_case("jss.discovery.configuration",
           "Report Configuration lists every component with services on the node, instance 0",
           "AS5710 Discovery; docs/jss.md: Discovery", unless_discovery, discovery_configuration),
      core_case("jss.liveness.heartbeat", "Query Heartbeat Pulse is answered with Report Heartbeat Pulse",
           "AS5710 Liveness; docs/jss.md: Liveness", unless_liveness, jss_heartbeat),
      core_case("jss.control.round_trip",
           "Request Control at its authority: Confirm Control 0, Report Control names the client; Release: Reject "
           "Control 0",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_round_trip),
      core_case("jss.control.insufficient_authority", "a request below its authority gets Confirm Control 2",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_insufficient_authority),
      core_case("jss.control.timeout",
           "Report Timeout is kept: control kept by asking again within it, lost (Reject Control 0) after it in silence",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_timeout),
      core_case("jss.control.preemption",
           "a higher authority takes control; the old controller gets Reject Control 0",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_preemption),
      core_case("jss.control.other_refused", "a request at the controller's authority gets Confirm Control 2",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_other_refused),
      core_case("jss.control.release_by_non_controller", "Release Control from a non-controller moves nothing",
           "AS5710 AccessControl; docs/jss.md: Access Control", unless_access_control, control_release_by_other),
      core_case("jss.management.status", "Query Status is answered with a status JSS defines (0..5)",
           "AS5710 Management; docs/jss.md: Management", unless_management, management_status),
      core_case("jss.management.standby_resume", "its controller's Standby and Resume move it between Ready and Standby",
           "AS5710 Management; docs/jss.md: Management", unless_management, management_standby_resume),
      core_case("jss.management.non_controller_ignored", "Resume from a non-controller (its controller's Standby) changes nothing",
           "AS5710 Management; docs/jss.md: Access Control, Management",
           unless_management, management_non_controller_ignored),
      core_case("jss.management.emergency",
           "Set Emergency puts it in Emergency; Clear Emergency by the same client returns it to the state it left",
           "AS5710 Management; docs/jss.md: Management", unless_management, management_emergency),
      core_case("jss.management.emergency_other_client",
           "an emergency set by one client is not cleared by another's Clear Emergency",
           "AS5710 Management; docs/jss.md: Management", unless_management, management_emergency_other_client),
      core_case("jss.events.periodic",
           "a periodic event is confirmed at most at the asked rate, its Events come at that rate with sequence "
           "numbers up by one, and stop after Cancel Event",
           "AS5710 Events; docs/jss.md: Events", unless_events, events_periodic),
      core_case("jss.events.every_change", "an every-change event on Query Status sends an Event when the status changes",
           "AS5710 Events; docs/jss.md: Events", unless_events_and_management, events_every_change),
      core_case("jss.events.query_events",
           "Query Events (all, by event ID) lists an event with its query until it is cancelled; Query Event Timeout "
           "is answered",
           "AS5710 Events 1.1; docs/jss.md: Events", unless_events, events_query_and_timeout),
      core_case("jss.events.rejects",
           "Create Event on a query it does not support, and Cancel Event of an unknown event, get Reject Event Request",
           "AS5710 Events; docs/jss.md: Events", unless_events, events_unsupported_rejected),
  };
  return cases;
}

}  // namespace jaus::conform
