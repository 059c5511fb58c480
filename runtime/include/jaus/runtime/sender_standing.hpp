// What a node knows of a message's sender beyond its JAUS ID, decided where
// the message enters (the transport and the node's liveness table) and
// handed with the message to the component, which decides what the sender
// may do (issue 28, docs/safety.md "Hostile network").
#pragma once

#include <cstdint>
#include <string_view>

namespace jaus::rt {

enum class SenderStanding : std::uint8_t {
  // Remembered by the node (route and liveness recorded) and from a host
  // allowed to command (transport.control_from): may do everything the
  // component's rules allow.
  trusted,
  // Remembered, from a host outside transport.control_from: may query,
  // subscribe to reports and set/clear its own emergency hold; may not take
  // control or change the component otherwise.
  observer,
  // The node could not remember it (its tables are full): nothing it asks
  // may leave state behind that would outlive it. Queries are answered,
  // Set Emergency is obeyed (a hold only the local clear releases).
  unrecorded,
};

// The lesser of two standings (a sender is as trusted as its least trusted part).
constexpr SenderStanding least_of(SenderStanding a, SenderStanding b) {
  return static_cast<std::uint8_t>(a) > static_cast<std::uint8_t>(b) ? a : b;
}

// A standing as a number that grows with doubt (trusted 0), and back: what
// the large-message assembler keeps of each piece, a whole message carrying
// the most of its pieces' (jaus/core/large_message_assembler.hpp).
constexpr std::uint8_t doubt_of(SenderStanding standing) { return static_cast<std::uint8_t>(standing); }
constexpr SenderStanding standing_of_doubt(std::uint8_t doubt) {
  return doubt >= doubt_of(SenderStanding::unrecorded) ? SenderStanding::unrecorded
                                                        : static_cast<SenderStanding>(doubt);
}

constexpr std::string_view to_string(SenderStanding standing) {
  switch (standing) {
    case SenderStanding::trusted: return "trusted";
    case SenderStanding::observer: return "observer (outside transport.control_from)";
    case SenderStanding::unrecorded: return "unrecorded (the node's tables are full)";
  }
  return "?";
}

}  // namespace jaus::rt
