#include "jaus/transport/ipv4.hpp"

#include <charconv>

namespace jaus::transport {

namespace {

// A decimal number with no sign, no leading '+', no spaces, within [0, max].
std::optional<std::uint32_t> parse_decimal(std::string_view text, std::uint32_t max) {
  if (text.empty() || text.size() > 10) return std::nullopt;
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || value > max) return std::nullopt;
  return value;
}

std::uint32_t mask_of(std::uint8_t prefix_length) {
  return prefix_length == 0 ? 0 : ~std::uint32_t{0} << (32 - prefix_length);
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
    if (dot == std::string_view::npos) return std::nullopt;
    const auto value = parse_decimal(text.substr(0, dot), 255);
    if (!value) return std::nullopt;
    address = (address << 8) | *value;
    text = octet < 3 ? text.substr(dot + 1) : std::string_view{};
  }
  return address;
}

std::optional<Ipv4Endpoint> parse_endpoint(std::string_view text, std::uint16_t default_port) {
  Ipv4Endpoint endpoint;
  endpoint.port = default_port;
  const std::size_t colon = text.find(':');
  if (colon != std::string_view::npos) {
    const auto port = parse_decimal(text.substr(colon + 1), 65535);
    if (!port || *port == 0) return std::nullopt;
    endpoint.port = static_cast<std::uint16_t>(*port);
    text = text.substr(0, colon);
  }
  const auto address = parse_ipv4(text);
  if (!address) return std::nullopt;
  endpoint.address = *address;
  return endpoint;
}

bool Cidr::contains(std::uint32_t address) const { return (address & mask_of(prefix_length)) == network; }

std::string to_string(const Cidr& c) { return ipv4_to_string(c.network) + "/" + std::to_string(c.prefix_length); }

std::optional<Cidr> parse_cidr(std::string_view text) {
  Cidr cidr;
  const std::size_t slash = text.find('/');
  if (slash != std::string_view::npos) {
    const auto length = parse_decimal(text.substr(slash + 1), 32);
    if (!length) return std::nullopt;
    cidr.prefix_length = static_cast<std::uint8_t>(*length);
    text = text.substr(0, slash);
  }
  const auto address = parse_ipv4(text);
  if (!address || (*address & ~mask_of(cidr.prefix_length)) != 0) return std::nullopt;
  cidr.network = *address;
  return cidr;
}

}  // namespace jaus::transport
