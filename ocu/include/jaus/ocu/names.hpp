// Words for the numbers JAUS sends (component IDs, identification types,
// response codes, primary status) and for the values an OCU states (codes,
// durations, rates): what errors and tools say.
#pragma once

#include <cstdint>
#include <string>

#include "jaus/base/time.hpp"

namespace jaus::ocu {

// "node manager", "primitive driver", ... ("component 77" when not in RA 3.x).
std::string component_kind(std::uint8_t component_id);
// Report Identification type: "vehicle", "OCU", "other subsystem", "node", "payload".
std::string identification_class(std::uint16_t type);
// Confirm Component Control response code: "granted", "not supported", "not available".
std::string control_response_text(std::uint8_t code);
// Confirm Service Connection response code: "created", "command not supported", ...
std::string service_connection_response_text(std::uint8_t code);
// Primary status (bits 0-3 of Report Component Status): "Ready", ... or "unknown (7)".
std::string primary_status_text(std::uint8_t primary_status);

// "1 s", "0.25 s": how messages state a duration that was given.
std::string seconds_text(jaus::rt::Duration d);
// "4.0 s": how long something took (measured, so one decimal).
std::string elapsed_text(jaus::rt::Duration d);
// "0x4402".
std::string code_text(std::uint16_t code);
// A rate as people write it: 5, 0.25, 12.5 (two decimals at most).
std::string hz_text(double hz);

}  // namespace jaus::ocu
