// The robustness cases: what a component does with what it cannot use (an
// unknown code, a payload cut short or running on). No reply may claim
// success, and the component keeps answering.
#include <algorithm>

#include "case_support.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "state_support.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

// Sends raw bytes as a message with `code` and records them.
void send_raw(CaseContext& c, std::uint16_t code, std::vector<std::uint8_t> payload) {
  Header h;
  h.command_code = code;
  h.source = c.session.self();
  h.destination = c.target();
  h.data_size = static_cast<std::uint16_t>(payload.size());
  c.session.send_raw(h, payload);
  c.exchange.push_back(Exchanged{true, h, std::move(payload), c.session.clock().now() - c.started});
}

// What came back, if anything, within half a second (or the reply budget if
// shorter): on a network a reply takes milliseconds, and absence is waited for.
std::optional<std::uint16_t> any_other_reply(CaseContext& c) {
  auto reply =
      c.session.await_reply(c.target(), {}, std::min<rt::Duration>(c.reply_timeout, std::chrono::milliseconds(500)));
  if (!reply) return std::nullopt;
  return reply->header.command_code;
}

CaseOutcome still_answers(CaseContext& c, const std::string& after) {
  auto state = primary_status(c);
  if (!state) return fail("after " + after + ", " + state.error().message());
  return pass(after + ": no reply, still answers (" + state_text(*state) + ")");
}

CaseOutcome unknown_code(CaseContext& c) {
  constexpr std::uint16_t kUnknown = 0x0FFE;  // a command code no RA message has
  send_raw(c, kUnknown, {1, 2, 3});
  if (auto reply = any_other_reply(c)) return fail("answered an unknown code with " + ocu::code_text(*reply));
  return still_answers(c, "unknown code 0x0FFE");
}

CaseOutcome truncated_query(CaseContext& c) {
  // Query Identification needs its query type: an empty payload is malformed.
  send_raw(c, msg::QueryIdentification::code, {});
  if (auto reply = any_other_reply(c); reply && *reply == msg::ReportIdentification::code)
    return fail("answered a Query Identification without its query type with Report Identification");
  return still_answers(c, "Query Identification cut short");
}

CaseOutcome overlong_command(CaseContext& c) {
  // Set Emergency is two bytes; four are not Set Emergency.
  auto before = primary_status(c);
  if (!before) return fail(before.error().message());
  send_raw(c, msg::SetEmergency::code, {1, 0, 0, 0});
  auto after = primary_status(c);
  send(c, msg::ClearEmergency{{1}}, priority::kSafetyCritical);  // never left set, whatever it did
  if (!after) return fail("after an overlong Set Emergency, " + after.error().message());
  if (*after != *before)
    return fail("acted on a Set Emergency with two bytes too many: " + state_text(*before) + " -> " +
                state_text(*after));
  return pass("an overlong Set Emergency changed nothing (" + state_text(*after) + ")");
}

}  // namespace

std::span<const ConformanceCase> robustness_cases() {
  static const std::vector<ConformanceCase> list{
      {"robust.unknown_code", "an unknown code gets no reply and the component keeps answering",
       "Part 2 (unknown messages are ignored); issue 14", nullptr, unknown_code},
      {"robust.truncated", "a query cut short is not answered as if whole; the component keeps answering",
       "Part 3, Code 2B00h Query Identification (field 1 is required)", nullptr, truncated_query},
      {"robust.overlong", "a command with bytes after its last field is not executed",
       "Part 2 (data size is the message's size)", nullptr, overlong_command},
  };
  return list;
}

}  // namespace jaus::conform
