// The commands that stop what they reach, in RA 3.x and SAE JAUS alike (the
// codes are the same): Shutdown, Standby, Set Emergency. One list for every
// rule that treats a stop apart: a receiver obeys each copy (the duplicate
// filter), a stop from an unverified endpoint always acts (the transport), a
// wildcard stop is also broadcast (the OCU), a stop never waits behind other
// traffic (the send budget).
#pragma once

#include <cstdint>

namespace jaus {

inline constexpr std::uint16_t kShutdownCode = 0x0002;
inline constexpr std::uint16_t kStandbyCode = 0x0003;
inline constexpr std::uint16_t kSetEmergencyCode = 0x0006;

constexpr bool is_stop_command(std::uint16_t code) {
  return code == kShutdownCode || code == kStandbyCode || code == kSetEmergencyCode;
}

}  // namespace jaus
