// `jausctl control ADDR --authority N`: request control, hold it until
// SIGINT/SIGTERM or --for, release it; report the component's state while
// held, and a loss when it happens.
#include "control_hold.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

namespace {
// How long to wait for Report Component Control after a Reject (it only adds detail).
constexpr jaus::rt::Duration kWhoHasControlTimeout = std::chrono::milliseconds(500);
}  // namespace

int run_control(OcuSession& session, const ControlOptions& options, CommandIo io) {
  const std::string target = options.target.to_string();
  ControlHold control(session, options.target, options.authority, options.status_silence);
  const auto requested = control.request(options.timeout);
  if (requested.outcome != ControlHold::Outcome::granted) {
    io.err << "jausctl control: " << requested.text << "\n";
    return kExitFailure;
  }
  io.out << requested.text << "\n" << std::flush;

  const auto start = session.clock().now();
  const auto end = control.hold(options.hold_for, [&](const std::string& state) {
    io.out << target << ": state " << state << "\n" << std::flush;
  });
  const auto held = elapsed_text(session.clock().now() - start);
  if (end == ControlHold::End::rejected) {
    const std::string why = control.who_has_control(std::min(options.timeout, kWhoHasControlTimeout));
    io.err << "jausctl control: control of " << target << " lost after " << held
           << ": Reject Component Control received" << (why.empty() ? "" : "; " + why) << "\n";
    return kExitFailure;
  }
  if (end == ControlHold::End::silent) {
    control.release();  // in case only the reports are lost: it must not think we still hold it
    io.err << "jausctl control: control of " << target << " lost after " << held
           << ": no Report Component Status from it for " << seconds_text(options.status_silence)
           << " (stopped, or unreachable)\n";
    return kExitFailure;
  }
  control.release();
  io.out << "control of " << target << " released after " << held << " (" << control.liveness_checks()
         << " liveness checks answered)\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
