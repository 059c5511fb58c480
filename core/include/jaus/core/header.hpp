// The 16-byte JAUS message header (jaus-wire-notes.md), every multi-byte field
// little-endian.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "jaus/core/address.hpp"
#include "jaus/core/error.hpp"
#include "jaus/core/expected.hpp"

namespace jaus {

inline constexpr std::size_t kHeaderSize = 16;
inline constexpr std::size_t kMaxPayloadSize = 4080;  // data size field is 12 bits, capped by the RA

enum class AckNak : std::uint8_t { none = 0, ack_requested = 1, nak = 2, ack = 3 };

enum class DataFlag : std::uint8_t { single = 0, first = 1, middle = 2, retransmitted = 4, last = 8 };

// JAUS version in header bits 8-13.
inline constexpr std::uint8_t kVersionRa30 = 1;  // RA 3.0 / 3.1
inline constexpr std::uint8_t kVersionRa32 = 2;  // RA 3.2 / 3.3: what we send

namespace priority {
inline constexpr std::uint8_t kDefault = 6;
inline constexpr std::uint8_t kHigh = 11;
inline constexpr std::uint8_t kSafetyCritical = 12;  // 12-15
}  // namespace priority

struct Header {
  std::uint8_t priority = priority::kDefault;  // 0-15
  AckNak ack_nak = AckNak::none;
  bool service_connection = false;
  bool experimental = false;
  std::uint8_t version = kVersionRa32;
  std::uint16_t command_code = 0;
  Address destination;
  Address source;
  std::uint16_t data_size = 0;  // payload bytes
  DataFlag data_flag = DataFlag::single;
  std::uint16_t sequence = 0;

  bool operator==(const Header&) const = default;
};

// Writes the header; fields out of their bit range are an error.
Expected<std::array<std::uint8_t, kHeaderSize>, Error> encode_header(const Header& header);
void encode_header_unchecked(const Header& header, std::span<std::uint8_t, kHeaderSize> out);

// Reads and validates a header: version 1 or 2, known data flag, data size <= 4080.
Expected<Header, Error> decode_header(std::span<const std::uint8_t> bytes);

// A received message: the header and a view of its payload, whose length the
// header's data size must match exactly.
struct PacketView {
  Header header;
  std::span<const std::uint8_t> payload;
};
Expected<PacketView, Error> decode_packet(std::span<const std::uint8_t> bytes);

}  // namespace jaus
