// The values the OCU commands take on the command line (addresses, command
// codes, durations, endpoints, presence vectors), parsed without I/O. Each
// parser returns the value or one line saying what is wrong with the text.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"
#include "jaus/ocu/names.hpp"

namespace jausctl::ocu {

// jausctl's OCU commands are built on the OCU library.
using namespace jaus::ocu;

// A parsed value, or why the text is not one (invalid_argument, one line).
template <class T>
using Parsed = jaus::Expected<T>;
inline jaus::Unexpected<jaus::Error> invalid(std::string why) {
  return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument, std::move(why)));
}

// "S.N.C.I", each 1..254, or 255 (broadcast) where `allow_broadcast`.
Parsed<jaus::Address> parse_address(std::string_view text, bool allow_broadcast);

// "0x4402", "4402" (hex) or a message name from the catalogue ("Report Global Pose").
Parsed<std::uint16_t> parse_message_code(std::string_view text);

// "0x1F" or "1F": a presence vector of up to 32 bits.
Parsed<std::uint32_t> parse_presence_vector(std::string_view text);

// An authority (Request Component Control): 0..255.
Parsed<std::uint8_t> parse_authority(std::string_view text);

// A service connection rate in Hz: more than 0 and at most 1092 (its wire range).
Parsed<double> parse_rate_hz(std::string_view text);

// A count of reports: 1 or more.
Parsed<std::uint64_t> parse_count(std::string_view text);

// Seconds as a decimal number ("1", "0.25"), > 0 and at most a day.
Parsed<jaus::rt::Duration> parse_seconds(std::string_view text);

// "a.b.c.d[:port]"; a missing port is `default_port`. Port 0 (any free port)
// is accepted only where `allow_port_zero` (a bind address, not a peer).
Parsed<jaus::transport::Ipv4Endpoint> parse_endpoint_text(std::string_view text, std::uint16_t default_port,
                                                          bool allow_port_zero);

// "a.b.c.d[:port]", a multicast group (224.0.0.0/4); a missing port is 3794.
Parsed<jaus::transport::Ipv4Endpoint> parse_multicast_group(std::string_view text);

// Where an OCU command reaches its nodes: the static peers (--to) and the
// multicast group (--multicast). No --to means 127.0.0.1:3794, but with
// --multicast it means the group alone (discovery with multicast only).
struct PeerOptions {
  std::vector<jaus::transport::Ipv4Endpoint> to;
  std::optional<jaus::transport::Ipv4Endpoint> multicast;
};
inline constexpr std::string_view kDefaultPeer = "127.0.0.1:3794";
Parsed<PeerOptions> parse_peers(const std::vector<std::string>& to, std::string_view multicast);

// "opc" or "judp".
Parsed<jaus::transport::Framing> parse_framing(std::string_view text);

}  // namespace jausctl::ocu
