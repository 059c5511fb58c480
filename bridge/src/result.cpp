#include "jaus/bridge/result.hpp"

namespace jaus::bridge {

std::string_view to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::payload_too_short: return "payload too short";
    case ErrorCode::payload_too_long: return "payload too long";
    case ErrorCode::payload_too_large: return "payload too large for one frame";
    case ErrorCode::unknown_type: return "message type not in the protocol document";
    case ErrorCode::value_not_encodable: return "value not encodable";
    case ErrorCode::out_of_range: return "value out of range";
    case ErrorCode::text_too_long: return "text too long";
    case ErrorCode::too_many_elements: return "too many elements";
    case ErrorCode::bad_frame: return "bad frame";
    case ErrorCode::json: return "bad JSON";
  }
  return "unknown error";
}

std::string Error::message() const {
  std::string out = "offset " + std::to_string(offset);
  if (!field.empty()) out += ", field '" + field + "'";
  out += ": ";
  out += to_string(code);
  if (!detail.empty()) out += " (" + detail + ")";
  return out;
}

}  // namespace jaus::bridge
