// The stop counter of Report Component Status: bits 20-31 of the secondary
// status count, modulo 4096, the component's entries into a state other than
// Ready (Emergency, Standby, Failure, Shutdown, Initialize after a Reset).
//
// Why: a controller that samples the status (a service connection at 5-20 Hz,
// Query Component Status every 100 ms) misses a stop that came and went
// between two samples: Set Emergency then Clear Emergency from another OCU,
// back to back. Every sample carries the counter, so a controller that saw
// Ready with counter N and then Ready with another counter knows a stop
// happened meanwhile, however brief, and stops for good (the component
// stopped the platform then; a controller that went on commanding would undo
// that stop). Nothing is pushed between samples: an unsolicited Report
// Component Status would be read by a peer that pairs answers with its
// queries as the answer to its next one.
//
// Peers: the RA leaves bits 16-31 to the vendor; a peer that leaves them 0
// (OpenJAUS does) never shows a change, so nothing is lost by reading it. A
// peer whose bits 20-31 change for its own reasons looks like one that
// stopped: the controller stops, the safe side. 4096 stops between two
// samples (a wrap) would hide them: at 10 Hz that takes 40,960 state changes
// a second.
#pragma once

#include <cstdint>

namespace jaus::rt::stop_counter {

inline constexpr unsigned kShift = 20;
inline constexpr std::uint32_t kModulus = 1u << 12;
// Bits 16-19 are the component's own (Component::component_status_bits).
inline constexpr std::uint32_t kComponentBits = 0x000F0000u;

// The counter a secondary status carries.
constexpr std::uint16_t of(std::uint32_t secondary_status) {
  return static_cast<std::uint16_t>(secondary_status >> kShift);
}
// The secondary status bits that carry `stops_entered`.
constexpr std::uint32_t bits(std::uint64_t stops_entered) {
  return static_cast<std::uint32_t>(stops_entered % kModulus) << kShift;
}

}  // namespace jaus::rt::stop_counter
