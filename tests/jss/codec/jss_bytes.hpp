// Byte vectors from hex text, for the byte examples of docs/jss.md.
#pragma once

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

#include "jaus/base/hex.hpp"

namespace jaus::test {

inline std::vector<std::uint8_t> hex_bytes(std::string_view text) {
  auto bytes = parse_hex(text);
  EXPECT_TRUE(bytes) << text;
  return bytes ? *bytes : std::vector<std::uint8_t>{};
}

// ASCII text as bytes (strings inside the examples).
inline std::vector<std::uint8_t> ascii(std::string_view text) { return {text.begin(), text.end()}; }

inline std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace jaus::test
