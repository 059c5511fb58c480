// The 16-byte JAUS message header (docs/wire-format.md), every multi-byte field
// little-endian.
#pragma once

#include <algorithm>
#include <array>
#include <iterator>
#include <cstdint>
#include <span>

#include "jaus/core/address.hpp"
#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

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

namespace detail {
// Why a header was rejected (out of line: only bad packets get here).
Error header_error(std::span<const std::uint8_t> bytes, const Header& decoded, unsigned data_flag);
inline bool is_known_data_flag(unsigned flag) { return flag == 0 || flag == 1 || flag == 2 || flag == 4 || flag == 8; }
}  // namespace detail

// Writes the header as given, masking each field to its bits (hot path; the
// encoder sets command code and data size itself).
inline void encode_header_unchecked(const Header& h, std::span<std::uint8_t, kHeaderSize> out) {
  std::uint8_t* p = out.data();
  const auto properties = static_cast<std::uint16_t>(
      (h.priority & 0x0F) | ((static_cast<unsigned>(h.ack_nak) & 0x03) << 4) | (h.service_connection ? 0x40 : 0) |
      (h.experimental ? 0x80 : 0) | ((h.version & 0x3F) << 8));
  const auto data_control =
      static_cast<std::uint16_t>((h.data_size & 0x0FFF) | ((static_cast<unsigned>(h.data_flag) & 0x0F) << 12));
  // Little-endian, byte by byte; addresses go instance, component, node, subsystem.
  const std::uint8_t bytes[kHeaderSize] = {
      static_cast<std::uint8_t>(properties), static_cast<std::uint8_t>(properties >> 8),
      static_cast<std::uint8_t>(h.command_code), static_cast<std::uint8_t>(h.command_code >> 8),
      h.destination.instance, h.destination.component, h.destination.node, h.destination.subsystem,
      h.source.instance, h.source.component, h.source.node, h.source.subsystem,
      static_cast<std::uint8_t>(data_control), static_cast<std::uint8_t>(data_control >> 8),
      static_cast<std::uint8_t>(h.sequence), static_cast<std::uint8_t>(h.sequence >> 8)};
  std::copy(std::begin(bytes), std::end(bytes), p);
}

namespace detail {
// The header's fields from its 16 bytes, before any check.
inline Header read_header(const std::uint8_t* p) {
  Header h;
  const unsigned properties = p[0] | (p[1] << 8);
  h.priority = properties & 0x0F;
  h.ack_nak = static_cast<AckNak>((properties >> 4) & 0x03);
  h.service_connection = (properties & 0x40) != 0;
  h.experimental = (properties & 0x80) != 0;
  h.version = static_cast<std::uint8_t>((properties >> 8) & 0x3F);
  h.command_code = static_cast<std::uint16_t>(p[2] | (p[3] << 8));
  h.destination = Address{p[7], p[6], p[5], p[4]};
  h.source = Address{p[11], p[10], p[9], p[8]};
  const unsigned data_control = p[12] | (p[13] << 8);
  h.data_size = static_cast<std::uint16_t>(data_control & 0x0FFF);
  h.data_flag = static_cast<DataFlag>(data_control >> 12);
  h.sequence = static_cast<std::uint16_t>(p[14] | (p[15] << 8));
  return h;
}
// Version 1 or 2, known data flag, data size <= 4080.
inline bool is_valid_header(const Header& h) {
  return (h.version == kVersionRa30 || h.version == kVersionRa32) &&
         is_known_data_flag(static_cast<unsigned>(h.data_flag)) && h.data_size <= kMaxPayloadSize;
}
}  // namespace detail

// Reads and validates a header: version 1 or 2, known data flag, data size <= 4080.
inline Expected<Header, Error> decode_header(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kHeaderSize) return unexpected(detail::header_error(bytes, Header{}, 0));
  const Header h = detail::read_header(bytes.data());
  if (!detail::is_valid_header(h)) [[unlikely]]
    return unexpected(detail::header_error(bytes, h, static_cast<unsigned>(h.data_flag)));
  return h;
}

// A received message: the header and a view of its payload, whose length the
// header's data size must match exactly.
struct PacketView {
  Header header;
  std::span<const std::uint8_t> payload;
};
namespace detail {
Error packet_size_error(const Header& header, std::size_t payload_size);
}
// The checks of decode_header, then the data size; the header is read straight
// into the result rather than through decode_header's own Expected (a copy and
// a variant on every received packet).
[[gnu::always_inline]] inline Expected<PacketView, Error> decode_packet(std::span<const std::uint8_t> bytes) {
  if (bytes.size() < kHeaderSize) [[unlikely]]
    return unexpected(detail::header_error(bytes, Header{}, 0));
  const PacketView packet{detail::read_header(bytes.data()), bytes.subspan(kHeaderSize)};
  if (!detail::is_valid_header(packet.header)) [[unlikely]]
    return unexpected(detail::header_error(bytes, packet.header, static_cast<unsigned>(packet.header.data_flag)));
  if (packet.header.data_size != packet.payload.size()) [[unlikely]]
    return unexpected(detail::packet_size_error(packet.header, packet.payload.size()));
  return packet;
}

}  // namespace jaus
