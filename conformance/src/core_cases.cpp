// The core cases: what RA 3.x requires of every component, whatever its kind
// (Part 3 core and communications messages; discovery per docs/wire-format.md).
// Each leaves the component as it found it: control released, emergency
// cleared, state restored.
#include "case_support.hpp"
#include "jaus/messages/communications_messages.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "state_support.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

CaseOutcome identification(CaseContext& c) {
  auto report = ask<msg::ReportIdentification>(c, msg::QueryIdentification{{msg::identification::kComponent}});
  if (!report) return fail(report.error().message());
  if (report->query_type != msg::identification::kComponent)
    return fail("Report Identification answers query type " + std::to_string(report->query_type) + ", asked 4");
  return pass("Report Identification type 4, '" + report->identification + "'");
}

CaseOutcome status(CaseContext& c) {
  auto report = ask<msg::ReportComponentStatus>(c, msg::QueryComponentStatus{});
  if (!report) return fail(report.error().message());
  const unsigned primary = report->primary_status & 0x0F;
  if (primary > static_cast<unsigned>(msg::PrimaryStatus::emergency))
    return fail("primary status " + std::to_string(primary) + " is not one the RA defines (0..5)");
  return pass("primary status " + ocu::primary_status_text(report->primary_status));
}

CaseOutcome authority(CaseContext& c) {
  auto report = ask<msg::ReportComponentAuthority>(c, msg::QueryComponentAuthority{});
  if (!report) return fail(report.error().message());
  return pass("authority " + std::to_string(report->authority));
}

CaseOutcome services(CaseContext& c) {
  auto report = ask<msg::ReportServices>(c, msg::QueryServices{});
  if (!report) return fail(report.error().message());
  // Every component accepts the core queries: a list without Query Component
  // Status does not describe the component truthfully.
  for (const auto& service : report->services)
    for (const auto& input : service.inputs)
      if (input.command_code == msg::QueryComponentStatus::code)
        return pass(std::to_string(report->services.size()) +
                    " service entries, Query Component Status among the inputs");
  return fail("Report Services does not list Query Component Status (0x2002) among the inputs");
}

CaseOutcome heartbeat(CaseContext& c) {
  auto report = ask<msg::ReportHeartbeatPulse>(c, msg::QueryHeartbeatPulse{});
  if (!report) return fail(report.error().message());
  return pass("Report Heartbeat Pulse");
}

// Set Emergency puts the component in Emergency whoever sends it; Clear
// Emergency from the same sender returns it to the state it left.
CaseOutcome emergency(CaseContext& c) {
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  if (*before != msg::PrimaryStatus::ready && *before != msg::PrimaryStatus::standby)
    return skip("in " + state_text(*before) + ": Set Emergency is checked from Ready or Standby");
  send(c, msg::SetEmergency{{1}}, priority::kSafetyCritical);
  auto during = primary_status(c);
  send(c, msg::ClearEmergency{{1}}, priority::kSafetyCritical);  // whatever happened: never left set
  if (!during) return fail("after Set Emergency, " + during.error().message());
  if (*during != msg::PrimaryStatus::emergency)
    return fail("Set Emergency left it in " + state_text(*during) + ", not Emergency");
  auto after = primary_status(c);
  if (!after) return fail("after Clear Emergency, " + after.error().message());
  if (c.profile == Profile::openjaus && *after == msg::PrimaryStatus::standby && *before == msg::PrimaryStatus::ready) {
    // The RA 3.3 implementation's Clear Emergency always goes to Standby (wire
    // notes), and its Resume needs no control: back to Ready as found.
    send(c, msg::Resume{});
    return pass("Ready -> Emergency -> Standby (profile openjaus), resumed");
  }
  if (*after != *before)
    return fail("Clear Emergency left it in " + state_text(*after) + ", not " + state_text(*before) + " as before");
  return pass(state_text(*before) + " -> Emergency -> " + state_text(*after));
}

