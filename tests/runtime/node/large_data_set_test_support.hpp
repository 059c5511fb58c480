// Shared helpers of the large data set tests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "jaus/core/header.hpp"

namespace jaus::node::test {

// A payload whose bytes depend on their position, so a misplaced part shows.
inline std::vector<std::uint8_t> patterned_payload(std::size_t size, std::uint8_t seed = 0) {
  std::vector<std::uint8_t> payload(size);
  for (std::size_t i = 0; i < size; ++i) payload[i] = static_cast<std::uint8_t>((i * 7 + i / 251 + seed) & 0xFF);
  return payload;
}

inline Header image_header(std::uint16_t first_sequence, Address source = Address{1, 1, 37, 1}) {
  Header header;
  header.command_code = 0x4807;  // Report Image: the usual large message
  header.source = source;
  header.destination = Address{2, 1, 40, 1};
  header.sequence = first_sequence;
  return header;
}

}  // namespace jaus::node::test
