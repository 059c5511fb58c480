// The control cases: who may take a component's control, how it is reported
// and released (Part 3, Request/Release/Confirm Component Control). Each
// leaves nobody in control that the runner put there.
#include "case_support.hpp"
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
    return skip("profile openjaus: the RA 3.3 implementation never compares authorities (wire notes)");
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

const std::vector<ConformanceCase>& cases() {
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
  };
  return list;
}

}  // namespace

std::span<const ConformanceCase> control_cases() { return cases(); }

}  // namespace jaus::conform
