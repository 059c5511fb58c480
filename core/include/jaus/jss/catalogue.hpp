// JSS's side of the message catalogue (jaus/messages/catalogue.hpp holds both
// sets): contents, AS5669A headers and whole datagrams as JSON, service names
// and docs/jss-messages.md. Used by tools (jausctl --dialect jss, the
// Wireshark generator) and tests, not on the hot path.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/base/expected.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/messages/catalogue.hpp"

namespace jaus::jss {

using Bytes = std::vector<std::uint8_t>;

// The JSS messages' entries (name, class, service, summary, JSON form) are
// the catalogue's JSS set: msg::catalogue(wire::Dialect::jss),
// msg::find_message(wire::Dialect::jss, id or name).

// The short service name of a URI: "urn:jaus:jss:core:Discovery" -> "Discovery".
std::string_view service_name(std::string_view service_uri);

// Contents (u16 ID + body) as {"id": "0x2B00", "name": ..., "fields": {...}},
// and back from {"id" or "name", "fields"}.
Expected<nlohmann::ordered_json> contents_to_json(std::span<const std::uint8_t> contents);
Expected<Bytes> contents_from_json(const nlohmann::ordered_json& message);

// The AS5669A header as JSON, and back (keys it does not get keep their defaults).
nlohmann::ordered_json header_to_json(const JudpHeader& header);
Expected<JudpHeader> header_from_json(const nlohmann::ordered_json& header);

// A whole datagram: {"packets": [{"header": {...}, "message": {...}}, ...]};
// an ACK or a packet of a large message has "contents" (hex) instead of
// "message" when its contents are not a whole message.
Expected<nlohmann::ordered_json> datagram_to_json(std::span<const std::uint8_t> datagram);
// One datagram from {"header": {...}, "message": {...}} (one transport message).
Expected<Bytes> datagram_from_json(const nlohmann::ordered_json& packet);

// docs/jss-messages.md, generated from the descriptions.
std::string messages_markdown();

}  // namespace jaus::jss
