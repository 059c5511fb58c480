// JSS message contents: the u16 message ID (little-endian), then the body
// (docs/jss.md, "The bytes on the wire"). What AS5669A carries in a transport message, what
// Create Event embeds and Event wraps.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::jss {

inline constexpr std::size_t kMessageIdSize = 2;

// The contents of `message`, or why its values do not fit their fields (a
// string over 255 characters, a list over its count, an embedded message
// without its ID).
template <class M>
Expected<std::vector<std::uint8_t>> try_encode_contents(const M& message) {
  std::size_t capacity = 64;
  if constexpr (wire::has_fixed_layout<typename M::body_type>())
    capacity = kMessageIdSize + 4 + wire::kMaxFixedLayoutSize<typename M::body_type>;
  std::vector<std::uint8_t> out;
  for (;;) {
    out.resize(capacity);
    out[0] = static_cast<std::uint8_t>(M::code & 0xFF);
    out[1] = static_cast<std::uint8_t>(M::code >> 8);
    auto size = wire::encode_payload<typename M::body_type>(message, std::span(out).subspan(kMessageIdSize),
                                                            wire::Dialect::jss);
    if (size) {
      out.resize(kMessageIdSize + *size);
      return out;
    }
    // One transport message carries at most 65521 bytes of contents; a large
    // message may carry more, but nothing we describe needs 16 MiB.
    if (size.error().code != ErrorCode::output_too_small || capacity >= (16u << 20)) {
      Error e = size.error();
      e.offset += kMessageIdSize;
      return unexpected(std::move(e));
    }
    capacity *= 4;
  }
}

// The contents of `message`; empty when try_encode_contents fails (a value
// the caller put out of its field's range: never sent).
template <class M>
std::vector<std::uint8_t> encode_contents(const M& message) {
  auto contents = try_encode_contents(message);
  return contents ? std::move(*contents) : std::vector<std::uint8_t>{};
}

// Decodes a body (the contents after the message ID) as M's. Error offsets
// count from the start of the contents.
template <class M>
Expected<M> decode_body(std::span<const std::uint8_t> body) {
  M out{};
  if (auto decoded = wire::decode_payload_into<typename M::body_type>(body, out, wire::Dialect::jss, kMessageIdSize);
      !decoded)
    return unexpected(decoded.error());
  return out;
}

// Decodes contents that must be an M: checks the message ID, then the body.
template <class M>
Expected<M> decode_contents(std::span<const std::uint8_t> contents) {
  if (contents.size() < kMessageIdSize)
    return unexpected(Error{ErrorCode::truncated, 0, "message_id",
                            "needs 2 bytes, " + std::to_string(contents.size()) + " left"});
  if (const auto id = message_id_of(contents); id != M::code) {
    char text[64];
    std::snprintf(text, sizeof text, "0x%04X, expected 0x%04X (", static_cast<unsigned>(id),
                  static_cast<unsigned>(M::code));
    return unexpected(Error{ErrorCode::unknown_message, 0, "message_id", text + std::string(M::name) + ")"});
  }
  return decode_body<M>(contents.subspan(kMessageIdSize));
}

}  // namespace jaus::jss
