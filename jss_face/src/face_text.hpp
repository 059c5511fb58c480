// Message IDs as text for the face's logs ("0x200D").
#pragma once

#include <cstdint>
#include <string>

namespace jaus::jss_face {

inline std::string hex_id(std::uint16_t id) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string text = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) text += kDigits[(id >> shift) & 0xF];
  return text;
}

}  // namespace jaus::jss_face
