// The control cases: who may take a component's control, how it is reported
// and released (Part 3, Request/Release/Confirm Component Control). Each
// leaves nobody in control that the runner put there.
#include <algorithm>

#include "case_support.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "state_support.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

// A component that grants control reports its controller and forgets it on
// release; one that refuses answers Confirm 2 or Reject, which is conformant.
CaseOutcome round_trip(CaseContext& c) {
  std::string granted_detail;
  {
    ControlHeld control(c, 255);
    if (!control.granted()) return pass("control refused (" + control.why() + ")");
    auto held = current_controller(c);
    if (!held) return fail("granted, then " + held.error().message());
    if (*held != c.session.self())
      return fail("granted, but Report Component Control names " + held->to_string() + " as controller");
  }  // released
  auto after = current_controller(c);
  if (!after) return fail("released, then " + after.error().message());
  if (*after == c.session.self()) return fail("still reports the runner as controller after Release Component Control");
  return pass("granted, reported, released");
}

// A request with less authority than the component's own is refused, and
// refused requests leave the controller as it was.
CaseOutcome lower_authority_refused(CaseContext& c) {
  if (c.profile == Profile::openjaus)
    return skip("profile openjaus: the RA 3.3 implementation never compares authorities (docs/wire-format.md)");
  auto own = ask<msg::ReportComponentAuthority>(c, msg::QueryComponentAuthority{});
  if (!own) return fail(own.error().message());
  if (own->authority == 0) return skip("its authority is 0: no lower authority to ask with");
  auto before = current_controller(c);
  if (!before) return fail(before.error().message());
  const std::uint8_t lower = static_cast<std::uint8_t>(own->authority - 1);
  ControlHeld control(c, lower);
  if (control.granted())
    return fail("granted to authority " + std::to_string(lower) + " below its own " + std::to_string(own->authority));
  auto after = current_controller(c);
  if (!after) return fail(after.error().message());
  if (*after != *before) return fail("a refused request moved its controller to " + after->to_string());
  return pass("authority " + std::to_string(lower) + " refused (" + control.why() + ")");
}

// Release Component Control from a non-controller leaves control where it is.
CaseOutcome release_by_non_controller(CaseContext& c) {
  auto before = current_controller(c);
  if (!before) return fail(before.error().message());
  if (*before == c.session.self()) return skip("the runner controls it");
  send(c, msg::ReleaseComponentControl{});
  auto after = current_controller(c);
  if (!after) return fail(after.error().message());
  if (*after != *before)
    return fail("a Release from a non-controller moved its controller from " + before->to_string() + " to " +
                after->to_string());
  return pass(before->is_valid() ? "controller " + before->to_string() + " kept" : "still uncontrolled");
}

// Asking again while in control keeps control (a controller's periodic renewal).
CaseOutcome controller_asks_again(CaseContext& c) {
  ControlHeld control(c, 255);
  if (!control.granted()) return skip("control not granted (" + control.why() + ")");
  send(c, msg::RequestComponentControl{{255}});
  auto reply = await(c, {msg::ConfirmComponentControl::code, msg::RejectComponentControl::code});
  if (!reply) return fail("the controller asked again: " + reply.error().message());
  if (reply->header.command_code == msg::RejectComponentControl::code)
    return fail("the controller asked again and was rejected");
  auto confirm = decode<msg::ConfirmComponentControl>(c, *reply);
  if (!confirm) return fail(confirm.error().message());
  if (confirm->response_code != msg::control_response::kAccepted)
    return fail("the controller asked again and got response " + std::to_string(confirm->response_code));
  auto held = current_controller(c);
  if (!held) return fail(held.error().message());
  if (*held != c.session.self()) return fail("after asking again, the controller is " + held->to_string());
  return pass("kept control");
}

// The component's own authority: the floor a requester must reach.
Expected<std::uint8_t> own_authority(CaseContext& c) {
  auto own = ask<msg::ReportComponentAuthority>(c, msg::QueryComponentAuthority{});
  if (!own) return unexpected(own.error());
  return own->authority;
}

// Asks for control from the runner; true when granted (Confirm 0). A reply
// of Reject, Confirm 1 or 2, or none, is a refusal.
bool runner_granted(CaseContext& c, std::uint8_t authority, std::string& seen) {
  send(c, msg::RequestComponentControl{{authority}});
  auto reply = await(c, {msg::ConfirmComponentControl::code, msg::RejectComponentControl::code});
  if (!reply) {
    seen = "no answer";
    return false;
  }
  if (reply->header.command_code == msg::RejectComponentControl::code) {
    seen = "Reject";
    return false;
  }
  auto confirm = decode<msg::ConfirmComponentControl>(c, *reply);
  if (!confirm) {
    seen = confirm.error().message();
    return false;
  }
  seen = "Confirm " + std::to_string(confirm->response_code);
  return confirm->response_code == msg::control_response::kAccepted;
}