// Two holders of the emergency (the runner and its second OCU): the first
// one's Clear leaves it in Emergency, the second one's returns it to the
// state it left ("provided that all emergency conditions have been cleared").
CaseOutcome emergency_two_holders(CaseContext& c) {
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  if (*before != msg::PrimaryStatus::ready && *before != msg::PrimaryStatus::standby)
    return skip("in " + state_text(*before) + ": Set Emergency is checked from Ready or Standby");
  auto second = c.second();
  if (!second) return fail(second.error().message());
  ocu::OcuSession& other = **second;
  send(c, msg::SetEmergency{{1}}, priority::kSafetyCritical);
  send_from(c, other, c.target(), msg::SetEmergency{{1}}, priority::kSafetyCritical);
  // Asked by the second holder: answered after its own Set Emergency.
  auto during = ask_from<msg::ReportComponentStatus>(c, other, msg::QueryComponentStatus{});
  send(c, msg::ClearEmergency{{1}}, priority::kSafetyCritical);
  auto after_first = primary_status(c);
  send_from(c, other, c.target(), msg::ClearEmergency{{1}}, priority::kSafetyCritical);  // never left set
  auto after_both = ask_from<msg::ReportComponentStatus>(c, other, msg::QueryComponentStatus{});
  if (!during) return fail("after two Set Emergency, " + during.error().message());
  const auto state_of = [](const msg::ReportComponentStatus& r) {
    return static_cast<msg::PrimaryStatus>(r.primary_status & 0x0F);
  };
  if (state_of(*during) != msg::PrimaryStatus::emergency)
    return fail("two Set Emergency left it in " + state_text(state_of(*during)) + ", not Emergency");
  if (!after_first) return fail("after the first holder's Clear Emergency, " + after_first.error().message());
  if (*after_first != msg::PrimaryStatus::emergency)
    return fail("the first holder's Clear Emergency left Emergency (for " + state_text(*after_first) +
                ") while the second OCU still held it");
  if (!after_both) return fail("after both holders' Clear Emergency, " + after_both.error().message());
  const auto after = state_of(*after_both);
  if (c.profile == Profile::openjaus && after == msg::PrimaryStatus::standby && *before == msg::PrimaryStatus::ready) {
    // Its Clear Emergency goes to Standby (docs/wire-format.md, "Interoperability");
    // its Resume needs no control.
    send(c, msg::Resume{});
    return pass("Ready -> Emergency (two holders) -> Emergency (one cleared) -> Standby (profile openjaus), resumed");
  }
  if (after != *before)
    return fail("both holders' Clear Emergency left it in " + state_text(after) + ", not " + state_text(*before) +
                " as before");
  return pass(state_text(*before) + " -> Emergency (two holders) -> Emergency (one cleared) -> " + state_text(after));
}

// The controller's Standby and Resume move it between Ready and Standby.
CaseOutcome standby_and_resume(CaseContext& c) {
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  if (*before != msg::PrimaryStatus::ready) return skip("in " + state_text(*before) + ", not Ready");
  ControlHeld control(c);
  if (!control.granted()) return skip("control not granted (" + control.why() + "): Resume needs the controller");
  send(c, msg::Standby{});
  auto standing_by = primary_status(c);
  send(c, msg::Resume{});
  auto resumed = primary_status(c);
  if (!standing_by) return fail("after Standby, " + standing_by.error().message());
  if (*standing_by != msg::PrimaryStatus::standby)
    return fail("Standby from its controller left it in " + state_text(*standing_by));
  if (!resumed) return fail("after Resume, " + resumed.error().message());
  if (*resumed != msg::PrimaryStatus::ready)
    return fail("Resume from its controller left it in " + state_text(*resumed));
  return pass("Ready -> Standby -> Ready");
}

// Commands that change a component's state are the controller's: Resume,
// Reset and Shutdown from anyone else change nothing, and it keeps answering.
CaseOutcome refused_without_control(CaseContext& c) {
  if (c.profile == Profile::openjaus)
    return skip(
        "profile openjaus: the RA 3.3 implementation lets anyone Shutdown, Standby, Resume and Reset "
        "(docs/wire-format.md); not sent");
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  if (*before == msg::PrimaryStatus::shutdown) return skip("already in Shutdown");
  auto controller = current_controller(c);
  if (!controller) return fail(controller.error().message());
  if (*controller == c.session.self()) return skip("the runner controls it");
  for (const char* command : {"Resume", "Reset", "Shutdown"}) {
    const std::string what(command);
    if (what == "Resume") send(c, msg::Resume{});
    if (what == "Reset") send(c, msg::Reset{});
    if (what == "Shutdown") send(c, msg::Shutdown{});
    auto after = primary_status(c);
    if (!after) return fail(what + " from a non-controller, then " + after.error().message());
    // Resume from Ready or Reset may pass through Initialize only when executed.
    if (*after != *before)
      return fail(what + " from a non-controller moved it from " + state_text(*before) + " to " + state_text(*after));
  }
  return pass("Resume, Reset and Shutdown from a non-controller: still " + state_text(*before));
}

// Every core query it accepts answered, decoding whole (the decoder checks
// the size and presence vector) with the report's code: "" when all were,
// else the first that was not.
std::string core_queries_unanswered(CaseContext& c, std::string& asked) {
  asked.clear();
  std::string wrong;
  const auto check = [&](std::string_view what, auto reply) {
    if (!wrong.empty()) return;
    asked += (asked.empty() ? "" : ", ") + std::string(what);
    if (!reply) wrong = std::string(what) + ": " + reply.error().message();
  };
  check("Identification",
        ask<msg::ReportIdentification>(c, msg::QueryIdentification{{msg::identification::kComponent}}));
  check("Component Status", ask<msg::ReportComponentStatus>(c, msg::QueryComponentStatus{}));
  check("Component Authority", ask<msg::ReportComponentAuthority>(c, msg::QueryComponentAuthority{}));
  check("Component Control", ask<msg::ReportComponentControl>(c, msg::QueryComponentControl{}));
  check("Heartbeat Pulse", ask<msg::ReportHeartbeatPulse>(c, msg::QueryHeartbeatPulse{}));
  check("Services", ask<msg::ReportServices>(c, msg::QueryServices{}));
  if (c.component.accepts(msg::QueryTime::code)) check("Time", ask<msg::ReportTime>(c, msg::QueryTime{{0x03}}));
  return wrong;
}

