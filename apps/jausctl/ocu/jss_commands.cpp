// The session commands of --dialect jss: status, query, send, emergency,
// control, subscribe, each on a JssSession. Queries are resent every 250 ms
// until answered; commands go with an ACK request, resent until ACKed
// (JssSession::send_contents_must_arrive), as the RA commands do.
#include <algorithm>

#include "jaus/jss/all.hpp"
#include "jaus/ocu/jss_control.hpp"
#include "jaus/ocu/jss_events.hpp"
#include "jaus/ocu/names.hpp"
#include "jaus/ocu/rate_meter.hpp"
#include "command_output.hpp"
#include "first_reply.hpp"
#include "jss_commands.hpp"

namespace jausctl::ocu {

namespace {

namespace jss_msg = jaus::jss::msg;
using jaus::jss::JssId;

constexpr std::uint16_t kFirstQueryId = 0x2000;  // below: commands
// A JSS node's NAK gives no reason.
constexpr std::string_view kJssNakMeans = "refused (NAK)";

// The JSON of received contents, as `jausctl msg decode --dialect jss` prints them, with who sent them.
jaus::Expected<Json> received_json(const JssReceived& message) {
  auto json = jaus::jss::contents_to_json(message.contents);
  if (!json) {
    jaus::Error e = json.error();
    e.detail = "from " + message.source().to_string() + ": " + e.detail;
    return jaus::unexpected(std::move(e));
  }
  (*json)["source"] = message.source().to_string();
  return json;
}

std::string message_name(std::span<const std::uint8_t> contents) {
  const auto id = jaus::jss::message_id_of(contents);
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::jss, id);
  return info ? std::string(info->name) : code_text(id);
}

jaus::Expected<jss_msg::ReportStatus> query_status(JssSession& session, const JssId& target, jaus::rt::Duration timeout) {
  auto report = session.query<jss_msg::ReportStatus>(target, jss_msg::QueryStatus{}, timeout);
  if (!report && report.error().code != jaus::ErrorCode::timeout && report.error().code != jaus::ErrorCode::interrupted)
    return jaus::unexpected(
        jaus::make_error(jaus::ErrorCode::malformed,
                         "Report Status from " + target.to_string() + " does not decode: " + report.error().message()));
  return report;
}

}  // namespace

int run_jss_status(JssSession& session, const JssId& target, jaus::rt::Duration timeout, CommandIo io) {
  auto report = query_status(session, target, timeout);
  if (!report) return fail(io, "status", report.error().message());
  const unsigned code = report->status & 0x0F;
  const std::string_view name = jaus::wire::name_of(jaus::msg::kComponentStates, code);
  const Json out{{"component", target.to_string()},
                 {"primary_status", name.empty() ? Json(code) : Json(std::string(name))},
                 {"primary_status_code", code},
                 {"emergency", is_emergency_state(report->status)}};
  io.out << json_line(out) << "\n";
  return kExitOk;
}

int run_jss_query(JssSession& session, const JssId& target, const JssPreparedQuery& query, jaus::rt::Duration timeout,
                  CommandIo io) {
  auto reply = session.request_contents(target, query.contents, {query.report_id}, timeout);
  if (!reply) return fail(io, "query", reply.error().message());
  auto json = received_json(*reply);
  if (!json) return fail(io, "query", json.error().message());
  io.out << json_line(*json) << "\n";
  return kExitOk;
}

int run_jss_send(JssSession& session, const JssId& target, const std::vector<std::uint8_t>& message,
                 jaus::rt::Duration timeout, CommandIo io) {
  const FirstReply<JssSession> first(session, target);
  const auto start = session.clock().now();
  const auto id = jaus::jss::message_id_of(message);
  if (id < kFirstQueryId && !target.is_broadcast()) {
    const auto priority =
        id == jss_msg::SetEmergency::code ? jaus::jss::JudpPriority::safety_critical : jaus::jss::JudpPriority::normal;
    const auto arrival = session.send_contents_must_arrive(target, message, priority);
    if (arrival.outcome != Arrival::acknowledged)
      return fail(io, "send", not_arrived_text(message_name(message), target, arrival, kJssNakMeans));
  } else {
    session.send_contents(target, message);
  }
  // JSS commands mostly have no reply: silence is not a failure.
  const auto waited = session.clock().now() - start;
  if (!first.reply() && waited < timeout)
    session.run_until([&] { return first.reply().has_value(); }, timeout - waited);
  if (!first.reply()) return session.interrupted() ? fail(io, "send", "interrupted") : kExitOk;
  auto json = received_json(*first.reply());
  if (!json) return fail(io, "send", json.error().message());
  io.out << json_line(*json) << "\n";
  return kExitOk;
}

