// JSON form of messages, following from their descriptions:
//   {"type":"0x0204","name":"set_velocity","kind":"command","timestamp":5,
//    "flags":0,"version":0,"fields":{"translational":1.25,...}}
// An ACK: {"type":"0x0202","name":"ack","acknowledges":"set_differential_output",...,"fields":{"result":0}}
#pragma once

#include <nlohmann/json.hpp>

#include "jaus/clearpath/codec.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath {

nlohmann::json to_json(const Envelope& envelope);
nlohmann::json fields_to_json(const AnyMessage& message);

// Reads "type" (hex string or number) or "name", optional "timestamp", "flags",
// "version", and "fields" (every wire field required). For an ACK give
// "name":"ack" and the acknowledged "type".
Expected<Envelope> envelope_from_json(const nlohmann::json& json);
Expected<AnyMessage> message_from_json(const AnyMessage& prototype, const nlohmann::json& fields);

}  // namespace jaus::clearpath
