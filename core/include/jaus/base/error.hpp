// Errors as values, one type for the whole project: what went wrong and, for
// bytes and JSON being read or written (JAUS messages, Clearpath frames), where
// (byte offset) and in which field. Nothing in the libraries throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace jaus {

// Grouped by domain (see ErrorDomain); the order is kept stable so a code's
// number never changes meaning.
enum class ErrorCode : std::uint8_t {
  // --- codec: bytes and JSON being read or written (JAUS wire, Clearpath frames);
  //     the error has an offset and maybe a field.
  truncated,              // fewer bytes than the field needs
  trailing_bytes,         // bytes left after the last field
  data_size_mismatch,     // JAUS header data size disagrees with the datagram
  data_size_too_large,    // JAUS header data size over 4080
  unsupported_version,    // JAUS header version other than RA 3.0/3.1 or 3.2/3.3
  bad_data_flag,          // JAUS data flag not one of 0, 1, 2, 4, 8
  reserved_presence_bits, // presence vector sets bits the message does not define
  count_out_of_range,     // an element count outside its allowed range
  count_mismatch,         // an array whose length disagrees with its declared count
  bad_value,              // a value the field cannot hold (enum tag, NaN, overflow after scaling)
  out_of_range,           // a value outside the range its document gives
  string_too_long,        // text longer than its field
  unknown_message,        // message code or type not in the message set
  output_too_small,       // encode buffer cannot hold the message
  payload_too_large,      // payload larger than one packet or frame can carry (detail: the limit)
  bad_frame,              // bytes that are not one well-formed frame (Clearpath; a JAUS datagram's framing)
  json,                   // JSON input malformed or of the wrong type
  // --- I/O and time: the detail is the whole story, one line.
  io,                     // a socket, port or file cannot be opened, bound or used
  timeout,                // no answer within the time given
  interrupted,            // stopped by a signal or by the caller
  // --- usage and configuration
  invalid_argument,       // a value given by the user or the configuration that cannot be used
  // --- peers: what another node answered or sent
  refused,                // the peer answered no
  malformed,              // a message from a peer that does not decode (the detail says which, and why)
};

// The groups above: what kind of thing went wrong, for callers that react to a
// kind rather than to one code (retry on io_time, report usage to the user, ...).
enum class ErrorDomain : std::uint8_t {
  codec,   // bytes or JSON; the error says where (offset, field)
  io_time, // io, timeout, interrupted
  usage,   // invalid_argument: the user's or the configuration's value
  peer,    // refused, malformed: another node's answer
};

std::string_view to_string(ErrorCode code);
std::string_view to_string(ErrorDomain domain);
ErrorDomain domain(ErrorCode code);
// True for the codec errors, which say where in the bytes they happened.
bool has_position(ErrorCode code);

struct Error {
  ErrorCode code{};
  std::size_t offset = 0;  // byte offset in the buffer being decoded/encoded (codec errors)
  std::string field;       // field name or path ("latitude_deg", "voltages[2]"), empty if none; for other
                           // errors what they concern, if anything (an option's key, "jausd.yaml:12")
  std::string detail;      // extra words (limits, the bad value); the whole message for other errors

  // One line. Codec errors: "offset 23, field 'latitude_deg': truncated (needs 4 bytes)";
  // others: the detail ("127.0.0.1:3794 is already in use"), or the code's words without one.
  std::string message() const;
};

// An error that is only a sentence (io, timeout, refused, ...).
inline Error make_error(ErrorCode code, std::string detail) { return Error{code, 0, {}, std::move(detail)}; }

}  // namespace jaus