// Controlled by another requester (the second OCU) at authority A: requests
// at A - 1 and at A are refused and leave the controller as it was (control
// is "uninterruptible" but for a higher authority).
CaseOutcome other_requester_refused(CaseContext& c) {
  if (c.profile == Profile::openjaus)
    return skip("profile openjaus: the RA 3.3 implementation never compares authorities (docs/wire-format.md)");
  auto own = own_authority(c);
  if (!own) return fail(own.error().message());
  if (*own == 255) return skip("its authority is 255: no authority above it for the controller");
  auto second = c.second();
  if (!second) return fail(second.error().message());
  const auto held = static_cast<std::uint8_t>(*own + 1);
  ControlHeld control(c, held, **second);
  if (!control.granted())
    return skip("control not granted to the second OCU at authority " + std::to_string(held) + " (" + control.why() +
                ")");
  std::string seen;
  for (const std::uint8_t asked : {static_cast<std::uint8_t>(held - 1), held}) {
    const std::string what = "authority " + std::to_string(asked) + " from another requester";
    if (runner_granted(c, asked, seen)) {
      send(c, msg::ReleaseComponentControl{});
      return fail(what + " took control from its controller at authority " + std::to_string(held));
    }
    auto controller = current_controller(c);
    if (!controller) return fail(what + " refused, then " + controller.error().message());
    if (*controller != (*second)->self())
      return fail(what + " refused (" + seen + "), but its controller is now " + controller->to_string() + ", not " +
                  (*second)->self().to_string());
  }
  return pass("controlled at authority " + std::to_string(held) + ": authority " + std::to_string(held - 1) + " and " +
              std::to_string(held) + " from another requester refused, controller kept");
}

// A higher authority from another requester takes control; the controller
// it takes it from is told with Reject Component Control.
CaseOutcome higher_authority_takes_over(CaseContext& c) {
  auto own = own_authority(c);
  if (!own) return fail(own.error().message());
  if (*own >= 254) return skip("its authority is " + std::to_string(*own) + ": no two authorities above it");
  auto second = c.second();
  if (!second) return fail(second.error().message());
  const auto held = static_cast<std::uint8_t>(*own + 1);
  ControlHeld by_second(c, held, **second);
  if (!by_second.granted())
    return skip("control not granted to the second OCU at authority " + std::to_string(held) + " (" + by_second.why() +
                ")");
  bool rejected = false;
  const auto listener = (*second)->listen([&](const ocu::Received& r) {
    rejected |= r.header.source == c.target() && r.header.command_code == msg::RejectComponentControl::code;
  });
  const auto higher = static_cast<std::uint8_t>(held + 1);
  ControlHeld by_runner(c, higher);
  if (by_runner.granted()) c.session.run_until([&] { return rejected; }, c.reply_timeout);
  (*second)->unlisten(listener);
  if (!by_runner.granted())
    return fail("authority " + std::to_string(higher) + " from another requester refused (" + by_runner.why() +
                ") while the controller held " + std::to_string(held) + ": the highest authority must be accepted");
  auto controller = current_controller(c);
  if (!controller) return fail("taken over, then " + controller.error().message());
  if (*controller != c.session.self()) return fail("taken over, but its controller is " + controller->to_string());
  if (!rejected) return fail("taken over, but the controller it was taken from got no Reject Component Control");
  return pass("authority " + std::to_string(higher) + " took control from " + std::to_string(held) +
              ", which got Reject Component Control");
}

