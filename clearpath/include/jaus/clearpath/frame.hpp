// One Clearpath frame on the wire:
//   AA | LEN | ~LEN | VER | TIMESTAMP u32 LE | FLAGS | TYPE u16 LE | 55 | PAYLOAD | CRC u16 LE
// LEN counts every byte after ~LEN, the CRC included (payload + 11).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::clearpath {

inline constexpr std::uint8_t kStartOfHeader = 0xAA;
inline constexpr std::uint8_t kStartOfText = 0x55;
inline constexpr std::size_t kFrameHeaderSize = 12;      // AA through 55
inline constexpr std::size_t kStxOffset = 11;
inline constexpr std::size_t kLengthOffset = 1;
inline constexpr std::size_t kLengthCheckOffset = 2;
inline constexpr std::size_t kLeadBytes = 3;  // AA LEN ~LEN: the bytes LEN does not count
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
Expected<std::size_t> append_frame(std::vector<std::uint8_t>& out, const FrameHeader& header,
                                 std::span<const std::uint8_t> payload);
Expected<std::vector<std::uint8_t>> encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload);

// The one check of a frame's bytes, used by decode_frame and FrameParser:
// bytes start at a 0xAA and may run past the frame or stop short of it.
enum class FrameCheck {
  complete,     // a whole frame with a good CRC: header and size are set
  need_more,    // nothing wrong so far, but the frame is not all there
  bad_length,   // LEN and ~LEN disagree, or LEN < 11
  oversize,     // LEN announces more than the limit given
  missing_stx,  // no 0x55 where the header ends
  bad_crc,      // checksum mismatch: header and both CRCs are set
};

struct FrameInspection {
  FrameCheck check = FrameCheck::need_more;
  std::size_t size = 0;  // the frame's size from LEN (set from oversize on)
  FrameHeader header;
  std::uint16_t expected_crc = 0;
  std::uint16_t received_crc = 0;
};

FrameInspection inspect_frame(std::span<const std::uint8_t> bytes, std::size_t max_frame_size = kMaxFrameSize);

// Exactly one well-formed frame (length pair, STX, CRC) and nothing else.
Expected<Frame> decode_frame(std::span<const std::uint8_t> bytes);

// Cuts a buffer of frames this side encoded itself (a simulated platform's
// output) into one view per frame, by their LEN bytes; a cut-off last frame
// comes out as it is. Not a validator: a peer's bytes go through FrameParser.
std::vector<std::span<const std::uint8_t>> split_frames(std::span<const std::uint8_t> frames);

}  // namespace jaus::clearpath
