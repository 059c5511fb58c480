#include "jaus/clearpath/ack.hpp"

#include <array>
#include <utility>

namespace jaus::clearpath {

std::string describe_ack_result(std::uint16_t result) {
  if (result == 0) return "ok";
  static constexpr std::array<std::pair<std::uint16_t, std::string_view>, 7> kBits{{
      {kAckBadChecksum, "bad checksum"},
      {kAckTypeNotSupported, "type not supported"},
      {kAckBadFormat, "bad format"},
      {kAckOutOfRange, "out of range"},
      {kAckNoBandwidth, "no bandwidth"},
      {kAckFrequencyTooHigh, "frequency too high"},
      {kAckTooManyTypes, "too many message types"},
  }};
  std::string out;
  std::uint16_t known = 0;
  for (const auto& [bit, text] : kBits) {
    known = static_cast<std::uint16_t>(known | bit);
    if ((result & bit) == 0) continue;
    if (!out.empty()) out += "|";
    out += text;
  }
  if ((result & ~known) != 0) out += (out.empty() ? "" : "|") + std::string("unknown bits");
  return out;
}

}  // namespace jaus::clearpath
