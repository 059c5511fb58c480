// A message type is a command code, a name and a described body. Messages the
// RA calls "identical to Code X" reuse X's body under their own code.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/wire/describe.hpp"

namespace jaus::wire {

// A string usable as a template argument (the message's name).
template <std::size_t N>
struct FixedName {
  char text[N]{};
  constexpr FixedName(const char (&s)[N]) { std::copy_n(s, N, text); }  // NOLINT: implicit by design
  constexpr std::string_view view() const { return {text, N - 1}; }
};

template <std::uint16_t Code, FixedName Name, class Body>
struct Message : Body {
  static constexpr std::uint16_t code = Code;
  static constexpr std::string_view name = Name.view();
  using body_type = Body;
};

// A body without fields.
struct Empty {
  bool operator==(const Empty&) const = default;
  static constexpr auto describe() { return std::tuple<>{}; }
};

template <class M>
concept MessageType = requires {
  { M::code } -> std::convertible_to<std::uint16_t>;
  { M::name } -> std::convertible_to<std::string_view>;
  M::describe();
};

namespace detail {
// A Message<Code, Name, Body> is encoded as its Body: the codec is compiled
// once per body (in jaus_core, compiled_codecs.hpp), not once per message.
template <class M>
concept IsMessageOfOtherBody = requires { typename M::body_type; } && !std::is_same_v<M, typename M::body_type>;
}  // namespace detail

// Encodes the payload (no header) into `out`; returns the number of bytes.
// The payload may exceed one packet: the node splits it into a large data set.
template <class M>
Expected<std::size_t, Error> encode_payload(const M& message, std::span<std::uint8_t> out,
                                            Dialect dialect = Dialect::ra) {
  if constexpr (detail::IsMessageOfOtherBody<M>) {
    return encode_payload<typename M::body_type>(message, out, dialect);  // one instantiation per body
  } else {
    ByteWriter w(out);
    CodecContext ctx{dialect, {}};
    encode_fields(message, w, ctx);
    if (w.failed()) return unexpected(w.error());
    return w.size();
  }
}

namespace detail {
// A decode that failed, or left bytes over: its error. Out of line and cold,
// so that decode_payload_into's success path stays small enough to inline into
// its caller (with the error built inline it was not: 50 instructions more a
// message, issue 50).
[[gnu::noinline, gnu::cold]] inline Expected<void> decode_failure(ByteReader& r) {
  if (!r.failed()) {
    r.set_field({});
    r.fail(ErrorCode::trailing_bytes, std::to_string(r.remaining()) + " bytes");
  }
  return unexpected(r.error());
}
}  // namespace detail

// Decodes a payload into an existing object (reusing its storage: no heap
// allocation for fixed-size messages). Every byte must be consumed.
template <class M>
Expected<void> decode_payload_into(std::span<const std::uint8_t> payload, M& out, Dialect dialect = Dialect::ra,
                                   std::size_t base_offset = 0) {
  if constexpr (detail::IsMessageOfOtherBody<M>) {
    return decode_payload_into<typename M::body_type>(payload, out, dialect, base_offset);
  } else {
    ByteReader r(payload, base_offset);
    CodecContext ctx{dialect, {}};
    decode_fields(r, out, ctx);
    if (!r.failed() && r.remaining() == 0) [[likely]]
      return {};
    return detail::decode_failure(r);
  }
}

template <class M>
Expected<M, Error> decode_payload(std::span<const std::uint8_t> payload, Dialect dialect = Dialect::ra) {
  M out{};
  if (auto decoded = decode_payload_into(payload, out, dialect); !decoded) return unexpected(decoded.error());
  return out;
}

// Encodes header + payload into `out` (at least 16 + payload bytes). The
// header's command code and data size are set from the message; the payload
// must fit one packet.
template <class M>
Expected<std::size_t, Error> encode_message(Header header, const M& message, std::span<std::uint8_t> out,
                                            Dialect dialect = Dialect::ra) {
  if (out.size() < kHeaderSize) return unexpected(Error{ErrorCode::output_too_small, 0, {}, {}});
  const auto payload_capacity = std::min(out.size() - kHeaderSize, kMaxPayloadSize);
  auto size = encode_payload(message, out.subspan(kHeaderSize, payload_capacity), dialect);
  if (!size) {
    Error e = size.error();
    if (e.code == ErrorCode::output_too_small && out.size() - kHeaderSize >= kMaxPayloadSize) {
      e.code = ErrorCode::payload_too_large;
      e.detail = "more than 4080 bytes in one packet";
    }
    e.offset += kHeaderSize;
    return unexpected(std::move(e));
  }
  header.command_code = M::code;
  header.data_size = static_cast<std::uint16_t>(*size);
  encode_header_unchecked(header, out.template first<kHeaderSize>());
  return kHeaderSize + *size;
}

}  // namespace jaus::wire
