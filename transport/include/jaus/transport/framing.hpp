// The two datagram framings RA 3.x nodes use on UDP (docs/wire-format.md):
//   OPC  : "JAUS01.0" then the JAUS message (16-byte header + payload);
//   JUDP : 0x01 (transport version), 0x00 (header compression), 0x00
//          (compression flags), message length as a big-endian u16, then
//          the message.
// Sans-I/O: bytes in, the JAUS message (or why the datagram is not one) out.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "jaus/base/expected.hpp"
#include "jaus/core/header.hpp"

namespace jaus::transport {

// as5669a: a complete SAE JAUS datagram, sent as it is (no prefix).
enum class Framing : std::uint8_t { opc, judp, as5669a };
std::string_view to_string(Framing framing);

inline constexpr std::array<std::uint8_t, 8> kOpcPrefix = {'J', 'A', 'U', 'S', '0', '1', '.', '0'};
inline constexpr std::size_t kJudpPrefixSize = 5;
inline constexpr std::size_t kMaxPrefixSize = 8;
// Nothing larger than the OPC prefix, a header and a full payload is JAUS.
inline constexpr std::size_t kMaxDatagramSize = kMaxPrefixSize + kHeaderSize + kMaxPayloadSize;

// Why a datagram was dropped; each reason has its own counter.
enum class DropReason : std::uint8_t {
  unknown_framing,  // neither prefix: not JAUS
  truncated,        // shorter than a prefix and a header
  length_mismatch,  // JUDP length or the header's data size disagrees with the datagram
  bad_header,       // header fields out of range (version, data size)
  oversized,        // larger than any JAUS datagram
  not_allowed,      // source outside the allow-list
  from_self,        // our own multicast coming back
  invalid_source,   // a source ID with a 0 (invalid) or 255 (broadcast) octet
  route_claim,      // a node ID already heard from another live endpoint (spoofed, or two peers with one ID)
  relayed_copy,     // a configured peer relayed a message of a node we hear directly: a duplicate
  jss_malformed,    // first byte 0x02 (AS5669A) but not a valid AS5669A datagram
  jss_off,          // an AS5669A datagram while the node has no JSS face
  alias_source,     // an RA source in the JSS clients' alias subsystem: only the JSS face speaks for it
  count_            // number of reasons
};
std::string_view to_string(DropReason reason);

struct Unframed {
  Framing framing;
  PacketView packet;  // header decoded, payload a view into the datagram
};

// Detects the framing, checks the framing's length and the JAUS header. An
// error's offset is in the datagram ("offset 3: data size mismatch (JUDP
// length 40, datagram carries 36 bytes)").
Expected<Unframed> unframe(std::span<const std::uint8_t> datagram);
// The counter an unframe() error counts in.
DropReason drop_reason(const Error& unframe_error);

// The bytes that go before a message of `message_size` bytes (header included).
struct FramePrefix {
  std::array<std::uint8_t, kMaxPrefixSize> bytes{};
  std::size_t size = 0;
  std::span<const std::uint8_t> view() const { return std::span(bytes).first(size); }
};
FramePrefix frame_prefix(Framing framing, std::size_t message_size);

}  // namespace jaus::transport
