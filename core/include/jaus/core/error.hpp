// Errors as values: what went wrong, where (byte offset) and in which field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace jaus {

enum class ErrorCode : std::uint8_t {
  truncated,              // fewer bytes than the field needs
  trailing_bytes,         // bytes left after the last field
  data_size_mismatch,     // header data size disagrees with the datagram
  data_size_too_large,    // header data size over 4080
  unsupported_version,    // header version other than RA 3.0/3.1 or 3.2/3.3
  bad_data_flag,          // data flag not one of 0, 1, 2, 4, 8
  reserved_presence_bits, // presence vector sets bits the message does not define
  count_out_of_range,     // an element count outside its allowed range
  count_mismatch,         // an array whose length disagrees with its declared count
  bad_value,              // a value the field cannot hold (enum tag, NaN, ...)
  string_too_long,        // text longer than its fixed field
  unknown_message,        // command code not in the message set
  output_too_small,       // encode buffer cannot hold the message
  payload_too_large,      // encoded payload larger than one packet (4080 bytes)
  json,                   // JSON input malformed or of the wrong type
};

std::string_view to_string(ErrorCode code);

struct Error {
  ErrorCode code{};
  std::size_t offset = 0;      // byte offset in the buffer being decoded/encoded
  std::string_view field;      // field name (static storage), empty if not field-specific
  std::string detail;          // optional extra words (JSON errors, limits)

  // One line: "offset 23, field 'latitude_deg': truncated (needs 4 bytes)".
  std::string message() const;
};

}  // namespace jaus