int run_jss_emergency(JssSession& session, const JssId& target, bool set, jaus::rt::Duration timeout, CommandIo io) {
  jss_msg::SetEmergency set_message;
  set_message.emergency_code = 1;  // STOP, the only code JSS defines
  jss_msg::ClearEmergency clear_message;
  clear_message.emergency_code = 1;
  // A stop keeps trying longer (the session's policy for its ID: --stop-give-up-after).
  const auto arrival = set ? session.send_must_arrive(target, set_message, jaus::jss::JudpPriority::safety_critical)
                           : session.send_must_arrive(target, clear_message);
  const std::string what = set ? "Set Emergency" : "Clear Emergency";
  if (target.is_broadcast()) {
    if (arrival.outcome == Arrival::interrupted) return fail(io, "emergency", what + " interrupted");
    io.out << what << " sent to " << target.to_string() << " by " << session.self().to_string() << " ("
           << transmissions_text(arrival) << "; a broadcast is not acknowledged)\n";
    return kExitOk;
  }
  if (arrival.outcome != Arrival::acknowledged)
    return fail(io, "emergency", emergency_not_arrived_text(set, what, target, arrival, kJssNakMeans));
  return confirm_emergency_state(
      session, target, set, what, io, timeout, [&] { return query_status(session, target, timeout); },
      [](const jss_msg::ReportStatus& report) { return report.status; });
}

int run_jss_control(JssSession& session, const JssControlCommand& command, CommandIo io) {
  const std::string what = "control of " + command.target.to_string();
  JssControlHold::Options options;
  options.authority = command.authority;
  options.request_timeout = command.timeout;
  auto hold = JssControlHold::take(session, command.target, options);
  if (!hold)
    return fail(io, "control",
                hold.error().code == jaus::ErrorCode::refused ? what + " refused: " + hold.error().message()
                                                              : hold.error().message());
  io.out << what << " granted to " << session.self().to_string() << " (authority " << int{command.authority}
         << "; timeout " << int{(*hold)->timeout_s()} << " s, requested again every "
         << seconds_text((*hold)->refresh_period()) << ")\n"
         << std::flush;
  const auto start = session.clock().now();
  const bool held = (*hold)->hold_for(command.hold_for);
  const auto elapsed = elapsed_text(session.clock().now() - start);
  if (!held) return fail(io, "control", what + " lost after " + elapsed + ": " + (*hold)->lost_reason());
  auto released = (*hold)->release(command.timeout);
  if (!released)
    return fail(
        io, "control",
        what + ": Release Control not answered (" + released.error().message() + "); its timeout ends the control");
  io.out << what << " released after " << elapsed << "\n";
  return kExitOk;
}

int run_jss_subscribe(JssSession& session, const JssSubscribeCommand& command, CommandIo io) {
  auto& clock = session.clock();
  const std::string label = message_name(command.query.contents) + " events from " + command.target.to_string();
  RateMeter meter(clock.now());
  bool output_broken = false;
  JssEventOptions options;
  options.type = command.every_change ? JssEventType::every_change : JssEventType::periodic;
  options.rate_hz = command.rate_hz;
  options.request_timeout = command.timeout;
  auto event =
      JssEvent::create(session, command.target, command.query.contents, options, [&](const JssEventReport& report) {
        meter.tick(clock.now());
        auto json = jaus::jss::contents_to_json(report.report);
        if (!json) {
          io.err << "jausctl subscribe: " << json.error().message() << "\n";
          return;
        }
        (*json)["source"] = report.provider.to_string();
        (*json)["event"] = Json{{"event_id", report.event_id}, {"sequence", report.sequence}};
        io.out << json_line(*json) << "\n" << std::flush;
        output_broken = !io.out;
      });
  if (!event) return fail(io, "subscribe", event.error().message());
  io.err << "jausctl subscribe: " << label << (command.every_change ? " on every change" : "") << " at "
         << hz_text((*event)->confirmed_rate_hz()) << " Hz (event " << int{(*event)->event_id()} << ")\n";
  const auto start = clock.now();
  const auto limit = command.run_for.value_or(std::chrono::hours(24 * 365));
  const auto finished = [&] {
    return output_broken || (command.count && meter.count() >= *command.count) || !(*event)->open();
  };
  session.run_until(finished, limit);
  const bool ended_by_provider = !(*event)->open();
  const auto cancelled = (*event)->cancel();
  io.err << "jausctl subscribe: " << label << ": " << summary_text(meter.total())
         << (ended_by_provider ? "; the event was ended by its provider"
             : cancelled       ? "; event cancelled"
                               : "; Cancel Event not confirmed")
         << "\n";
  if (command.count && meter.count() < *command.count && !session.interrupted() && !output_broken) {
    io.err << "jausctl subscribe: only " << meter.count() << " of " << *command.count << " events within "
           << elapsed_text(clock.now() - start) << "\n";
    return kExitFailure;
  }
  return kExitOk;
}

}  // namespace jausctl::ocu
