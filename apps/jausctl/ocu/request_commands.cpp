// The one-shot OCU commands: status, query, send, emergency. Each sends one
// message and waits (up to the timeout) for the answer.
#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/names.hpp"
#include "image_file.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

namespace {

int fail(CommandIo io, std::string_view command, const std::string& why) {
  io.err << "jausctl " << command << ": " << why << "\n";
  return kExitFailure;
}
int fail(CommandIo io, std::string_view command, const jaus::Error& why) { return fail(io, command, why.message()); }

// The status report of `target`, decoded.
jaus::Expected<jaus::msg::ReportComponentStatus> query_status(OcuSession& session,
                                                                          const jaus::Address& target,
                                                                          jaus::rt::Duration timeout) {
  auto reply = session.request(target, jaus::msg::QueryComponentStatus{}, {jaus::msg::ReportComponentStatus::code},
                               timeout);
  if (!reply) return jaus::unexpected(reply.error());
  jaus::msg::ReportComponentStatus report{};
  if (auto decoded = jaus::wire::decode_payload_into(reply->payload, report, session.options().dialect, jaus::kHeaderSize);
      !decoded)
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::malformed,
                                             "Report Component Status from " + reply->header.source.to_string() +
                                                 " does not decode: " + decoded.error().message()));
  return report;
}

// After Clear Emergency: how long the component may take to leave Emergency, asked this often.
constexpr jaus::rt::Duration kClearSettles = std::chrono::seconds(1);
constexpr jaus::rt::Duration kClearPoll = std::chrono::milliseconds(100);

bool is_emergency(const jaus::msg::ReportComponentStatus& report) {
  return (report.primary_status & 0x0F) == static_cast<unsigned>(jaus::msg::PrimaryStatus::emergency);
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
                 {"emergency", is_emergency(*report)}};
  io.out << json_line(out) << "\n";
  return kExitOk;
}

int run_query(OcuSession& session, const jaus::Address& target, const PreparedMessage& query,
              std::uint16_t report_code, jaus::rt::Duration timeout, CommandIo io,
              const std::optional<std::string>& save_image) {
  jaus::Header header = query.header;
  header.destination = target;
  session.send_raw(header, query.payload);
  auto reply = session.await_reply(target, {report_code}, timeout);
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
  jaus::Header header = message.header;
  header.destination = target;
  session.send_raw(header, message.payload);
  // Commands have no reply in the RA: silence is not a failure here.
  auto reply = session.await_reply(target, {}, timeout);
  if (!reply) return kExitOk;
  auto json = message_json(*reply, session.options().dialect);
  if (!json) return fail(io, "send", json.error());
  io.out << json_line(*json) << "\n";
  return kExitOk;
}

int run_emergency(OcuSession& session, const jaus::Address& target, bool set, jaus::rt::Duration timeout,
                  CommandIo io) {
  // Bit 0 of the emergency code is Stop, the only condition the RA defines.
  if (set)
    session.send(target, jaus::msg::SetEmergency{{1}}, jaus::priority::kSafetyCritical);
  else
    session.send(target, jaus::msg::ClearEmergency{{1}});
  const std::string what = set ? "Set Emergency" : "Clear Emergency";
  if (target.is_broadcast()) {
    // Many components may answer; there is no single state to show.
    io.out << what << " sent to " << target.to_string() << " by " << session.self().to_string() << "\n";
    return kExitOk;
  }
  // The status query follows the command through the same queue: its answer shows the outcome.
  auto report = query_status(session, target, timeout);
  if (!report) return fail(io, "emergency", what + " sent, but " + report.error().message() + " to show its state");
  const std::string state = primary_status_text(report->primary_status);
  if (set && !is_emergency(*report))
    return fail(io, "emergency", target.to_string() + " is in " + state + " after Set Emergency");
  // A clear may need a moment: a vehicle whose platform must first report its
  // emergency flag clear stays in Emergency until it does (docs/safety.md).
  const auto settle_until = session.clock().now() + std::min<jaus::rt::Duration>(timeout, kClearSettles);
  while (!set && is_emergency(*report) && session.clock().now() < settle_until) {
    session.run_for(kClearPoll);
    auto again = query_status(session, target, timeout);
    if (!again) break;
    report = std::move(again);
  }
  if (!set && is_emergency(*report))
    return fail(io, "emergency", target.to_string() + " is still in Emergency: another sender holds it, " +
                                     "the platform's own stop does, or " + session.self().to_string() + " never set it");
  // Who set or cleared it: the holder's ID is what clears the hold later (--as).
  io.out << target.to_string() << ": emergency " << (set ? "set" : "cleared") << " by " << session.self().to_string()
         << " (state " << state << ")\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
