// Hex text <-> bytes, for tools, logs and test vectors.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus {

// Upper-case, no separators.
std::string to_hex(std::span<const std::uint8_t> bytes);

// Accepts upper or lower case; spaces and a leading "0x" are ignored. A failure
// (invalid_argument) says where ("odd number of hex digits", "'G' at position 4 ...").
Expected<std::vector<std::uint8_t>> parse_hex(std::string_view text);

}  // namespace jaus
