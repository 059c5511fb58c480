#include "jaus/transport/ipv4.hpp"

#include "jaus/base/quoted.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

namespace jaus::transport {

namespace {
Unexpected<Error> invalid(std::string why) { return unexpected(make_error(ErrorCode::invalid_argument, std::move(why))); }
}  // namespace

namespace {

bool all_digits(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// Decimal digits only (no sign, no spaces), at most `max_digits` of them.
std::optional<std::uint32_t> parse_digits(std::string_view text, std::size_t max_digits) {
  if (text.empty() || text.size() > max_digits || !all_digits(text)) return std::nullopt;
  std::uint32_t value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

std::uint32_t mask_of(std::uint8_t prefix_length) {
  return prefix_length == 0 ? 0 : ~std::uint32_t{0} << (32 - std::min<std::uint8_t>(prefix_length, 32));
}


std::string not_ipv4(std::string_view host) {
  return jaus::quoted(host) + " is not an IPv4 address a.b.c.d (host names are not resolved)";
}

}  // namespace

std::string ipv4_to_string(std::uint32_t a) {
  return std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 0xFF) + "." + std::to_string((a >> 8) & 0xFF) +
         "." + std::to_string(a & 0xFF);
}

std::string to_string(const Ipv4Endpoint& e) { return ipv4_to_string(e.address) + ":" + std::to_string(e.port); }

std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
  std::uint32_t address = 0;
  for (int octet = 0; octet < 4; ++octet) {
    const std::size_t dot = octet < 3 ? text.find('.') : text.size();
    if (dot == std::string_view::npos) return std::nullopt;  // fewer than four octets
    const std::string_view part = text.substr(0, dot);
    if (part.size() > 1 && part.front() == '0') return std::nullopt;  // leading zero: octal to some parsers
    const auto value = parse_digits(part, 3);
    if (!value || *value > 255) return std::nullopt;  // also a fifth octet: '.' is not a digit
    address = (address << 8) | *value;
    text = octet < 3 ? text.substr(dot + 1) : std::string_view{};
  }
  return address;
}

Expected<Ipv4Endpoint> parse_endpoint(std::string_view text, std::uint16_t default_port) {
  if (text.empty()) return invalid(("empty address (expected a.b.c.d[:port])"));
  const std::size_t colon = text.find(':');
  const std::string_view host = text.substr(0, colon);
  const auto address = parse_ipv4(host);
  if (!address) return invalid(not_ipv4(host));
  Ipv4Endpoint endpoint{*address, default_port};
  if (colon != std::string_view::npos) {
    const std::string_view port = text.substr(colon + 1);
    const auto value = parse_digits(port, 5);
    if (!value || *value < 1 || *value > 65535)
      return invalid("port " + jaus::quoted(port) + " of " + jaus::quoted(text) + " must be 1..65535");
    endpoint.port = static_cast<std::uint16_t>(*value);
  }
  return endpoint;
}

bool Cidr::contains(std::uint32_t address) const {
  const std::uint32_t mask = mask_of(prefix_length);
  return (address & mask) == (network & mask);
}

std::string to_string(const Cidr& c) { return ipv4_to_string(c.network) + "/" + std::to_string(c.prefix_length); }

Expected<Cidr> parse_cidr(std::string_view text) {
  if (text.empty()) return invalid(("empty network (expected a.b.c.d/prefix)"));
  const std::size_t slash = text.find('/');
  const std::string_view host = text.substr(0, slash);
  const auto address = parse_ipv4(host);
  if (!address) return invalid(not_ipv4(host));
  Cidr cidr{*address, 32};
  if (slash != std::string_view::npos) {
    const std::string_view prefix = text.substr(slash + 1);
    const auto value = parse_digits(prefix, 2);
    if (!value || *value > 32)
      return invalid("prefix length " + jaus::quoted(prefix) + " of " + jaus::quoted(text) + " must be 0..32");
    cidr.prefix_length = static_cast<std::uint8_t>(*value);
  }
  const std::uint32_t mask = mask_of(cidr.prefix_length);
  if ((cidr.network & mask) != cidr.network)
    return invalid(jaus::quoted(text) + " has host bits set below the prefix (the network is " +
                      to_string(Cidr{cidr.network & mask, cidr.prefix_length}) + ")");
  return cidr;
}

std::vector<Cidr> local_networks() {
  std::vector<Cidr> out{Cidr{0x7F000000, 8}};
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) != 0) return out;  // loopback at least
  for (const ifaddrs* it = list; it != nullptr; it = it->ifa_next) {
    if (it->ifa_addr == nullptr || it->ifa_netmask == nullptr || it->ifa_addr->sa_family != AF_INET) continue;
    sockaddr_in address{}, netmask{};
    std::memcpy(&address, it->ifa_addr, sizeof address);  // no alignment assumed of the kernel's sockaddr
    std::memcpy(&netmask, it->ifa_netmask, sizeof netmask);
    const std::uint32_t mask = ntohl(netmask.sin_addr.s_addr);
    const auto prefix = static_cast<std::uint8_t>(std::popcount(mask));
    const Cidr cidr{ntohl(address.sin_addr.s_addr) & mask_of(prefix), prefix};
    if (std::find(out.begin(), out.end(), cidr) == out.end()) out.push_back(cidr);
  }
  ::freeifaddrs(list);
  return out;
}

}  // namespace jaus::transport
