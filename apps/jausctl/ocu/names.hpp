// Words for the numbers JAUS sends: component IDs, identification types,
// response codes, primary status. Used in what the OCU commands print.
#pragma once

#include <cstdint>
#include <string>

namespace jausctl::ocu {

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

}  // namespace jausctl::ocu
