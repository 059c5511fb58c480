// IPv4 endpoints and CIDR ranges as plain values: what the configuration and
// the command line write ("127.0.0.2:3794", "10.0.0.0/8"), independent of
// the socket library.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace jaus::transport {

inline constexpr std::uint16_t kJausPort = 3794;

struct Ipv4Endpoint {
  std::uint32_t address = 0;  // host byte order: 127.0.0.1 is 0x7F000001
  std::uint16_t port = kJausPort;
  auto operator<=>(const Ipv4Endpoint&) const = default;
  bool is_any() const { return address == 0; }
  bool is_multicast() const { return (address >> 28) == 0xE; }  // 224.0.0.0/4
};
std::string to_string(const Ipv4Endpoint& endpoint);
std::string ipv4_to_string(std::uint32_t address);

// "a.b.c.d" (dotted decimal, nothing else).
std::optional<std::uint32_t> parse_ipv4(std::string_view text);
// "a.b.c.d[:port]"; a missing port is `default_port`.
std::optional<Ipv4Endpoint> parse_endpoint(std::string_view text, std::uint16_t default_port = kJausPort);

struct Cidr {
  std::uint32_t network = 0;  // host byte order, host bits cleared
  std::uint8_t prefix_length = 32;
  bool operator==(const Cidr&) const = default;
  bool contains(std::uint32_t address) const;
};
std::string to_string(const Cidr& cidr);
// "a.b.c.d/len", or "a.b.c.d" for /32. Host bits set below the prefix are an error.
std::optional<Cidr> parse_cidr(std::string_view text);

}  // namespace jaus::transport
