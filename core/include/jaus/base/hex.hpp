// Hex text <-> bytes, for tools, logs and test vectors.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace jaus {

// Upper-case, no separators.
std::string to_hex(std::span<const std::uint8_t> bytes);

// Accepts upper or lower case; spaces and a leading "0x" are ignored. On
// failure `why` says where ("odd number of hex digits", "'G' at position 4 ...").
bool parse_hex(std::string_view text, std::vector<std::uint8_t>& out, std::string& why);

}  // namespace jaus
