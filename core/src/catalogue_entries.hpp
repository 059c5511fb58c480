// Catalogue entries generated from a list of described messages. Included only
// by the catalogue_*.cpp files, one per subgroup, so they compile in parallel.
#pragma once

#include <nlohmann/json.hpp>

#include "jaus/messages/all.hpp"
#include "jaus/messages/catalogue.hpp"

namespace jaus::msg::detail {

using Json = nlohmann::ordered_json;

template <class M>
Expected<Json, Error> payload_to_json(std::span<const std::uint8_t> payload, wire::Dialect dialect) {
  M message{};
  if (auto error = wire::decode_payload_into(payload, message, dialect, kHeaderSize))
    return unexpected(std::move(*error));
  return wire::fields_to_json<Json>(message);
}

template <class M>
Expected<Bytes, Error> payload_from_json(const Json& fields, wire::Dialect dialect) {
  M message{};
  std::string why;
  if (!wire::fields_from_json<Json>(fields, message, why)) return unexpected(Error{ErrorCode::json, 0, {}, why});
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

template <class... Ms>
std::vector<MessageInfo> entries_of(TypeList<Ms...>) {
  return {MessageInfo{Ms::code, Ms::name, &payload_to_json<Ms>, &payload_from_json<Ms>,
                      [] { return wire::fields_doc<Ms>(); }}...};
}

std::vector<MessageInfo> core_entries();
std::vector<MessageInfo> communications_entries();
std::vector<MessageInfo> platform_entries();
std::vector<MessageInfo> manipulator_entries();
std::vector<MessageInfo> environment_entries();
std::vector<MessageInfo> discovery_and_event_entries();

}  // namespace jaus::msg::detail
