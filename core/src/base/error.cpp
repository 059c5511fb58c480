#include "jaus/base/error.hpp"

namespace jaus {

std::string_view to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::truncated: return "truncated";
    case ErrorCode::trailing_bytes: return "unexpected bytes after the last field";
    case ErrorCode::data_size_mismatch: return "header data size disagrees with the packet length";
    case ErrorCode::data_size_too_large: return "data size larger than 4080 bytes";
    case ErrorCode::unsupported_version: return "unsupported JAUS version";
    case ErrorCode::bad_data_flag: return "invalid data flag";
    case ErrorCode::reserved_presence_bits: return "presence vector sets reserved bits";
    case ErrorCode::count_out_of_range: return "count out of range";
    case ErrorCode::count_mismatch: return "array length disagrees with its count";
    case ErrorCode::bad_value: return "invalid value";
    case ErrorCode::out_of_range: return "value out of range";
    case ErrorCode::string_too_long: return "string longer than its field";
    case ErrorCode::unknown_message: return "unknown command code";
    case ErrorCode::output_too_small: return "output buffer too small";
    case ErrorCode::payload_too_large: return "payload too large";
    case ErrorCode::bad_frame: return "bad frame";
    case ErrorCode::json: return "bad JSON";
    case ErrorCode::io: return "I/O error";
    case ErrorCode::timeout: return "no answer in time";
    case ErrorCode::interrupted: return "interrupted";
    case ErrorCode::invalid_argument: return "invalid argument";
    case ErrorCode::refused: return "refused";
    case ErrorCode::malformed: return "malformed message";
  }
  return "unknown error";
}

bool has_position(ErrorCode code) { return code <= ErrorCode::json; }

std::string Error::message() const {
  if (!has_position(code)) return detail.empty() ? std::string(to_string(code)) : detail;
  std::string out = "offset " + std::to_string(offset);
  if (!field.empty()) out += ", field '" + field + "'";
  out += ": ";
  out += to_string(code);
  if (!detail.empty()) out += " (" + detail + ")";
  return out;
}

}  // namespace jaus