// The controller asking again at a lower authority (still at or above the
// component's own) keeps control at that authority: Report Component Control
// gives it, and another requester above it but not above the old one now
// takes over ("must always accept the control of the highest authority").
CaseOutcome controller_lowers_authority(CaseContext& c) {
  if (c.profile == Profile::openjaus)
    return skip("profile openjaus: the RA 3.3 implementation never compares authorities (docs/wire-format.md)");
  auto own = own_authority(c);
  if (!own) return fail(own.error().message());
  if (*own >= 253) return skip("its authority is " + std::to_string(*own) + ": no three authorities from it up");
  const auto low = static_cast<std::uint8_t>(*own + 1);
  const auto high = static_cast<std::uint8_t>(*own + 2);
  ControlHeld control(c, high);
  if (!control.granted())
    return skip("control not granted at authority " + std::to_string(high) + " (" + control.why() + ")");
  std::string seen;
  if (!runner_granted(c, low, seen))
    return fail("the controller asked again at authority " + std::to_string(low) + " (from " + std::to_string(high) +
                ") and was refused (" + seen + ")");
  auto report = ask<msg::ReportComponentControl>(c, msg::QueryComponentControl{});
  if (!report) return fail("after asking again lower, " + report.error().message());
  if (report->controller != c.session.self())
    return fail("after asking again lower, Report Component Control names " + report->controller.to_string());
  if (report->authority != low)
    return fail("the controller asked again at authority " + std::to_string(low) + ", Report Component Control gives " +
                std::to_string(report->authority));
  auto second = c.second();
  if (!second) return fail(second.error().message());
  ControlHeld by_second(c, high, **second);
  if (!by_second.granted())
    return fail("authority " + std::to_string(high) + " from another requester refused (" + by_second.why() +
                ") while the controller held " + std::to_string(low));
  return pass("asked again at " + std::to_string(low) + " from " + std::to_string(high) + ": kept, reported at " +
              std::to_string(low) + ", then taken over at " + std::to_string(high));
}

// Controlled by another requester: the runner's Release moves nothing; the
// controller's own Release ends control.
CaseOutcome release_by_other_requester(CaseContext& c) {
  auto second = c.second();
  if (!second) return fail(second.error().message());
  ControlHeld by_second(c, 255, **second);
  if (!by_second.granted()) return skip("control not granted to the second OCU (" + by_second.why() + ")");
  send(c, msg::ReleaseComponentControl{});
  auto kept = current_controller(c);
  if (!kept) return fail(kept.error().message());
  if (*kept != (*second)->self())
    return fail("a Release from another requester moved its controller from " + (*second)->self().to_string() + " to " +
                kept->to_string());
  by_second.release();
  auto after = current_controller(c);
  if (!after) return fail("released by its controller, then " + after.error().message());
  if (*after == (*second)->self()) return fail("still reports its controller after the controller's Release");
  return pass("another requester's Release ignored; the controller's ended control");
}

// How long the silent-requester case waits for the component to notice:
// well over the usual timeouts (controller 3 s, node 5 s), so that a pass
// never depends on luck and a fail on a live node costs this much only.
constexpr rt::Duration kSilenceLimit = std::chrono::seconds(10);
// Reports that stop for this long have stopped (an SC at 10 Hz).
constexpr rt::Duration kReportsStopped = std::chrono::seconds(1);

