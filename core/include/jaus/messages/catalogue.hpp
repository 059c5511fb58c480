// The message catalogue: every supported message of both message sets, RA 3.x
// and SAE JAUS (JSS), keyed by (dialect, code), with its name, class, JSON
// form and field docs. Built from the one message description (all.hpp and
// jaus/jss/all.hpp); used by tools (jausctl msg, the Wireshark generator, the
// generated docs) and tests, not on the hot path.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::msg {

using Bytes = std::vector<std::uint8_t>;

// A dialect names the message set it speaks: `ra` and `openjaus` the RA 3.x
// set (openjaus reads and writes some of its fields differently), `jss` the
// SAE JAUS set. The set of an entry is `ra` or `jss`.
constexpr wire::Dialect message_set_of(wire::Dialect dialect) {
  return dialect == wire::Dialect::jss ? wire::Dialect::jss : wire::Dialect::ra;
}

// From the code's top nibble. JSS defines command (0x0), query (0x2) and
// inform (0x4) only; RA also the event and node management classes.
enum class MessageClass : std::uint8_t {
  command, query, inform, event_setup, event_notification, node_management, experimental
};
std::string_view to_string(MessageClass message_class);
MessageClass message_class_of(wire::Dialect set, std::uint16_t code);

struct MessageInfo {
  wire::Dialect set = wire::Dialect::ra;  // ra (RA 3.x) or jss (SAE JAUS)
  std::uint16_t code = 0;                 // RA command code, or JSS message ID
  std::string_view name;                  // "Query Identification"
  std::string_view type_name;             // "QueryIdentification": msg::QueryIdentification, jss::msg::...
  MessageClass message_class = MessageClass::command;
  std::string_view service_uri;  // JSS: the service that defines it, "urn:jaus:jss:core:Discovery"; RA: empty
  std::string_view summary;      // JSS: one sentence, what it asks, says or does; RA: empty
  // The body (RA: the payload after the 16-byte header; JSS: the contents
  // after the 2-byte ID) to the JSON object of its fields, and back, read and
  // written in `dialect` (openjaus for the RA set where asked; a JSS message is
  // always read as JSS).
  Expected<nlohmann::ordered_json, Error> (*body_to_json)(std::span<const std::uint8_t> body,
                                                          wire::Dialect dialect) = nullptr;
  Expected<Bytes, Error> (*body_from_json)(const nlohmann::ordered_json& fields, wire::Dialect dialect) = nullptr;
  // The fields as described in the set's dialect (name, presence bit, wire type, limits), for docs.
  std::string (*fields_doc)() = nullptr;
};

// The message set a dialect speaks, sorted by code.
std::span<const MessageInfo> catalogue(wire::Dialect dialect);
const MessageInfo* find_message(wire::Dialect dialect, std::uint16_t code);
// By name ("Query Identification") or type name ("QueryIdentification").
const MessageInfo* find_message(wire::Dialect dialect, std::string_view name);

// RA only, from the code: core, communications, platform, manipulator,
// environment sensor, discovery (JSS names a message's service instead).
std::string_view message_subgroup(std::uint16_t code);

// docs/messages.md, generated from the descriptions (`jausctl msg doc`).
std::string messages_markdown();

// A whole RA message (header + payload) as {"code": "0x4402", "name": ...,
// "header": {...}, "fields": {...}}, and back. from_json derives the command
// code and data size; header keys it does not get take their defaults.
Expected<nlohmann::ordered_json, Error> message_to_json(std::span<const std::uint8_t> bytes,
                                                        wire::Dialect dialect = wire::Dialect::ra);
Expected<Bytes, Error> message_from_json(const nlohmann::ordered_json& message,
                                         wire::Dialect dialect = wire::Dialect::ra);

nlohmann::ordered_json header_to_json(const Header& header);

}  // namespace jaus::msg
