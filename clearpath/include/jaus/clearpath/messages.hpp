// The Clearpath message set: look-up by type code and name, and messages made by type.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "jaus/clearpath/any_message.hpp"
#include "jaus/clearpath/message_kind.hpp"

namespace jaus::clearpath {

// A type code of the document and its message name.
struct MessageTypeInfo {
  std::uint16_t type;
  std::string_view name;
  MessageKind kind;
};

// All typed messages of the document, ordered by type code (Ack excluded).
std::span<const MessageTypeInfo> message_catalogue();
std::optional<MessageTypeInfo> find_message(std::uint16_t type);
std::optional<MessageTypeInfo> find_message(std::string_view name);

// Default-constructed message of that type (nullopt for types the document lacks).
std::optional<AnyMessage> make_message(std::uint16_t type);

// The type code a message is sent with (Ack: nullopt, it borrows its target's).
std::optional<std::uint16_t> type_of(const AnyMessage& message);
std::string_view name_of(const AnyMessage& message);

}  // namespace jaus::clearpath
