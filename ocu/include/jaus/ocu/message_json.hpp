// Messages known only at run time (a code or JSON from the command line), to
// and from the JSON form `jausctl msg decode` prints:
//   {"code":"0x4402","name":...,"header":{...},"fields":{...}}
// Sans-I/O: built on the message catalogue.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/core/header.hpp"
#include "jaus/wire/codecs.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::ocu {

using Json = nlohmann::ordered_json;

// A message ready to send: header (addresses are set by the sender) and payload.
struct PreparedMessage {
  jaus::Header header;
  std::vector<std::uint8_t> payload;
};

// The report that answers a query: Query X (0x2nnn) -> Report X (0x4nnn).
std::optional<std::uint16_t> report_code_for(std::uint16_t query_code);

// The query of `code`, with `presence_vector` when given (an error if the
// query has none), `fields` for its other fields (camera_id, ...); fields not
// given are 0.
jaus::Expected<PreparedMessage> prepare_query(std::uint16_t code, std::optional<std::uint32_t> presence_vector,
                                      const Json& fields);

// A message in the `jausctl msg decode` form. Header keys it has (priority,
// ack_nak, ...) are kept; addresses, data size and sequence number are the
// sender's.
jaus::Expected<PreparedMessage> prepare_message(const Json& message, jaus::wire::Dialect dialect);

// A received message in the `jausctl msg decode` form. A code outside the
// catalogue is kept as hex ("payload"); a payload that does not decode is an error.
jaus::Expected<Json> message_json(const Received& message, jaus::wire::Dialect dialect);

// One line of JSON; text that is not UTF-8 prints as U+FFFD (as msg decode does).
std::string json_line(const Json& json);

// Errors are invalid_argument (a code or field that cannot be used), json, or
// the codec's own error when a received payload does not decode; message()
// is one line for people.
// "bad JSON ('x' is missing)" rather than the codec's "offset 0: ..." for JSON input.
std::string describe_error(const jaus::Error& error);

}  // namespace jaus::ocu
