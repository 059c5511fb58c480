// Errors as values for the Clearpath codec: every fallible call returns a
// Result<T>, never throws. An Error says what went wrong and where.
#pragma once

#include <cassert>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace jaus::bridge {

enum class ErrorCode {
  payload_too_short,   // fewer bytes than the message layout needs
  payload_too_long,    // bytes left over after the last field
  payload_too_large,   // encoded payload over the 244 bytes one frame can carry
  unknown_type,        // message type not in the protocol document
  value_not_encodable, // value does not fit its wire field (after scaling), or NaN
  out_of_range,        // value outside the range the document gives for the field
  text_too_long,       // string longer than its field allows
  too_many_elements,   // list longer than its one-byte count allows
  bad_frame,           // frame bytes are not one well-formed frame
  json,                // JSON input malformed or of the wrong shape
};

std::string_view to_string(ErrorCode code);

struct Error {
  ErrorCode code{};
  std::size_t offset = 0;  // byte offset in the payload/frame being processed
  std::string field;       // field path ("left.p", "voltages[2]"), empty if not field-specific
  std::string detail;      // extra words: limits, the bad value

  // One line, e.g. "offset 4, field 'right': payload too short (needs 2 bytes)".
  std::string message() const;
};

template <class T>
class Result {
 public:
  Result(T value) : state_(std::in_place_index<0>, std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : state_(std::in_place_index<1>, std::move(error)) {}  // NOLINT

  bool has_value() const { return state_.index() == 0; }
  explicit operator bool() const { return has_value(); }
  T& value() & { assert(has_value()); return std::get<0>(state_); }
  const T& value() const& { assert(has_value()); return std::get<0>(state_); }
  T&& value() && { assert(has_value()); return std::get<0>(std::move(state_)); }
  const Error& error() const { assert(!has_value()); return std::get<1>(state_); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  std::variant<T, Error> state_;
};

}  // namespace jaus::bridge
