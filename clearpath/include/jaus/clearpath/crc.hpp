// CRC-16/CCITT-FALSE of the Clearpath protocol frame (poly 0x1021, init 0xFFFF,
// no reflection, no final XOR). Boost.CRC does the work; no hand-written table.
#pragma once

#include <cstdint>
#include <span>

namespace jaus::clearpath {

std::uint16_t clearpath_crc(std::span<const std::uint8_t> bytes) noexcept;

}  // namespace jaus::clearpath
