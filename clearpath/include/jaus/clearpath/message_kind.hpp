// What a type code is, from its range alone.
#pragma once

#include <cstdint>
#include <string_view>

namespace jaus::clearpath {

enum class MessageKind { command, request, data, unassigned };

constexpr MessageKind kind_of(std::uint16_t type) {
  if (type >= 0x0001 && type <= 0x3FFF) return MessageKind::command;
  if (type >= 0x4000 && type <= 0x7FFF) return MessageKind::request;
  if (type >= 0x8000 && type <= 0xBFFF) return MessageKind::data;
  return MessageKind::unassigned;
}

constexpr std::string_view to_string(MessageKind kind) {
  switch (kind) {
    case MessageKind::command: return "command";
    case MessageKind::request: return "request";
    case MessageKind::data: return "data";
    case MessageKind::unassigned: break;
  }
  return "unassigned";
}

// Every data type is its request type + 0x4000.
constexpr std::uint16_t reply_type_of(std::uint16_t request_type) {
  return static_cast<std::uint16_t>(request_type + 0x4000);
}

}  // namespace jaus::clearpath
