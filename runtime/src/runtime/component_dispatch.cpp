// A component's receive path: every message is counted, handed to its
// handler or refused (not the controller, sender's standing, not Ready,
// malformed), each refusal counted and logged through the repeat limiter.
#include "jaus/runtime/component.hpp"

namespace jaus::rt {

void Component::receive(const Header& header, std::span<const std::uint8_t> payload, wire::Dialect dialect,
                        SenderStanding standing) {
  // Handlers read it through sender_standing(); kept for this message only
  // (a message sent meanwhile is queued by the node, never handled inside this call).
  const SenderStanding outer = standing_;
  standing_ = standing;
  dispatch(header, payload, dialect);
  standing_ = outer;
}

void Component::dispatch(const Header& header, std::span<const std::uint8_t> payload, wire::Dialect dialect) {
  ++counters_.received;
  if (lifecycle_.state() == PrimaryStatus::shutdown) return;  // a shut-down component answers nothing

  // Any traffic from the controller proves it is alive.
  if (control_.is_controller(header.source)) controller_last_heard_ = env_.clock.now();

  // Reports on our own service connections go to their subscribers.
  if (subscriptions_.on_report(header, payload)) return;

  const auto it = handlers_.find(header.command_code);
  if (it == handlers_.end()) {
    if (unhandled(header, payload)) return;
    ++counters_.unsupported;
    // A broadcast reaches every component, most of which have no use for it
    // (the node manager's own heartbeat, each second): counted, not a line.
    if (header.destination.is_broadcast()) return;
    log_repeated("unsupported messages ignored", LogLevel::debug, [&] {
      return "ignored unsupported message 0x" + wire::detail::hex_u32(header.command_code) + " from " +
             header.source.to_string();
    });
    return;
  }
  const Handler& handler = it->second;
  if (handler.access == Access::controller && !control_.is_controller(header.source)) {
    refuse_not_controller(header, handler.name);
    return;
  }
  // A controller that is no longer trusted (moved outside control_from, or
  // its route lost to a full table) commands nothing.
  if (handler.access == Access::controller && standing_ != SenderStanding::trusted) {
    refuse_for_standing(header, handler.name);
    return;
  }
  if (handler.ready_only && lifecycle_.state() != PrimaryStatus::ready) {
    ++counters_.refused_wrong_state;
    log_repeated("commands not executed outside Ready", LogLevel::warn, [&] {
      return std::string(handler.name) + " from " + header.source.to_string() + " not executed in " +
             std::string(to_string(lifecycle_.state()));
    });
    return;
  }
  if (auto handled = handler.invoke(header, payload, dialect); !handled) {
    ++counters_.decode_errors;
    log_repeated("malformed messages ignored", LogLevel::warn, [&] {
      return "malformed " + std::string(handler.name) + " from " + header.source.to_string() + ": " +
             handled.error().message();
    });
    return;
  }
  // Only a command that decoded (and, checked above, came from the
  // controller) feeds the deadman of its service connection.
  if (handler.access == Access::controller && handler.ready_only) services_.on_command(header);
}

void Component::refuse_not_controller(const Header& header, std::string_view what) {
  ++counters_.refused_not_controller;
  log_repeated("commands from a non-controller not executed", LogLevel::warn, [&] {
    const auto& controller = control_.controller();
    return std::string(what) + " from " + header.source.to_string() +
           " not executed: " + (controller ? "controlled by " + to_string(*controller) : "not controlled");
  });
}

void Component::refuse_for_standing(const Header& header, std::string_view what) {
  const bool unrecorded = standing_ == SenderStanding::unrecorded;
  ++(unrecorded ? counters_.refused_unrecorded : counters_.refused_observer);
  const auto line = [&] {
    return std::string(what) + " from " + header.source.to_string() + " refused: sender " +
           std::string(to_string(standing_));
  };
  // Per standing, not per sender: a flood of forged sources is one line and a count.
  if (unrecorded)
    log_repeated("requests from unrecorded senders refused", LogLevel::warn, line);
  else
    log_repeated("requests from observers refused", LogLevel::info, line);
}

}  // namespace jaus::rt
