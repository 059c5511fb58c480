// IPv4 endpoints and CIDR ranges as plain values: what the configuration and
// the command line write ("127.0.0.2:3794", "10.0.0.0/8"), independent of
// the socket library. The parsers refuse host names and IPv6; their errors
// name the value and what is wrong with it, ready to follow "'bind': ".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::transport {

inline constexpr std::uint16_t kJausPort = 3794;

struct Ipv4Endpoint {
  std::uint32_t address = 0;  // host byte order: 127.0.0.1 is 0x7F000001
  std::uint16_t port = kJausPort;
  auto operator<=>(const Ipv4Endpoint&) const = default;
  bool is_any() const { return address == 0; }
  bool is_multicast() const { return (address >> 28) == 0xE; }  // 224.0.0.0/4
};
std::string to_string(const Ipv4Endpoint& endpoint);  // "a.b.c.d:port"
std::string ipv4_to_string(std::uint32_t address);    // "a.b.c.d"

// "a.b.c.d": four decimal octets 0..255, no leading zeros, signs or spaces.
std::optional<std::uint32_t> parse_ipv4(std::string_view text);
// "a.b.c.d[:port]", port 1..65535 (decimal digits only); a missing port is
// `default_port`. Errors (invalid_argument), as message(): "'robot.local' is not an IPv4 address a.b.c.d (host
// names are not resolved)", "port '0' of '1.2.3.4:0' must be 1..65535", ...
Expected<Ipv4Endpoint> parse_endpoint(std::string_view text, std::uint16_t default_port = kJausPort);

struct Cidr {
  std::uint32_t network = 0;  // host byte order, host bits cleared
  std::uint8_t prefix_length = 32;  // 0..32 (more counts as 32)
  bool operator==(const Cidr&) const = default;
  bool contains(std::uint32_t address) const;  // address in host byte order
};
std::string to_string(const Cidr& cidr);  // "10.0.0.0/8"
// "a.b.c.d/prefix" (prefix 0..32) or "a.b.c.d" (/32). Host bits set below
// the prefix ("10.1.2.3/8") are an error that names the network meant.
Expected<Cidr> parse_cidr(std::string_view text);

// The networks of this host's IPv4 interfaces (address and netmask of each,
// host bits cleared), always with 127.0.0.0/8, without duplicates: what the
// word `local` in a CIDR list stands for. Read when called (getifaddrs): an
// interface that comes up later is not in an earlier answer.
std::vector<Cidr> local_networks();

}  // namespace jaus::transport
