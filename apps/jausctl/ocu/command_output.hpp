// What jausctl's OCU commands of both dialects say the same way: a failure
// line, how many times a command went out, why one did not arrive, and how
// an emergency command's result is confirmed from the status. Private to
// apps/jausctl/ocu.
#pragma once

#include <algorithm>
#include <chrono>
#include <string>
#include <string_view>

#include "exit_codes.hpp"
#include "jaus/messages/primary_status.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/ocu/names.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

// "jausctl <command>: <why>" on err; the exit code to return.
inline int fail(CommandIo io, std::string_view command, const std::string& why) {
  io.err << "jausctl " << command << ": " << why << "\n";
  return kExitFailure;
}
inline int fail(CommandIo io, std::string_view command, const jaus::Error& why) {
  return fail(io, command, why.message());
}

// "10 transmissions in 0.5 s"
inline std::string transmissions_text(const jaus::ocu::ArrivalResult& result) {
  return std::to_string(result.transmissions) + (result.transmissions == 1 ? " transmission" : " transmissions") +
         " in " + jaus::ocu::seconds_text(result.elapsed);
}

// Why a command that must arrive did not, in one line: "Set Emergency to
// 1.1.33.1 not acknowledged (10 transmissions in 0.5 s)". `target` in either
// dialect; `nak_means`: what a NAK from its node says.
template <class Id>
std::string not_arrived_text(const std::string& what, const Id& target, const jaus::ocu::ArrivalResult& result,
                             std::string_view nak_means) {
  const std::string to = what + " to " + target.to_string();
  switch (result.outcome) {
    case jaus::ocu::Arrival::refused: return to + " " + std::string(nak_means);
    case jaus::ocu::Arrival::interrupted: return to + ": interrupted before it was acknowledged";
    case jaus::ocu::Arrival::acknowledged:
    case jaus::ocu::Arrival::unacknowledged: break;
  }
  return to + " not acknowledged (" + transmissions_text(result) + ")";
}

// After Clear Emergency: how long the component may take to leave Emergency, asked this often.
inline constexpr jaus::rt::Duration kClearSettles = std::chrono::seconds(1);
inline constexpr jaus::rt::Duration kClearPoll = std::chrono::milliseconds(100);

// A status report's primary status (either dialect's: the low nibble) is Emergency.
inline bool is_emergency_state(unsigned primary_status) {
  return (primary_status & 0x0F) == static_cast<unsigned>(jaus::msg::PrimaryStatus::emergency);
}

// Why an emergency command did not arrive; a Set Emergency that did not
// says the vehicle may not have stopped.
template <class Id>
std::string emergency_not_arrived_text(bool set, const std::string& what, const Id& target,
                                       const jaus::ocu::ArrivalResult& result, std::string_view nak_means) {
  std::string why = not_arrived_text(what, target, result, nak_means);
  if (set && result.outcome != jaus::ocu::Arrival::interrupted)
    why += ": it may NOT have stopped; stop it another way (its own stop button, the radio's)";
  return why;
}

// The end of `jausctl emergency` in either dialect, once the command was
// acknowledged (so acted on) or only the status can tell: the component's
// status shows the state it left. `query_status()` asks for it (an Expected
// report), `primary_status(report)` reads its state. A clear may need a
// moment: a vehicle whose platform must first report its emergency flag clear
// stays in Emergency until it does (docs/safety.md).
template <class Session, class Id, class QueryStatus, class PrimaryStatus>
int confirm_emergency_state(Session& session, const Id& target, bool set, const std::string& what, CommandIo io,
                            jaus::rt::Duration timeout, QueryStatus query_status, PrimaryStatus primary_status) {
  const auto in_emergency = [&](const auto& report) { return is_emergency_state(primary_status(report)); };
  const auto state_text = [&](const auto& report) { return jaus::ocu::primary_status_text(primary_status(report)); };
  auto report = query_status();
  if (!report)
    return fail(io, "emergency", what + " acknowledged, but " + report.error().message() + " to show its state");
  if (set && !in_emergency(*report))
    return fail(io, "emergency", target.to_string() + " is in " + state_text(*report) + " after Set Emergency");
  const auto settle_until = session.clock().now() + std::min<jaus::rt::Duration>(timeout, kClearSettles);
  while (!set && in_emergency(*report) && session.clock().now() < settle_until) {
    session.run_for(kClearPoll);
    auto again = query_status();
    if (!again) break;
    report = std::move(again);
  }
  if (!set && in_emergency(*report))
    return fail(io, "emergency", target.to_string() + " is still in Emergency: another sender holds it, " +
                                     "the platform's own stop does, or " + session.self().to_string() + " never set it");
  // Who set or cleared it: the holder's ID is what clears the hold later (--as).
  io.out << target.to_string() << ": emergency " << (set ? "set" : "cleared") << " by " << session.self().to_string()
         << " (state " << state_text(*report) << ")\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
