// Catalogue entries generated from lists of described messages, for both
// message sets. Included only by the catalogue_*.cpp files (one per RA
// subgroup, platform in two, and one per JSS service family, in jss/), so they
// compile in parallel; each also defines its bodies' codecs.
#pragma once

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "jaus/messages/catalogue.hpp"
#include "jaus/messages/compiled_json_codecs.hpp"

namespace jaus::msg::detail {

using Json = nlohmann::ordered_json;

// Where a body starts in its message, for error offsets: after RA's 16-byte
// header, after JSS's 2-byte message ID.
constexpr std::size_t body_offset(wire::Dialect set) { return set == wire::Dialect::jss ? 2 : kHeaderSize; }

// A message's code from its JSON form, for both sets: `key` ("code" in RA,
// "id" in JSS) as a number or hex text ("0x4402"), else its `name` in
// `set`'s catalogue. Errors are ErrorCode::json naming the field.
Expected<std::uint16_t, Error> message_code_from_json(const Json& message, std::string_view key, wire::Dialect set);

// The dialect a body of `Set` is read and written in when `asked` is asked:
// a JSS body always in JSS's, an RA body in openjaus where asked, else RA's.
constexpr wire::Dialect dialect_for(wire::Dialect set, wire::Dialect asked) {
  if (set == wire::Dialect::jss) return wire::Dialect::jss;
  return asked == wire::Dialect::openjaus ? wire::Dialect::openjaus : wire::Dialect::ra;
}

// A body's JSON form is its set's (RA's shows the fields openjaus alone sends).
template <class Body, wire::Dialect Set>
Expected<Json, Error> body_to_json(std::span<const std::uint8_t> body, wire::Dialect asked) {
  Body message{};
  if (auto decoded = wire::decode_payload_into(body, message, dialect_for(Set, asked), body_offset(Set)); !decoded)
    return unexpected(decoded.error());
  return wire::fields_to_json<Json>(message, Set);
}

template <class Body, wire::Dialect Set>
Expected<Bytes, Error> body_from_json(const Json& fields, wire::Dialect asked) {
  Body message{};
  if (auto filled = wire::fields_from_json<Json>(fields, message, Set); !filled) return unexpected(filled.error());
  // Large enough for most bodies; Report Image may be larger.
  Bytes out(4096);
  for (;;) {
    auto size = wire::encode_payload(message, out, dialect_for(Set, asked));
    if (size) {
      out.resize(*size);
      return out;
    }
    if (size.error().code != ErrorCode::output_too_small || out.size() >= (16u << 20)) return unexpected(size.error());
    out.resize(out.size() * 4);
  }
}

// "Query Identification" -> "QueryIdentification", at compile time.
template <class M>
struct TypeName {
  static constexpr auto text = [] {
    std::array<char, M::name.size() + 1> out{};
    std::size_t n = 0;
    for (const char c : M::name)
      if (c != ' ') out[n++] = c;
    return out;
  }();
  static constexpr std::string_view view() { return std::string_view(text.data()); }
};

// The functions are instantiated for the message's body: Message<Code, Name,
// Body> adds only the code and the name, so messages sharing a body (Set X
// and Report X, the empty queries) share one instantiation. A JSS entry's
// service and summary are added by jss/catalogue.cpp from its table.
template <wire::Dialect Set, class M>
MessageInfo entry_of() {
  using Body = typename M::body_type;
  MessageInfo info;
  info.set = Set;
  info.code = M::code;
  info.name = M::name;
  info.type_name = TypeName<M>::view();
  info.message_class = message_class_of(Set, M::code);
  info.body_to_json = &body_to_json<Body, Set>;
  info.body_from_json = &body_from_json<Body, Set>;
  info.fields_doc = [] { return wire::fields_doc<Body>(Set); };
  return info;
}

template <wire::Dialect Set, class... Ms>
std::vector<MessageInfo> entries_of(TypeList<Ms...>) {
  return {entry_of<Set, Ms>()...};
}

// The messages of the list whose code satisfies Keep (the others are not
// instantiated): a subgroup split over files.
template <wire::Dialect Set, bool (*Keep)(std::uint16_t), class... Ms>
std::vector<MessageInfo> entries_of(TypeList<Ms...>) {
  std::vector<MessageInfo> entries;
  ([&] {
    if constexpr (Keep(Ms::code)) entries.push_back(entry_of<Set, Ms>());
  }(), ...);
  return entries;
}

// Platform, the largest RA subgroup, in two files of about equal compile cost,
// split by topic so that a Set X and its Report X (one body) stay together.
// Specifications, operational data, pose, velocity state, wrench effort,
// discrete devices, global and local vector: 0x_400 to 0x_408.
constexpr bool is_platform_state(std::uint16_t code) { return (code & 0xFF) <= 0x08; }
// Travel speed, waypoints and path segments: 0x_40A to 0x_410.
constexpr bool is_platform_waypoint(std::uint16_t code) { return !is_platform_state(code); }

// "0x4402".
std::string code_text(std::uint16_t code);

// The RA set, by subgroup.
std::vector<MessageInfo> core_entries();
std::vector<MessageInfo> communications_entries();
std::vector<MessageInfo> platform_state_entries();
std::vector<MessageInfo> platform_waypoint_entries();
std::vector<MessageInfo> manipulator_entries();
std::vector<MessageInfo> environment_entries();
std::vector<MessageInfo> discovery_and_event_entries();
// The JSS set: access control, management, time, liveness, events and
// discovery; drivers, sensors, waypoints and the list manager
// (jss/catalogue_*.cpp). Its services and summaries: jss/message_notes.hpp.
std::vector<MessageInfo> jss_core_entries();
std::vector<MessageInfo> jss_mobility_entries();
// The whole JSS set, with its services and summaries (jss/catalogue.cpp).
std::vector<MessageInfo> jss_set();

}  // namespace jaus::msg::detail