// The core queries are answered in every state but Shutdown: here in Ready,
// in Standby (its controller's) and in Emergency, the states an OCU can put
// it in. Initialize and Failure cannot be reached from outside on purpose.
CaseOutcome queries_in_every_state(CaseContext& c) {
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  if (*before != msg::PrimaryStatus::ready) return skip("in " + state_text(*before) + ", not Ready");
  std::string asked;
  if (auto wrong = core_queries_unanswered(c, asked); !wrong.empty()) return fail("in Ready, " + wrong);
  std::string states = "Ready";
  {
    ControlHeld control(c);
    if (control.granted()) {
      send(c, msg::Standby{});
      auto state = primary_status(c);
      std::string wrong;
      if (state && *state == msg::PrimaryStatus::standby) wrong = core_queries_unanswered(c, asked);
      send(c, msg::Resume{});
      if (!state) return fail("after Standby, " + state.error().message());
      if (!wrong.empty()) return fail("in Standby, " + wrong);
      if (*state == msg::PrimaryStatus::standby) states += ", Standby";
      // A round trip: the Resume is acted on before the Set Emergency below,
      // which a node may otherwise take first (its priority is higher), to
      // return to Standby when cleared.
      (void)primary_status(c);
    }
  }
  send(c, msg::SetEmergency{{1}}, priority::kSafetyCritical);
  auto state = primary_status(c);
  std::string wrong;
  if (state && *state == msg::PrimaryStatus::emergency) wrong = core_queries_unanswered(c, asked);
  send(c, msg::ClearEmergency{{1}}, priority::kSafetyCritical);  // never left set
  // Its Clear Emergency goes to Standby (docs/wire-format.md, "Interoperability").
  if (c.profile == Profile::openjaus) send(c, msg::Resume{});
  if (!state) return fail("after Set Emergency, " + state.error().message());
  if (!wrong.empty()) return fail("in Emergency, " + wrong);
  if (*state == msg::PrimaryStatus::emergency) states += ", Emergency";
  return pass(asked + " answered in " + states);
}

}  // namespace

std::span<const ConformanceCase> core_cases() {
  static const std::vector<ConformanceCase> list{
      {"core.identification", "answers Query Identification (component) with Report Identification type 4",
       "Part 3, Code 2B00h Query Identification; docs/wire-format.md: Liveness and discovery", nullptr, identification},
      {"core.status", "answers Query Component Status with a primary status the RA defines",
       "Part 3, Code 2002h Query Component Status, Figure 5.1", nullptr, status},
      {"core.authority", "answers Query Component Authority", "Part 3, Code 2001h Query Component Authority", nullptr,
       authority},
      {"core.services", "answers Query Services, listing the core queries it accepts",
       "Part 3, Code 2B03h Query Services; docs/wire-format.md: Liveness and discovery", nullptr, services},
      {"core.heartbeat", "answers Query Heartbeat Pulse with Report Heartbeat Pulse",
       "Part 3, Code 2202h Query Heartbeat Pulse", nullptr, heartbeat},
      {"core.emergency", "Set Emergency puts it in Emergency; Clear Emergency returns it to the state it left",
       "Part 3, Code 0006h Set Emergency, Code 0007h Clear Emergency", nullptr, emergency},
      {"core.emergency_two_holders",
       "with two holders, one Clear Emergency leaves it in Emergency; the second returns it to the state it left",
       "Part 3, Code 0007h Clear Emergency (\"provided that all emergency conditions have been cleared\")", nullptr,
       emergency_two_holders},
      {"core.standby_resume", "its controller's Standby and Resume move it Ready -> Standby -> Ready",
       "Part 3, Code 0003h Standby, Code 0004h Resume", nullptr, standby_and_resume},
      {"core.queries_in_every_state", "the core queries are answered, whole, in Ready, Standby and Emergency",
       "Part 3, Codes 2001h, 2002h, 2011h (\"All components must be able to respond to this message in any "
       "state\"); the other core queries (2B00h, 200Dh, 2202h, 2B03h) alike",
       nullptr, queries_in_every_state},
      {"core.refused_without_control", "Resume, Reset and Shutdown from a non-controller change nothing",
       "Part 3, Code 000Dh Request Component Control (commands are the controller's)", nullptr,
       refused_without_control},
  };
  return list;
}

}  // namespace jaus::conform
