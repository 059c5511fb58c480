// Acknowledgement of a command or request: same type and timestamp as the
// message it acknowledges, and a two-byte result whose bits say what was wrong.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "jaus/clearpath/fields.hpp"

namespace jaus::clearpath {

enum AckResultBit : std::uint16_t {
  kAckBadChecksum = 1u << 0,       // the platform did not get the message: retry it
  kAckTypeNotSupported = 1u << 1,
  kAckBadFormat = 1u << 2,
  kAckOutOfRange = 1u << 3,
  kAckNoBandwidth = 1u << 4,       // requests only
  kAckFrequencyTooHigh = 1u << 5,  // requests only
  kAckTooManyTypes = 1u << 6,      // requests only
};

// "bad checksum|out of range" style text; "ok" for 0.
std::string describe_ack_result(std::uint16_t result);

struct Ack {
  static constexpr std::string_view kName = "ack";
  std::uint16_t result = 0;
  template <class Self, class V>
  static void describe(Self& s, V& v) { v(fields::integer<std::uint16_t>("result", s.result)); }
  bool operator==(const Ack&) const = default;
};

}  // namespace jaus::clearpath
