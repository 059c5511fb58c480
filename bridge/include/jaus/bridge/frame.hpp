// One Clearpath frame on the wire:
//   AA | LEN | ~LEN | VER | TIMESTAMP u32 LE | FLAGS | TYPE u16 LE | 55 | PAYLOAD | CRC u16 LE
// LEN counts every byte after ~LEN, the CRC included (payload + 11).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "jaus/bridge/result.hpp"

namespace jaus::bridge {

inline constexpr std::uint8_t kStartOfHeader = 0xAA;
inline constexpr std::uint8_t kStartOfText = 0x55;
inline constexpr std::size_t kHeaderSize = 12;      // AA through 55
inline constexpr std::size_t kStxOffset = 11;
inline constexpr std::size_t kFrameOverhead = 14;   // header + CRC
inline constexpr std::size_t kMinLengthField = 11;  // LEN of a frame without payload
inline constexpr std::size_t kMaxPayload = 255 - kMinLengthField;  // LEN is one byte
inline constexpr std::size_t kMaxFrameSize = kMaxPayload + kFrameOverhead;
inline constexpr std::uint8_t kFlagSuppressAck = 0x01;
// The document says version 1; both reference clients send 0 and nobody checks it.
inline constexpr std::uint8_t kDefaultVersion = 0;

struct FrameHeader {
  std::uint8_t version = kDefaultVersion;
  std::uint32_t timestamp = 0;  // ms
  std::uint8_t flags = 0;
  std::uint16_t type = 0;
  bool operator==(const FrameHeader&) const = default;
};

struct Frame {
  FrameHeader header;
  std::vector<std::uint8_t> payload;
  bool operator==(const Frame&) const = default;
};

// Appends one frame to out. Fails (out untouched) if the payload exceeds kMaxPayload.
Result<std::size_t> append_frame(std::vector<std::uint8_t>& out, const FrameHeader& header,
                                 std::span<const std::uint8_t> payload);
Result<std::vector<std::uint8_t>> encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload);

// Exactly one well-formed frame (length pair, STX, CRC) and nothing else.
Result<Frame> decode_frame(std::span<const std::uint8_t> bytes);

}  // namespace jaus::bridge
