// Typed messages <-> payload bytes <-> frames. Sans-I/O: bytes in, typed
// messages or an Error out; nothing here throws.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/messages.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath {

// A decoded frame: its header and what it says.
struct Envelope {
  FrameHeader header;
  AnyMessage message;
};

// Who sent the bytes. A frame with a command or request type is an ACK when
// it comes from the platform (an OK ACK of a request is byte-identical to
// the request sent with subscription 0, so the direction decides).
enum class Direction { to_platform, from_platform };

Expected<std::vector<std::uint8_t>> encode_payload(const AnyMessage& message);
Expected<AnyMessage> decode_payload(std::uint16_t type, std::span<const std::uint8_t> payload, Direction direction);

// Frame for a message. The header's type is taken from the message, except
// for an Ack, which uses header.type (the acknowledged type).
Expected<std::vector<std::uint8_t>> encode(const Envelope& envelope);
Expected<std::size_t> append_encoded(std::vector<std::uint8_t>& out, const Envelope& envelope);
Expected<Envelope> decode(const Frame& frame, Direction direction);

// Succeeds, or fails with the first field outside the range the document
// gives it (out_of_range). Decoding never checks ranges; a platform does before acting.
Expected<void> check_ranges(const AnyMessage& message);

}  // namespace jaus::clearpath
