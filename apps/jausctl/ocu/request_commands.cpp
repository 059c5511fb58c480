// The one-shot OCU commands: status, query, send, emergency. Over a lossy
// link (issue 32) a query is sent again every 250 ms until answered (queries
// are idempotent), and a command that must arrive (emergency, a command sent
// with `send`) goes with an ACK request, retransmitted until ACKed
// (jaus/ocu/must_arrive.hpp; docs/safety.md, "Loss: what must arrive").
#include <optional>

#include "jaus/messages/catalogue.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/names.hpp"
#include "jaus/ocu/repeated_query.hpp"
#include "jaus/ocu/wildcard_command.hpp"
#include "jaus/runtime/stop_counter.hpp"
#include "command_output.hpp"
#include "first_reply.hpp"
#include "image_file.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

namespace {

// An RA node NAKs a message that no component of it took.
constexpr std::string_view kRaNakMeans = "refused by its node (NAK): no component there took it";

// The status report of `target`, decoded.
jaus::Expected<jaus::msg::ReportComponentStatus> query_status(OcuSession& session,
                                                                          const jaus::Address& target,
                                                                          jaus::rt::Duration timeout) {
  auto reply = request_resending(session, target, jaus::msg::QueryComponentStatus{},
                                 {jaus::msg::ReportComponentStatus::code}, timeout);
  if (!reply) return jaus::unexpected(reply.error());
  jaus::msg::ReportComponentStatus report{};
  if (auto decoded = jaus::wire::decode_payload_into(reply->payload, report, session.options().dialect, jaus::kHeaderSize);
      !decoded)
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::malformed,
                                             "Report Component Status from " + reply->header.source.to_string() +
                                                 " does not decode: " + decoded.error().message()));
  return report;
}

// `send` retransmits until ACKed what commands (RA command class,
// 0x0000-0x1FFF: Resume, Standby, Shutdown, Reset, Set/Clear Emergency,
// control, service connections, Set ...), on the RA dialect: the common
// peer (openjaus) may ignore ACK requests, and would get it 10 times.
// Queries and reports go once: a lost query shows as no reply.
constexpr std::uint16_t kLastCommandCode = 0x1FFF;
bool is_command(const PreparedMessage& message) { return message.header.command_code <= kLastCommandCode; }
bool must_arrive(const PreparedMessage& message, jaus::wire::Dialect dialect) {
  return dialect == jaus::wire::Dialect::ra && is_command(message);
}

// How long a stop to a peer of the openjaus dialect waits for an ACK that
// may never come before its status is asked.
constexpr jaus::rt::Duration kOpenJausAckWait = std::chrono::seconds(1);

// A wildcard looks for its members at least this long (--timeout when
// longer): a vehicle that has just started answers within it.
constexpr jaus::rt::Duration kWildcardLooksFor = std::chrono::seconds(3);

std::string address_list(const std::vector<jaus::Address>& addresses) {
  std::string out;
  for (const auto& a : addresses) out += (out.empty() ? "" : ", ") + a.to_string();
  return out;
}

// A command to a wildcard (WildcardCommand): which components confirmed it
// on `out`; exit 1 when none did or some did not, with the line on `err`
// saying which. Never "sent" for what nobody confirmed (issue 49).
int run_wildcard(OcuSession& session, std::string_view command, const std::string& what,
                 const jaus::Address& target, jaus::Header header, std::span<const std::uint8_t> payload,
                 jaus::rt::Duration timeout, CommandIo io) {
  WildcardPolicy policy;
  policy.look_for = std::max(timeout, kWildcardLooksFor);
  const auto result = send_to_every_member(session, target, header, payload, policy);
  const std::string sent = what + " to " + target.to_string() + " by " + session.self().to_string();
  const auto confirmed = result.confirmed();
  const auto unconfirmed = result.unconfirmed();
  if (!confirmed.empty())
    io.out << sent << ": confirmed by " << confirmed.size() << (confirmed.size() == 1 ? " component" : " components")
           << " (" << address_list(confirmed) << ") in " << elapsed_text(result.elapsed) << "\n";
  const std::string stopped_warning =
      is_stop(header.command_code) ? ": it may NOT have stopped; stop it another way (its own stop button, the radio's)"
                                   : "";
  if (result.interrupted)
    return fail(io, command, sent + ": interrupted" + (unconfirmed.empty() ? "" : " before " + address_list(unconfirmed) + " confirmed it"));
  if (confirmed.empty())
    return fail(io, command, sent + ": no component confirmed it within " + elapsed_text(result.elapsed) +
                                 (result.members.empty() ? " (none answered" : " (" + address_list(unconfirmed) + " did not")
                                 + (result.broadcasts ? "; broadcast " + std::to_string(result.broadcasts) + " times)" : ")") +
                                 stopped_warning);
  if (!unconfirmed.empty())
    return fail(io, command, "not confirmed by " + address_list(unconfirmed) + stopped_warning);
  return kExitOk;
}

}  // namespace

int run_status(OcuSession& session, const jaus::Address& target, jaus::rt::Duration timeout, CommandIo io) {
  auto report = query_status(session, target, timeout);
  if (!report) return fail(io, "status", report.error());
  // The state by the name Report Component Status's JSON uses ("ready"), its number when it has none.
  const unsigned code = report->primary_status & 0x0F;
  const std::string_view name = jaus::wire::name_of(jaus::msg::kComponentStates, code);
  const Json out{{"component", target.to_string()},
                 {"primary_status", name.empty() ? Json(code) : Json(std::string(name))},
                 {"primary_status_code", code},
                 {"secondary_status", report->secondary_status},
                 // The stop counter of bits 20-31 (jaus/runtime/stop_counter.hpp).
                 {"stops", jaus::rt::stop_counter::of(report->secondary_status)},
                 {"emergency", is_emergency_state(report->primary_status)}};
  io.out << json_line(out) << "\n";
  return kExitOk;
}

