// AS5669A datagrams (docs/jss.md, "The bytes on the wire"): framing only; the contents are
// left to the JSS message codec.
#include "jaus/jss/judp.hpp"

#include <algorithm>
#include <string>

#include "jaus/base/hex.hpp"
#include "jaus/core/byte_io.hpp"

namespace jaus::jss {
namespace {

// Byte 1: bits 0-5 message type, bits 6-7 header compression. Sources
// disagree on the HC bits (docs/jss.md, "The bytes on the wire"), so bits 0-1 are read as HC too:
// nobody sends either, and guessing would misplace every later field.
constexpr std::uint8_t kHcBitsEitherReading = 0xC3;
constexpr std::uint8_t kMessageTypeMask = 0x3F;

// Offsets inside one transport message, from its type byte.
constexpr std::size_t kSizeAt = 1;
constexpr std::size_t kPropertiesAt = 3;
constexpr std::size_t kDestinationAt = 4;
constexpr std::size_t kSourceAt = 8;
constexpr std::size_t kContentsAt = 12;

Unexpected<Error> fail(ErrorCode code, std::size_t offset, std::string_view field, std::string detail) {
  return unexpected(Error{code, offset, std::string(field), std::move(detail)});
}

std::uint16_t u16_at(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::uint16_t>(d[at] | (d[at + 1] << 8));
}
std::uint32_t u32_at(std::span<const std::uint8_t> d, std::size_t at) {
  return static_cast<std::uint32_t>(d[at]) | (static_cast<std::uint32_t>(d[at + 1]) << 8) |
         (static_cast<std::uint32_t>(d[at + 2]) << 16) | (static_cast<std::uint32_t>(d[at + 3]) << 24);
}

std::uint8_t properties_byte(const JudpHeader& h) {
  return static_cast<std::uint8_t>((static_cast<unsigned>(h.priority) & 3u) |
                                   ((static_cast<unsigned>(h.broadcast) & 3u) << 2) |
                                   ((static_cast<unsigned>(h.ack_nak) & 3u) << 4) |
                                   ((static_cast<unsigned>(h.data_flag) & 3u) << 6));
}

}  // namespace

Expected<std::vector<JudpPacket>> decode_judp_datagram(std::span<const std::uint8_t> datagram) {
  if (datagram.empty()) return fail(ErrorCode::truncated, 0, "version", "empty datagram");
  if (datagram[0] != kAs5669aVersion)
    return fail(ErrorCode::unsupported_version, 0, "version",
                "0x" + to_hex(datagram.first(1)) + ", AS5669A is 0x02");
  std::vector<JudpPacket> packets;
  std::size_t at = 1;
  do {
    const std::size_t left = datagram.size() - at;
    if (left < kMinDataSize)
      return fail(ErrorCode::truncated, at, "header",
                  "a transport message needs at least 14 bytes, " + std::to_string(left) + " left");
    const std::uint8_t type_byte = datagram[at];
    if ((type_byte & kHcBitsEitherReading) != 0)
      return fail(ErrorCode::bad_frame, at, "message_type",
                  "header compression flags set (byte 0x" + to_hex(datagram.subspan(at, 1)) + "): not supported");
    if ((type_byte & kMessageTypeMask) != 0)
      return fail(ErrorCode::unknown_message, at, "message_type",
                  "message type " + std::to_string(type_byte & kMessageTypeMask) + ", only 0 (JAUS) is defined");
    const std::size_t data_size = u16_at(datagram, at + kSizeAt);
    if (data_size < kMinDataSize)
      return fail(ErrorCode::bad_frame, at + kSizeAt, "data_size",
                  std::to_string(data_size) + " is below the minimum 14");
    if (data_size > left)
      return fail(ErrorCode::data_size_mismatch, at + kSizeAt, "data_size",
                  std::to_string(data_size) + " but " + std::to_string(left) + " bytes left in the datagram");
    const std::uint8_t props = datagram[at + kPropertiesAt];
    JudpPacket packet;
    packet.header.message_type = 0;
    packet.header.priority = static_cast<JudpPriority>(props & 3u);
    packet.header.broadcast = static_cast<JudpBroadcast>((props >> 2) & 3u);
    packet.header.ack_nak = static_cast<JudpAckNak>((props >> 4) & 3u);
    packet.header.data_flag = static_cast<JudpDataFlag>((props >> 6) & 3u);
    if (packet.header.broadcast == static_cast<JudpBroadcast>(3))
      return fail(ErrorCode::bad_value, at + kPropertiesAt, "broadcast", "broadcast flag 3 is not defined");
    packet.header.destination = JssId::unpack(u32_at(datagram, at + kDestinationAt));
    packet.header.source = JssId::unpack(u32_at(datagram, at + kSourceAt));
    const std::size_t contents_size = data_size - kMinDataSize;
    packet.contents = datagram.subspan(at + kContentsAt, contents_size);
    packet.header.sequence = u16_at(datagram, at + kContentsAt + contents_size);
    packets.push_back(packet);
    at += data_size;
  } while (at < datagram.size());
  return packets;
}

Expected<std::size_t> encode_judp_datagram(const JudpHeader& header, std::span<const std::uint8_t> contents,
                                           std::span<std::uint8_t> out) {
  const std::size_t data_size = kMinDataSize + contents.size();
  if (data_size > 0xFFFF)
    return fail(ErrorCode::payload_too_large, 0, "contents",
                std::to_string(contents.size()) + " bytes; one transport message carries at most 65521");
  if (header.message_type != 0)
    return fail(ErrorCode::bad_value, 1, "message_type", "only message type 0 (JAUS) is sent");
  if (header.broadcast == static_cast<JudpBroadcast>(3))
    return fail(ErrorCode::bad_value, 4, "broadcast", "broadcast flag 3 is not defined");
  const std::size_t total = 1 + data_size;
  if (out.size() < total)
    return fail(ErrorCode::output_too_small, 0, {},
                "needs " + std::to_string(total) + " bytes, " + std::to_string(out.size()) + " given");
  ByteWriter w(out);
  w.write(kAs5669aVersion);
  w.write(std::uint8_t{0});
  w.write(static_cast<std::uint16_t>(data_size));
  w.write(properties_byte(header));
  w.write(header.destination.packed());
  w.write(header.source.packed());
  w.write_bytes(contents);
  w.write(header.sequence);
  return total;
}

std::vector<std::uint8_t> make_judp_datagram(const JudpHeader& header, std::span<const std::uint8_t> contents) {
  std::vector<std::uint8_t> out(1 + kMinDataSize + contents.size());
  auto size = encode_judp_datagram(header, contents, out);
  if (!size) return {};
  out.resize(*size);
  return out;
}

std::uint16_t message_id_of(std::span<const std::uint8_t> contents) {
  if (contents.size() < 2) return 0;
  return static_cast<std::uint16_t>(contents[0] | (contents[1] << 8));
}

JudpPriority jss_priority_from_ra(std::uint8_t ra_priority) {
  if (ra_priority < 3) return JudpPriority::low;
  return static_cast<JudpPriority>(std::min(3, (ra_priority - 3) / 3));
}

std::uint8_t ra_priority_from_jss(JudpPriority priority) {
  return static_cast<std::uint8_t>(3 * static_cast<unsigned>(priority) + 3);
}

std::string_view to_string(JudpAckNak flag) {
  switch (flag) {
    case JudpAckNak::none: return "none";
    case JudpAckNak::ack_requested: return "ack_requested";
    case JudpAckNak::nak: return "nak";
    case JudpAckNak::ack: return "ack";
  }
  return "?";
}

std::string_view to_string(JudpDataFlag flag) {
  switch (flag) {
    case JudpDataFlag::single: return "single";
    case JudpDataFlag::first: return "first";
    case JudpDataFlag::middle: return "middle";
    case JudpDataFlag::last: return "last";
  }
  return "?";
}

}  // namespace jaus::jss
