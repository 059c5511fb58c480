#include "jaus/clearpath/frame.hpp"

#include <algorithm>

#include "jaus/clearpath/crc.hpp"

namespace jaus::clearpath {

Expected<std::size_t> append_frame(std::vector<std::uint8_t>& out, const FrameHeader& header,
                                 std::span<const std::uint8_t> payload) {
  if (payload.size() > kMaxPayload)
    return unexpected(Error{ErrorCode::payload_too_large, 0, "",
                            std::to_string(payload.size()) + " bytes, at most " + std::to_string(kMaxPayload)});
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

Expected<std::vector<std::uint8_t>> encode_frame(const FrameHeader& header, std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  auto written = append_frame(out, header, payload);
  if (!written) return unexpected(written.error());
  return out;
}

namespace {
FrameHeader read_header(std::span<const std::uint8_t> bytes) {
  FrameHeader header;
  header.version = bytes[3];
  header.timestamp = static_cast<std::uint32_t>(bytes[4]) | (static_cast<std::uint32_t>(bytes[5]) << 8) |
                     (static_cast<std::uint32_t>(bytes[6]) << 16) | (static_cast<std::uint32_t>(bytes[7]) << 24);
  header.flags = bytes[8];
  header.type = static_cast<std::uint16_t>(bytes[9] | (bytes[10] << 8));
  return header;
}
}  // namespace

FrameInspection inspect_frame(std::span<const std::uint8_t> bytes, std::size_t max_frame_size) {
  FrameInspection result;
  if (bytes.size() < kLeadBytes) return result;
  const std::uint8_t length = bytes[kLengthOffset];
  if (static_cast<std::uint8_t>(length ^ bytes[kLengthCheckOffset]) != 0xFF || length < kMinLengthField) {
    result.check = FrameCheck::bad_length;
    return result;
  }
  result.size = std::size_t{length} + kLeadBytes;
  if (result.size > max_frame_size) {
    result.check = FrameCheck::oversize;
    return result;
  }
  if (bytes.size() <= kStxOffset) return result;
  if (bytes[kStxOffset] != kStartOfText) {
    result.check = FrameCheck::missing_stx;
    return result;
  }
  if (bytes.size() < result.size) return result;
  const auto frame = bytes.first(result.size);
  const std::size_t crc_at = result.size - 2;
  result.header = read_header(frame);
  result.expected_crc = clearpath_crc(frame.first(crc_at));
  result.received_crc = static_cast<std::uint16_t>(frame[crc_at] | (frame[crc_at + 1] << 8));
  result.check = result.expected_crc == result.received_crc ? FrameCheck::complete : FrameCheck::bad_crc;
  return result;
}

Expected<Frame> decode_frame(std::span<const std::uint8_t> bytes) {
  const auto bad = [](std::size_t offset, std::string why) {
    return unexpected(Error{ErrorCode::bad_frame, offset, "", std::move(why)});
  };
  if (bytes.size() < kFrameOverhead) return bad(0, "shorter than the 14-byte minimum");
  if (bytes[0] != kStartOfHeader) return bad(0, "no 0xAA start byte");
  const auto inspection = inspect_frame(bytes);
  switch (inspection.check) {
    case FrameCheck::bad_length: return bad(kLengthOffset, "LEN and ~LEN disagree, or LEN below 11");
    case FrameCheck::oversize:  // cannot happen: one LEN byte cannot announce more than kMaxFrameSize
    case FrameCheck::need_more:
      return bad(kLengthOffset, "LEN says " + std::to_string(inspection.size) + " bytes, got " +
                                    std::to_string(bytes.size()));
    case FrameCheck::missing_stx: return bad(kStxOffset, "no 0x55 after the header");
    case FrameCheck::bad_crc: return bad(inspection.size - 2, "CRC mismatch");
    case FrameCheck::complete: break;
  }
  if (bytes.size() != inspection.size)
    return bad(kLengthOffset, "LEN says " + std::to_string(inspection.size) + " bytes, got " +
                                  std::to_string(bytes.size()));
  return Frame{inspection.header, std::vector<std::uint8_t>(bytes.begin() + kFrameHeaderSize,
                                                            bytes.begin() + static_cast<std::ptrdiff_t>(inspection.size - 2))};
}

std::vector<std::span<const std::uint8_t>> split_frames(std::span<const std::uint8_t> frames) {
  std::vector<std::span<const std::uint8_t>> out;
  std::size_t at = 0;
  while (at + kLeadBytes <= frames.size()) {
    const std::size_t size = std::min(std::size_t{frames[at + kLengthOffset]} + kLeadBytes, frames.size() - at);
    out.push_back(frames.subspan(at, size));
    at += size;
  }
  return out;
}

}  // namespace jaus::clearpath
