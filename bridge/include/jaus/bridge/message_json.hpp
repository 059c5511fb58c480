// JSON form of messages, following from their descriptions:
//   {"type":"0x0204","name":"set_velocity","kind":"command","timestamp":5,
//    "flags":0,"version":0,"fields":{"translational":1.25,...}}
// An ACK: {"type":"0x0202","name":"ack","acknowledges":"set_differential_output",...,"fields":{"result":0}}
#pragma once

#include <nlohmann/json.hpp>

#include "jaus/bridge/codec.hpp"
#include "jaus/bridge/result.hpp"

namespace jaus::bridge {

nlohmann::json to_json(const Envelope& envelope);
nlohmann::json fields_to_json(const Message& message);

// Reads "type" (hex string or number) or "name", optional "timestamp", "flags",
// "version", and "fields" (every wire field required). For an ACK give
// "name":"ack" and the acknowledged "type".
Result<Envelope> envelope_from_json(const nlohmann::json& json);
Result<Message> message_from_json(const Message& prototype, const nlohmann::json& fields);

}  // namespace jaus::bridge
