// The core cases: what RA 3.x requires of every component, whatever its kind
// (Part 3 core messages; discovery per jaus-wire-notes.md). Each asks once
// and judges the answer; none leaves the component controlled.
#include "jaus/conform/conformance_case.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/ocu/names.hpp"

namespace jaus::conform {

namespace {

CaseOutcome pass(std::string detail) { return {Verdict::pass, std::move(detail)}; }
CaseOutcome fail(std::string detail) { return {Verdict::fail, std::move(detail)}; }

// Sends `query`, waits for a reply of type R from the target and decodes it.
template <class R, class Q>
Expected<R> ask(CaseContext& c, const Q& query) {
  auto reply = c.session.request(c.target, query, {R::code}, c.reply_timeout);
  if (!reply) return unexpected(reply.error());
  R report{};
  if (auto error = wire::decode_payload_into(reply->payload, report, c.session.options().dialect, kHeaderSize))
    return unexpected(make_error(ErrorCode::malformed, std::string(R::name) + " does not decode: " + error->message()));
  return report;
}

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
        return pass(std::to_string(report->services.size()) + " service entries, Query Component Status among the inputs");
  return fail("Report Services does not list Query Component Status (0x2002) among the inputs");
}

CaseOutcome control_round_trip(CaseContext& c) {
  // The lowest authority: a component that grants it must report us as its
  // controller; one that refuses answers Confirm 2 (or Reject); either is conformant.
  auto confirm = c.session.request(c.target, msg::RequestComponentControl{{0}},
                                   {msg::ConfirmComponentControl::code, msg::RejectComponentControl::code},
                                   c.reply_timeout);
  if (!confirm) return fail(confirm.error().message());
  if (confirm->header.command_code == msg::RejectComponentControl::code)
    return pass("control refused with Reject Component Control");
  msg::ConfirmComponentControl answer{};
  if (wire::decode_payload_into(confirm->payload, answer, c.session.options().dialect, kHeaderSize))
    return fail("Confirm Component Control does not decode");
  if (answer.response_code != msg::control_response::kAccepted)
    return pass("control refused: " + ocu::control_response_text(answer.response_code));
  auto held = ask<msg::ReportComponentControl>(c, msg::QueryComponentControl{});
  c.session.send(c.target, msg::ReleaseComponentControl{});
  if (!held) return fail("granted, then " + held.error().message());
  if (held->controller != c.session.self())
    return fail("granted, but Report Component Control names " + held->controller.to_string() + " as controller");
  auto after = ask<msg::ReportComponentControl>(c, msg::QueryComponentControl{});
  if (!after) return fail("released, then " + after.error().message());
  if (after->controller == c.session.self()) return fail("still reports us as controller after Release Component Control");
  return pass("granted, reported, released");
}

const std::vector<ConformanceCase>& cases() {
  static const std::vector<ConformanceCase> list{
      {"core.identification", "answers Query Identification (component) with Report Identification type 4",
       identification},
      {"core.status", "answers Query Component Status with a primary status the RA defines", status},
      {"core.authority", "answers Query Component Authority", authority},
      {"core.services", "answers Query Services, listing the core queries it accepts", services},
      {"core.control", "grants or refuses control as the RA says; a granted controller is reported and released",
       control_round_trip},
  };
  return list;
}

}  // namespace

std::span<const ConformanceCase> core_cases() { return cases(); }

}  // namespace jaus::conform