// A requester that falls silent (the second OCU's link closed: no
// heartbeats, no answer to liveness queries) loses control and its service
// connections: another requester (the runner) sees the controller go, and
// the silent requester's port sees the reports stop.
CaseOutcome silent_requester(CaseContext& c) {
  auto second = c.second();
  if (!second) return fail(second.error().message());
  ocu::OcuSession& silent = **second;
  const Address silent_address = silent.self();
  std::string notes;
  // Control, at the highest authority.
  send_from(c, silent, c.target(), msg::RequestComponentControl{{255}});
  auto reply = await_at(c, silent, {msg::ConfirmComponentControl::code, msg::RejectComponentControl::code});
  bool controlled = false;
  if (reply && reply->header.command_code == msg::ConfirmComponentControl::code)
    if (auto confirm = decode<msg::ConfirmComponentControl>(c, *reply))
      controlled = confirm->response_code == msg::control_response::kAccepted;
  if (controlled && c.profile == Profile::openjaus) {
    send_from(c, silent, c.target(), msg::ReleaseComponentControl{});
    controlled = false;
    notes = "control not checked (profile openjaus: the RA 3.3 implementation has no control timeout); ";
  }
  // A service connection, for the report it provides with the highest code
  // (its kind's rather than the core Report Component Status, where it has one).
  std::optional<msg::ConfirmServiceConnection> sc;
  std::uint16_t sc_code = 0;
  if (!c.component.outputs.empty()) {
    const auto& [code, presence] = *c.component.outputs.rbegin();
    sc_code = code;
    msg::CreateServiceConnection create;
    create.command_code = sc_code;
    create.periodic_rate_hz = 10;
    create.presence_vector = presence;
    auto confirm = ask_from<msg::ConfirmServiceConnection>(c, silent, create);
    if (confirm && confirm->response_code == msg::sc_response::kCreated) sc = *confirm;
  }
  // What the fresh requester at the silent one's address cleans up when the
  // component did not.
  const auto clean_up = [&](bool release, bool terminate) {
    auto fresh = c.second();
    if (!fresh) return;
    if (release) send_from(c, **fresh, c.target(), msg::ReleaseComponentControl{});
    if (terminate && sc) send_from(c, **fresh, c.target(), msg::TerminateServiceConnection{{sc_code, sc->instance_id}});
  };
  if (!controlled && !sc) return skip(notes + "neither control nor a service connection granted: nothing to lose");
  if (sc) {
    bool report = false;
    const auto listener = silent.listen([&](const ocu::Received& r) {
      report |= r.header.source == c.target() && r.header.service_connection && r.header.command_code == sc_code;
    });
    c.session.run_until([&] { return report; }, c.reply_timeout);
    silent.unlisten(listener);
    if (!report) {
      clean_up(controlled, true);
      return fail("no report on the service connection before the silence, in " + ocu::seconds_text(c.reply_timeout));
    }
  }
  if (auto silenced = c.silence_second(); !silenced) {
    clean_up(controlled, true);
    return fail(silenced.error().message());
  }
  const auto silent_since = c.session.clock().now() - c.started;
  const auto last_report = [&] {
    rt::Duration last = silent_since;
    for (const auto& e : c.exchange)
      if (e.second && !e.sent && e.header.service_connection && e.header.command_code == sc_code)
        last = std::max(last, e.at);
    return last;
  };
  std::optional<rt::Duration> control_dropped_after;
  bool reports_stopped = !sc;
  for (;;) {
    const auto now = c.session.clock().now() - c.started;
    if (controlled && !control_dropped_after)
      if (auto controller = current_controller(c); controller && *controller != silent_address)
        control_dropped_after = c.session.clock().now() - c.started - silent_since;
    if (sc) reports_stopped = now - last_report() >= kReportsStopped;
    if ((!controlled || control_dropped_after) && reports_stopped) break;
    if (now - silent_since >= kSilenceLimit) break;
    c.session.run_for(std::chrono::milliseconds(250));
  }
  const bool kept_control = controlled && !control_dropped_after;
  if (kept_control || !reports_stopped) clean_up(kept_control, !reports_stopped);
  if (kept_control)
    return fail("its controller fell silent and kept control for " + ocu::seconds_text(kSilenceLimit) +
                " (controller liveness)");
  if (!reports_stopped)
    return fail("reports on a silent requester's service connection still came " + ocu::seconds_text(kSilenceLimit) +
                " after it fell silent");
  if (control_dropped_after)
    notes += "control dropped after " + ocu::seconds_text(*control_dropped_after) + " of silence";
  if (sc)
    notes += std::string(control_dropped_after ? ", " : "") + ocu::code_text(sc_code) + " reports stopped after " +
             ocu::seconds_text(last_report() - silent_since);
  return pass(notes);
}

}  // namespace

std::span<const ConformanceCase> control_cases() {
  static const std::vector<ConformanceCase> list{
      {"control.round_trip", "grants or refuses control; a granted controller is reported and released",
       "Part 3, Code 000Dh Request Component Control, Code 000Eh Release Component Control, Code 200Dh Query "
       "Component Control",
       nullptr, round_trip},
      {"control.lower_authority_refused", "a request below the component's authority is refused and moves nothing",
       "Part 3, Code 000Dh Request Component Control", nullptr, lower_authority_refused},
      {"control.release_by_non_controller", "Release Component Control from a non-controller moves nothing",
       "Part 3, Code 000Eh Release Component Control", nullptr, release_by_non_controller},
      {"control.controller_asks_again", "the controller asking again keeps control",
       "Part 3, Code 000Dh Request Component Control", nullptr, controller_asks_again},
      {"control.other_requester_refused",
       "controlled at authority A, a request at A - 1 or A from another requester is refused and moves nothing",
       "Part 3, Code 000Dh Request Component Control (uninterruptible control)", nullptr, other_requester_refused},
      {"control.higher_authority_takes_over",
       "a higher authority from another requester takes control; the controller gets Reject Component Control",
       "Part 3, Code 000Dh Request Component Control, Code 0010h Reject Component Control", nullptr,
       higher_authority_takes_over},
      {"control.controller_lowers_authority",
       "the controller asking again at a lower authority keeps control at it; a higher requester then takes over",
       "Part 3, Code 000Dh Request Component Control (the highest authority requesting is always accepted), Code "
       "400Dh Report Component Control",
       nullptr, controller_lowers_authority},
      {"control.release_by_other_requester",
       "controlled, a Release from another requester moves nothing; the controller's Release ends control",
       "Part 3, Code 000Eh Release Component Control", nullptr, release_by_other_requester},
      {"control.silent_requester", "a requester that falls silent loses control and its service connections",
       "docs/architecture.md: controller liveness (controller_timeout_s) and a silent node's service connections; "
       "docs/wire-format.md: Liveness and discovery (Part 3 gives no timeout)",
       nullptr, silent_requester},
  };
  return list;
}

}  // namespace jaus::conform
