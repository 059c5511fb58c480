#include "jaus/clearpath/crc.hpp"

#include <boost/crc.hpp>

namespace jaus::clearpath {

std::uint16_t clearpath_crc(std::span<const std::uint8_t> bytes) noexcept {
  boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return static_cast<std::uint16_t>(crc.checksum());
}

}  // namespace jaus::clearpath
