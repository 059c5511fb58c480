// AS5669A ("JUDP") datagrams (docs/jss.md, "The bytes on the wire"): the version byte 0x02, then
// one or more transport messages, each a general transport header, the
// contents (a JSS message: u16 message ID, then its body; empty for an ACK)
// and a u16 sequence number as a trailer. Every multi-byte field is
// little-endian. Sans-I/O: bytes in, values out.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/jss/jss_id.hpp"

namespace jaus::jss {

inline constexpr std::uint8_t kAs5669aVersion = 0x02;  // first byte of the datagram
// Header after the version byte: type/HC (1), data size (2), properties (1),
// destination (4), source (4); the sequence number (2) follows the contents.
inline constexpr std::size_t kTransportHeaderSize = 12;
inline constexpr std::size_t kSequenceSize = 2;
// Data size counts from the type byte through the sequence number: 14 + contents.
inline constexpr std::size_t kMinDataSize = kTransportHeaderSize + kSequenceSize;

enum class JudpPriority : std::uint8_t { low = 0, normal = 1, high = 2, safety_critical = 3 };
enum class JudpBroadcast : std::uint8_t { none = 0, local = 1, global = 2 };
enum class JudpAckNak : std::uint8_t { none = 0, ack_requested = 1, nak = 2, ack = 3 };
enum class JudpDataFlag : std::uint8_t { single = 0, first = 1, middle = 2, last = 3 };

struct JudpHeader {
  std::uint8_t message_type = 0;  // 0: a JAUS message (1-32 reserved)
  JudpPriority priority = JudpPriority::normal;
  JudpBroadcast broadcast = JudpBroadcast::none;
  JudpAckNak ack_nak = JudpAckNak::none;
  JudpDataFlag data_flag = JudpDataFlag::single;
  JssId destination;
  JssId source;
  std::uint16_t sequence = 0;
  bool operator==(const JudpHeader&) const = default;
};

// One transport message of a received datagram; `contents` views the datagram.
struct JudpPacket {
  JudpHeader header;
  std::span<const std::uint8_t> contents;
};

// Every transport message of a datagram (several back to back are accepted;
// we send one per datagram). Errors carry the byte offset in the datagram:
// not version 0x02, header compression (byte 1 bits 6-7 or 0-1 set: nobody
// sends it and its bit position is disputed: docs/jss.md), a data size
// below 14 or beyond the datagram, a message type other than 0.
Expected<std::vector<JudpPacket>> decode_judp_datagram(std::span<const std::uint8_t> datagram);

// Writes version byte, header, contents and sequence number into `out`
// (kTransportHeaderSize + 1 + contents + 2 bytes); returns the size.
Expected<std::size_t> encode_judp_datagram(const JudpHeader& header, std::span<const std::uint8_t> contents,
                                           std::span<std::uint8_t> out);
std::vector<std::uint8_t> make_judp_datagram(const JudpHeader& header, std::span<const std::uint8_t> contents);

// The JSS message ID of contents (its first two bytes); 0 when shorter.
std::uint16_t message_id_of(std::span<const std::uint8_t> contents);

// RA priority (0-15) <-> JSS (0-3), as JRM maps them (docs/jss.md, "The bytes on the wire").
JudpPriority jss_priority_from_ra(std::uint8_t ra_priority);
std::uint8_t ra_priority_from_jss(JudpPriority priority);

std::string_view to_string(JudpAckNak flag);
std::string_view to_string(JudpDataFlag flag);

}  // namespace jaus::jss
