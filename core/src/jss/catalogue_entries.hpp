// Catalogue entries generated from lists of described JSS messages. Included
// only by the catalogue_*.cpp files of core/src/jss, one per family, so they
// compile in parallel; each also defines its bodies' codecs (compiled_codecs.hpp).
#pragma once

#include <array>

#include <nlohmann/json.hpp>

#include "jaus/jss/all.hpp"
#include "jaus/jss/catalogue.hpp"
#include "jaus/messages/compiled_json_codecs.hpp"

namespace jaus {
JAUS_JSS_ALL_BODIES(JAUS_DECLARE_JSON_CODEC)
}  // namespace jaus

namespace jaus::jss::detail {

using Json = nlohmann::ordered_json;

template <class Body>
Expected<Json> body_to_json(std::span<const std::uint8_t> body) {
  Body message{};
  if (auto decoded = wire::decode_payload_into(body, message, wire::Dialect::jss, kMessageIdSize); !decoded)
    return unexpected(decoded.error());
  return wire::fields_to_json<Json>(message, wire::Dialect::jss);
}

template <class Body>
Expected<Bytes> body_from_json(const Json& fields) {
  Body message{};
  if (auto filled = wire::fields_from_json<Json>(fields, message, wire::Dialect::jss); !filled)
    return unexpected(filled.error());
  Bytes out(4096);
  for (;;) {
    auto size = wire::encode_payload(message, out, wire::Dialect::jss);
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

// The service and summary are added by catalogue.cpp from its table.
template <class M>
MessageInfo entry_of() {
  using Body = typename M::body_type;
  MessageInfo info;
  info.id = M::code;
  info.name = M::name;
  info.type_name = TypeName<M>::view();
  info.body_to_json = &body_to_json<Body>;
  info.body_from_json = &body_from_json<Body>;
  info.fields_doc = [] { return wire::fields_doc<Body>(wire::Dialect::jss); };
  return info;
}

template <class... Ms>
void append_entries(std::vector<MessageInfo>& out, msg::TypeList<Ms...>) {
  (out.push_back(entry_of<Ms>()), ...);
}

std::vector<MessageInfo> core_entries();      // access control, management, time, liveness, events, discovery
std::vector<MessageInfo> mobility_entries();  // drivers, sensors, waypoints, list manager

}  // namespace jaus::jss::detail
