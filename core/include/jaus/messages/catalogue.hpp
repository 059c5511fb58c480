// The message catalogue: every supported message by command code, with its
// name and its JSON form. Built from the message descriptions (all.hpp); used
// by tools (jausctl msg) and tests, not on the hot path.
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

struct MessageInfo {
  std::uint16_t code = 0;
  std::string_view name;
  // Payload (no header) to the JSON object of its fields, and back.
  Expected<nlohmann::ordered_json, Error> (*payload_to_json)(std::span<const std::uint8_t>, wire::Dialect) = nullptr;
  Expected<Bytes, Error> (*payload_from_json)(const nlohmann::ordered_json&, wire::Dialect) = nullptr;
  // The fields as described (name, presence bit, wire type, limits), for docs.
  std::string (*fields_doc)() = nullptr;
};

// docs/messages.md, generated from the descriptions (`jausctl msg doc`).
std::string messages_markdown();

// Every supported message, sorted by code.
std::span<const MessageInfo> catalogue();
const MessageInfo* find_message(std::uint16_t code);
const MessageInfo* find_message(std::string_view name);

// Derived from the code: class (command, query, inform, ...) and subgroup
// (core, communications, platform, manipulator, environment, discovery).
std::string_view message_class(std::uint16_t code);
std::string_view message_subgroup(std::uint16_t code);

// A whole message (header + payload) as {"code": "0x4402", "name": ...,
// "header": {...}, "fields": {...}}, and back. from_json derives the command
// code and data size; header keys it does not get take their defaults.
Expected<nlohmann::ordered_json, Error> message_to_json(std::span<const std::uint8_t> bytes,
                                                wire::Dialect dialect = wire::Dialect::ra);
Expected<Bytes, Error> message_from_json(const nlohmann::ordered_json& message, wire::Dialect dialect = wire::Dialect::ra);

nlohmann::ordered_json header_to_json(const Header& header);

}  // namespace jaus::msg
