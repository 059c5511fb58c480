#include "jaus/bridge/frame.hpp"

#include "jaus/bridge/crc.hpp"

namespace jaus::bridge {

Result<std::size_t> append_frame(std::vector<std::uint8_t>& out, const FrameHeader& header,
                                 std::span<const std::uint8_t> payload) {
  if (payload.size() > kMaxPayload)
    return Error{ErrorCode::payload_too_large, 0, "",
                 std::to_string(payload.size()) + " bytes, at most " + std::to_string(kMaxPayload)};
  const std::size_t start = out.size();
  const auto length = static_cast<std::uint8_t>(payload.size() + kMinLengthField);
  out.reserve(start + payload.size() + kFrameOverhead);
  out.push_back(kStartOfHeader);
  out.push_back(length);
  out.push_back(static_cast<std::uint8_t>(~length));
  out.push_back(header.version);
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(header.timestamp >> (8 * i)));
  out.push_back(header.flags);
  out.push_back(static_cast<std::uint8_t>(header.type));
  out.push_back(static_cast<std::uint8_t>(header.type >> 8));
  out.push_back(kStartOfText);
  out.insert(out.end(), payload.begin(), payload.end());
  const std::uint16_t crc = clearpath_crc(std::span(out).subspan(start));
  out.push_back(static_cast<std::uint8_t>(crc));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return out.size() - start;
}

Result<std::vector<std::uint8_t>> encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  auto written = append_frame(out, header, payload);
  if (!written) return written.error();
  return out;
}

Result<Frame> decode_frame(std::span<const std::uint8_t> bytes) {
  const auto bad = [](std::size_t offset, std::string why) {
    return Error{ErrorCode::bad_frame, offset, "", std::move(why)};
  };
  if (bytes.size() < kFrameOverhead) return bad(0, "shorter than the 14-byte minimum");
  if (bytes[0] != kStartOfHeader) return bad(0, "no 0xAA start byte");
  const std::uint8_t length = bytes[1];
  if (static_cast<std::uint8_t>(length ^ bytes[2]) != 0xFF) return bad(1, "LEN and ~LEN disagree");
  if (length < kMinLengthField) return bad(1, "LEN below 11");
  if (bytes.size() != std::size_t{length} + 3)
    return bad(1, "LEN says " + std::to_string(length + 3) + " bytes, got " + std::to_string(bytes.size()));
  if (bytes[kStxOffset] != kStartOfText) return bad(kStxOffset, "no 0x55 after the header");
  const std::size_t crc_at = bytes.size() - 2;
  const auto received = static_cast<std::uint16_t>(bytes[crc_at] | (bytes[crc_at + 1] << 8));
  if (received != clearpath_crc(bytes.first(crc_at))) return bad(crc_at, "CRC mismatch");
  Frame frame;
  frame.header.version = bytes[3];
  frame.header.timestamp = static_cast<std::uint32_t>(bytes[4]) | (static_cast<std::uint32_t>(bytes[5]) << 8) |
                           (static_cast<std::uint32_t>(bytes[6]) << 16) | (static_cast<std::uint32_t>(bytes[7]) << 24);
  frame.header.flags = bytes[8];
  frame.header.type = static_cast<std::uint16_t>(bytes[9] | (bytes[10] << 8));
  frame.payload.assign(bytes.begin() + kHeaderSize, bytes.begin() + static_cast<std::ptrdiff_t>(crc_at));
  return frame;
}

}  // namespace jaus::bridge
