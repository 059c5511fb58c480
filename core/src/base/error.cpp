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

std::string_view to_string(ErrorDomain domain) {
  switch (domain) {
    case ErrorDomain::codec: return "codec";
    case ErrorDomain::io_time: return "I/O and time";
    case ErrorDomain::usage: return "usage";
    case ErrorDomain::peer: return "peer";
  }
  return "unknown domain";
}

// Every code listed, so a new code without a domain fails to compile (-Wswitch).
ErrorDomain domain(ErrorCode code) {
  switch (code) {
    case ErrorCode::truncated:
    case ErrorCode::trailing_bytes:
    case ErrorCode::data_size_mismatch:
    case ErrorCode::data_size_too_large:
    case ErrorCode::unsupported_version:
    case ErrorCode::bad_data_flag:
    case ErrorCode::reserved_presence_bits:
    case ErrorCode::count_out_of_range:
    case ErrorCode::count_mismatch:
    case ErrorCode::bad_value:
    case ErrorCode::out_of_range:
    case ErrorCode::string_too_long:
    case ErrorCode::unknown_message:
    case ErrorCode::output_too_small:
    case ErrorCode::payload_too_large:
    case ErrorCode::bad_frame:
    case ErrorCode::json: return ErrorDomain::codec;
    case ErrorCode::io:
    case ErrorCode::timeout:
    case ErrorCode::interrupted: return ErrorDomain::io_time;
    case ErrorCode::invalid_argument: return ErrorDomain::usage;
    case ErrorCode::refused:
    case ErrorCode::malformed: return ErrorDomain::peer;
  }
  return ErrorDomain::usage;  // not reached: every code is listed
}

bool has_position(ErrorCode code) { return domain(code) == ErrorDomain::codec; }

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
