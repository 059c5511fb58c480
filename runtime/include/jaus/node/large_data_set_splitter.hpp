// Splits one message into the packets that carry it (docs/wire-format.md,
// "Large data sets"): a payload of at most 4080 bytes (or `piece_size`) is one
// packet with data flag 0; a larger one goes as packets of that size (the last one shorter)
// flagged 1 (first), 2 (middle) ... 8 (last), numbered s, s+1, ... from the
// header's sequence number s, wrapping after 65535.
//
// Nothing is copied: packets are views of the caller's payload, which must
// outlive the splitter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"
#include "jaus/core/large_message_pieces.hpp"

namespace jaus::node {

// Sequence numbers are 16 bits; more packets would reuse a number in one set.
inline constexpr std::size_t kMaxPacketsPerSet = kMaxPiecesPerMessage;

class LargeDataSetSplitter {
 public:
  // Packets a payload of this size needs (1 for an empty payload) in pieces
  // of at most `piece_size` bytes; reserve that many sequence numbers before splitting.
  static std::size_t packets_needed(std::size_t payload_size, std::size_t piece_size = kMaxPayloadSize);

  // `header.sequence` is the first packet's number; data size and data flag
  // are set per packet, every other field is copied. Fails when a header
  // field is out of range or the payload needs more than kMaxPacketsPerSet
  // packets.
  // `piece_size` (1..4080, clamped) is the most payload per packet: smaller
  // on a slow radio, where a 4080-byte packet holds the air for long
  // (NodeConfig::large_data_set_piece).
  static Expected<LargeDataSetSplitter, Error> create(const Header& header, std::span<const std::uint8_t> payload,
                                                      std::size_t piece_size = kMaxPayloadSize);

  std::size_t packet_count() const { return count_; }
  // Packet `index` (< packet_count()).
  PacketView packet(std::size_t index) const;
  // All packets, in sending order.
  std::vector<PacketView> packets() const;
  // Writes packet `index` as it goes on the wire (16-byte header + payload);
  // returns the bytes written.
  Expected<std::size_t, Error> encode(std::size_t index, std::span<std::uint8_t> out) const;

 private:
  LargeDataSetSplitter(const Header& header, std::span<const std::uint8_t> payload, std::size_t count,
                       std::size_t piece_size)
      : header_(header), payload_(payload), count_(count), piece_size_(piece_size) {}

  Header header_;
  std::span<const std::uint8_t> payload_;
  std::size_t count_;
  std::size_t piece_size_;
};

}  // namespace jaus::node
