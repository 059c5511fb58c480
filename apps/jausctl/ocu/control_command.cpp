// `jausctl control ADDR --authority N`: request control, hold it until
// SIGINT/SIGTERM or --for, release it; report the component's state while
// held, and a loss when it happens. With --send, repeat a command while the
// component is Ready; when it is not, stop for good (or pause, with
// --resume-when-ready): a Clear Emergency or Resume by someone else must not
// restart the motion by itself.
#include "jaus/messages/catalogue.hpp"
#include "jaus/ocu/control_hold.hpp"
#include "jaus/ocu/names.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

namespace {
// How long to wait for Report Component Control after a Reject (it only adds detail).
constexpr jaus::rt::Duration kWhoHasControlTimeout = std::chrono::milliseconds(500);

}  // namespace

std::string control_request_text(const ControlHold::RequestResult& r, const jaus::Address& target,
                                 std::uint8_t authority, const jaus::Address& self) {
  const std::string what = "control of " + target.to_string();
  if (r.error) return r.error->message();
  switch (r.outcome) {
    case ControlHold::Outcome::granted:
      return what + " granted to " + self.to_string() + " (authority " + std::to_string(authority) + ")";
    case ControlHold::Outcome::rejected: return what + " refused (Reject Component Control)";
    case ControlHold::Outcome::refused:
      return what + " refused: " + control_response_text(r.response_code) + " (response " +
             std::to_string(r.response_code) + ")";
    case ControlHold::Outcome::no_reply:
    case ControlHold::Outcome::interrupted: break;
  }
  return what + ": no answer";
}

namespace {

// "; taken over by 254.2.40.1 (authority 9)", "; it has no controller now", or nothing.
std::string controller_text(const std::optional<jaus::msg::ReportComponentControl>& report) {
  if (!report) return "";
  if (!report->controller.is_valid()) return "; it has no controller now";
  return "; taken over by " + report->controller.to_string() + " (authority " + std::to_string(report->authority) + ")";
}

// "Set Wrench Effort", or the code of a message the catalogue does not name.
std::string message_text(const PreparedMessage& message) {
  const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, message.header.command_code);
  return info ? std::string(info->name) : code_text(message.header.command_code);
}
}  // namespace

int run_control(OcuSession& session, const ControlOptions& options, CommandIo io) {
  const std::string target = options.target.to_string();
  ControlHold control(session, options.target, options.authority, options.status_silence);
  const auto requested = control.request(options.timeout);
  const std::string requested_text = control_request_text(requested, options.target, options.authority, session.self());
  if (requested.outcome != ControlHold::Outcome::granted) {
    io.err << "jausctl control: " << requested_text << "\n";
    return kExitFailure;
  }
  io.out << requested_text << "\n" << std::flush;
  const std::string sent = options.send ? message_text(*options.send) : "";
  bool started = false;  // sending began (the component was Ready)
  if (options.send) {
    const auto period = std::chrono::duration_cast<jaus::rt::Duration>(
        std::chrono::duration<double>(1.0 / options.send_rate_hz));
    const auto when_not_ready = options.resume_when_ready ? ControlHold::WhenNotReady::pause
                                                          : ControlHold::WhenNotReady::end_hold;
    control.send_while_held(*options.send, period, when_not_ready, [&](bool sending) {
      started = started || sending;
      if (!options.resume_when_ready) return;
      if (sending)
        io.out << target << ": Ready: sending " << sent << "\n" << std::flush;
      else
        io.out << target << ": not Ready: paused " << sent << " until it is Ready again (--resume-when-ready)\n"
               << std::flush;
    });
  }

  const auto start = session.clock().now();
  const auto end = control.hold(options.hold_for, [&](const std::string& state) {
    io.out << target << ": state " << state << "\n" << std::flush;
  });
  const auto held = elapsed_text(session.clock().now() - start);
  if (end == ControlHold::End::rejected && control.control_elsewhere()) {
    io.err << "jausctl control: control of " << target << " lost after " << held
           << ": the component dropped it (its Reject Component Control never arrived)"
           << controller_text(control.control_elsewhere()) << "\n";
    return kExitFailure;
  }
  if (end == ControlHold::End::rejected) {
    const auto controller = control.who_has_control(std::min(options.timeout, kWhoHasControlTimeout));
    io.err << "jausctl control: control of " << target << " lost after " << held
           << ": Reject Component Control received" << controller_text(controller) << "\n";
    return kExitFailure;
  }
  if (end == ControlHold::End::silent) {
    control.release();  // in case only the reports are lost: it must not think we still hold it
    io.err << "jausctl control: control of " << target << " lost after " << held
           << ": no Report Component Status from it for " << seconds_text(options.status_silence)
           << " (stopped, or unreachable)\n";
    return kExitFailure;
  }
  if (end == ControlHold::End::not_ready) {
    control.release();
    const auto& stop = control.stop_seen();
    const std::string state = stop                ? primary_status_text(stop->state)
                              : control.state() ? primary_status_text(*control.state())
                                                : "?";
    if (started && stop && stop->between_reports)
      io.err << "jausctl control: " << target << " stopped and went back to Ready between two status reports (stop counter "
             << stop->stops_before << " -> " << stop->stops_after << "): stopped sending " << sent
             << "; not resuming (see --resume-when-ready)\n";
    else if (started)
      io.err << "jausctl control: " << target << " entered " << state << ": stopped sending " << sent
             << "; not resuming (see --resume-when-ready)\n";
    else
      io.err << "jausctl control: " << target << " is in " << state << ", not Ready: sent no " << sent
             << "; not starting (see --resume-when-ready)\n";
    return kExitLeftReady;
  }
  if (end == ControlHold::End::unwatched) {
    control.release();
    io.err << "jausctl control: " << target
           << " refused its Report Component Status service connection: its state is unknown, so no " << sent
           << " was sent\n";
    return kExitFailure;
  }
  const auto released = control.release();
  if (released.outcome != Arrival::acknowledged)
    io.err << "jausctl control: Release Component Control to " << target << " not acknowledged ("
           << released.transmissions << " transmissions): it drops the control itself after its controller timeout\n";
  io.out << "control of " << target << " released after " << held << " (" << control.liveness_checks()
         << " liveness checks answered";
  if (options.send) io.out << ", " << control.sent_while_held() << " commands sent";
  io.out << ")\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
