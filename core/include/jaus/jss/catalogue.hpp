// The JSS message catalogue: every JSS message in scope by ID, with its name,
// service, class and JSON form, built from the descriptions (all.hpp). Used by
// tools (jausctl --dialect jss, the Wireshark generator, docs/jss-messages.md)
// and tests, not on the hot path.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/base/expected.hpp"
#include "jaus/jss/judp.hpp"

namespace jaus::jss {

using Bytes = std::vector<std::uint8_t>;

// From the ID's top nibble: 0x0 command, 0x2 query, 0x4 inform.
enum class MessageClass : std::uint8_t { command, query, inform };
std::string_view to_string(MessageClass message_class);

struct MessageInfo {
  std::uint16_t id = 0;
  std::string_view name;         // "Query Identification"
  std::string_view type_name;    // "QueryIdentification" (jss::msg::QueryIdentification)
  std::string_view service_uri;  // "urn:jaus:jss:core:Discovery": the service that defines it
  MessageClass message_class = MessageClass::command;
  std::string_view summary;      // one sentence: what it asks, says or does
  // Body (the contents after the ID) to the JSON object of its fields, and back.
  Expected<nlohmann::ordered_json> (*body_to_json)(std::span<const std::uint8_t> body) = nullptr;
  Expected<Bytes> (*body_from_json)(const nlohmann::ordered_json& fields) = nullptr;
  std::string (*fields_doc)() = nullptr;  // the fields as described, for docs
};

// Every message, sorted by ID.
std::span<const MessageInfo> catalogue();
const MessageInfo* find_message(std::uint16_t id);
// By name ("Query Identification") or type name ("QueryIdentification").
const MessageInfo* find_message(std::string_view name);
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
