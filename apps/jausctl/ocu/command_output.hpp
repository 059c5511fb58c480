// What jausctl's OCU commands of both dialects say the same way: a failure
// line, how many times a command went out, why one did not arrive, and how
// long an emergency clear is given to settle. Private to apps/jausctl/ocu.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

#include "exit_codes.hpp"
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

}  // namespace jausctl::ocu
