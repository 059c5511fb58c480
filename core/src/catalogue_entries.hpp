// Catalogue entries generated from a list of described messages. Included only
// by the catalogue_*.cpp files, one per subgroup (platform in two), so they
// compile in parallel.
#pragma once

#include <nlohmann/json.hpp>

#include "jaus/messages/compiled_json_codecs.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/messages/catalogue.hpp"

namespace jaus::msg::detail {

using Json = nlohmann::ordered_json;

template <class M>
Expected<Json, Error> payload_to_json(std::span<const std::uint8_t> payload, wire::Dialect dialect) {
  M message{};
  if (auto decoded = wire::decode_payload_into(payload, message, dialect, kHeaderSize); !decoded)
    return unexpected(decoded.error());
  return wire::fields_to_json<Json>(message);
}

template <class M>
Expected<Bytes, Error> payload_from_json(const Json& fields, wire::Dialect dialect) {
  M message{};
  if (auto filled = wire::fields_from_json<Json>(fields, message); !filled) return unexpected(filled.error());
  // Large enough for any single-packet payload; Report Image may be larger.
  Bytes out(64 * 1024);
  for (;;) {
    auto size = wire::encode_payload(message, out, dialect);
    if (size) {
      out.resize(*size);
      return out;
    }
    if (size.error().code != ErrorCode::output_too_small || out.size() >= (16u << 20)) return unexpected(size.error());
    out.resize(out.size() * 4);
  }
}

// The functions are instantiated for the message's body: Message<Code, Name,
// Body> adds only the code and the name, so messages sharing a body (Set X
// and Report X, the empty queries) share one instantiation.
template <class M>
MessageInfo entry_of() {
  using Body = typename M::body_type;
  return MessageInfo{M::code, M::name, &payload_to_json<Body>, &payload_from_json<Body>,
                     [] { return wire::fields_doc<Body>(); }};
}

template <class... Ms>
std::vector<MessageInfo> entries_of(TypeList<Ms...>) {
  return {entry_of<Ms>()...};
}

// The messages of the list whose code satisfies Keep (the others are not
// instantiated): a subgroup split over files.
template <bool (*Keep)(std::uint16_t), class... Ms>
std::vector<MessageInfo> entries_of(TypeList<Ms...>) {
  std::vector<MessageInfo> entries;
  ([&] {
    if constexpr (Keep(Ms::code)) entries.push_back(entry_of<Ms>());
  }(), ...);
  return entries;
}

// Platform, the largest subgroup, in two files of about equal compile cost,
// split by topic so that a Set X and its Report X (one body) stay together.
// Specifications, operational data, pose, velocity state, wrench effort,
// discrete devices, global and local vector: 0x_400 to 0x_408.
constexpr bool is_platform_state(std::uint16_t code) { return (code & 0xFF) <= 0x08; }
// Travel speed, waypoints and path segments: 0x_40A to 0x_410.
constexpr bool is_platform_waypoint(std::uint16_t code) { return !is_platform_state(code); }

std::vector<MessageInfo> core_entries();
std::vector<MessageInfo> communications_entries();
std::vector<MessageInfo> platform_state_entries();
std::vector<MessageInfo> platform_waypoint_entries();
std::vector<MessageInfo> manipulator_entries();
std::vector<MessageInfo> environment_entries();
std::vector<MessageInfo> discovery_and_event_entries();

}  // namespace jaus::msg::detail