int run_query(OcuSession& session, const jaus::Address& target, const PreparedMessage& query,
              std::uint16_t report_code, jaus::rt::Duration timeout, CommandIo io,
              const std::optional<std::string>& save_image) {
  auto reply = request_raw_resending(session, target, query.header, query.payload, {report_code}, timeout);
  if (!reply) return fail(io, "query", reply.error());
  auto json = message_json(*reply, session.options().dialect);
  if (!json) return fail(io, "query", json.error());
  if (save_image) {
    auto saved = save_report_image(*reply, *save_image);
    if (!saved) return fail(io, "query", saved.error());
    *json = with_saved_image(std::move(*json), *saved, *save_image);
  }
  io.out << json_line(*json) << "\n";
  return kExitOk;
}

int run_send(OcuSession& session, const jaus::Address& target, const PreparedMessage& message,
             jaus::rt::Duration timeout, CommandIo io) {
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, message.header.command_code);
  const std::string name = info ? std::string(info->name) : code_text(message.header.command_code);
  // A command to a wildcard reaches every component it names, each confirming it.
  if (target.is_broadcast() && is_command(message))
    return run_wildcard(session, "send", name, target, message.header, message.payload, timeout, io);
  const FirstReply<OcuSession> first(session, target);
  jaus::Header header = message.header;
  header.destination = target;
  const auto start = session.clock().now();
  if (must_arrive(message, session.options().dialect) && !target.is_broadcast()) {
    const auto arrival = send_must_arrive(session, target, header, message.payload);
    if (arrival.outcome != Arrival::acknowledged)
      return fail(io, "send", not_arrived_text(name, target, arrival, kRaNakMeans));
  } else {
    session.send_raw(header, message.payload);
  }
  // A command changes state: say who acted, the ID that holds what it left
  // (stderr: stdout is the reply's JSON).
  if (is_command(message))
    io.err << "jausctl send: " << name << " to " << target.to_string() << " by " << session.self().to_string()
           << (must_arrive(message, session.options().dialect) ? " (acknowledged)" : "") << "\n";
  // Commands have no reply in the RA: silence is not a failure here. With
  // the ID shared, what comes may be the other process's (a report of its
  // service connection): nothing is read as this command's reply.
  if (io.id_shared) return kExitOk;
  const auto waited = session.clock().now() - start;
  if (!first.reply() && waited < timeout)
    session.run_until([&] { return first.reply().has_value(); }, timeout - waited);
  if (!first.reply()) {
    if (session.interrupted()) return fail(io, "send", "interrupted");
    return kExitOk;
  }
  auto json = message_json(*first.reply(), session.options().dialect);
  if (!json) return fail(io, "send", json.error());
  io.out << json_line(*json) << "\n";
  return kExitOk;
}

int run_emergency(OcuSession& session, const jaus::Address& target, bool set, jaus::rt::Duration timeout,
                  CommandIo io) {
  // Bit 0 of the emergency code is Stop, the only condition the RA defines.
  const std::string what = set ? "Set Emergency" : "Clear Emergency";
  if (target.is_broadcast()) {
    // Every component it names, found or not yet, each confirming by its ACK (issue 49).
    std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
    jaus::Header header;
    header.command_code = set ? jaus::msg::SetEmergency::code : jaus::msg::ClearEmergency::code;
    header.priority = set ? jaus::priority::kSafetyCritical : jaus::priority::kDefault;
    const auto size = set ? jaus::wire::encode_payload(jaus::msg::SetEmergency{{1}}, payload)
                          : jaus::wire::encode_payload(jaus::msg::ClearEmergency{{1}}, payload);
    if (!size) return fail(io, "emergency", what + " does not encode");
    return run_wildcard(session, "emergency", what, target, header, std::span(payload).first(*size), timeout, io);
  }
  // Retransmitted until ACKed: the ACK comes once the component has acted on it.
  // A stop keeps trying longer (--stop-give-up-after). A peer of the
  // openjaus dialect may never ACK: its status is asked after a second.
  auto policy = jaus::ocu::MustArrivePolicy::for_code(
      set ? jaus::msg::SetEmergency::code : jaus::msg::ClearEmergency::code, session.options().must_arrive);
  if (session.options().dialect == jaus::wire::Dialect::openjaus) policy.give_up_after = kOpenJausAckWait;
  const auto arrival = set ? send_must_arrive(session, target, jaus::msg::SetEmergency{{1}},
                                              jaus::priority::kSafetyCritical, policy)
                           : send_must_arrive(session, target, jaus::msg::ClearEmergency{{1}}, jaus::priority::kDefault,
                                              policy);
  // The common RA 3.3 peer (--dialect openjaus) may ignore ACK requests:
  // there, only its status can tell (the state check below).
  const bool status_must_tell =
      arrival.outcome == Arrival::unacknowledged && session.options().dialect == jaus::wire::Dialect::openjaus;
  if (arrival.outcome != Arrival::acknowledged && !status_must_tell)
    return fail(io, "emergency", emergency_not_arrived_text(set, what, target, arrival, kRaNakMeans));
  if (status_must_tell)
    io.err << "jausctl emergency: " << not_arrived_text(what, target, arrival, kRaNakMeans)
           << " (the peer may ignore ACK requests): its status tells\n";
  return confirm_emergency_state(
      session, target, set, what, io, timeout, [&] { return query_status(session, target, timeout); },
      [](const jaus::msg::ReportComponentStatus& report) { return report.primary_status; });
}

}  // namespace jausctl::ocu
