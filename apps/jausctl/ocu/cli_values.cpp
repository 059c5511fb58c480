#include "cli_values.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "jaus/messages/catalogue.hpp"

namespace jausctl::ocu {

namespace {

using jaus::unexpected;

bool parse_hex_u32(std::string_view text, std::uint32_t& out) {
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) text.remove_prefix(2);
  if (text.empty() || text.size() > 8) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out, 16);
  return ec == std::errc{} && end == text.data() + text.size();
}

}  // namespace

Parsed<jaus::Address> parse_address(std::string_view text, bool allow_broadcast) {
  const auto address = jaus::Address::parse(text);
  if (!address)
    return invalid("bad address '" + std::string(text) + "': expected S.N.C.I (subsystem.node.component.instance)");
  if (!address->is_valid())
    return invalid("bad address '" + std::string(text) + "': 0 is not a valid ID at any level");
  if (!allow_broadcast && address->is_broadcast())
    return invalid("bad address '" + std::string(text) + "': 255 (broadcast) is not allowed here");
  return *address;
}

Parsed<std::uint16_t> parse_message_code(std::string_view text) {
  std::uint32_t value = 0;
  if (parse_hex_u32(text, value) && value <= 0xFFFF) {
    if (!jaus::msg::find_message(jaus::wire::Dialect::ra, static_cast<std::uint16_t>(value)))
      return invalid("unknown message code " + code_text(static_cast<std::uint16_t>(value)) +
                        " (jausctl msg list shows every code)");
    return static_cast<std::uint16_t>(value);
  }
  if (const auto* info = jaus::msg::find_message(jaus::wire::Dialect::ra, text)) return info->code;
  return invalid("unknown message '" + std::string(text) +
                    "': expected a code such as 0x2002 or a name such as \"Query Component Status\"");
}

Parsed<std::uint32_t> parse_presence_vector(std::string_view text) {
  std::uint32_t value = 0;
  if (!parse_hex_u32(text, value))
    return invalid("bad presence vector '" + std::string(text) + "': expected hex such as 0x1F (at most 32 bits)");
  return value;
}

Parsed<std::uint8_t> parse_authority(std::string_view text) {
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || value > 255)
    return invalid("bad authority '" + std::string(text) + "': expected 0..255");
  return static_cast<std::uint8_t>(value);
}

Parsed<double> parse_rate_hz(std::string_view text) {
  constexpr double kMaxRate = 1092;  // Create Service Connection: u16 scaled over [0, 1092] Hz
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || !(value > 0) || value > kMaxRate)
    return invalid("bad rate '" + std::string(text) + "': expected Hz, more than 0 and at most 1092");
  return value;
}

Parsed<std::uint64_t> parse_count(std::string_view text) {
  std::uint64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || value == 0)
    return invalid("bad count '" + std::string(text) + "': expected 1 or more");
  return value;
}

Parsed<jaus::rt::Duration> parse_seconds(std::string_view text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  constexpr double kDay = 86400;
  if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value) || value <= 0 || value > kDay)
    return invalid("bad duration '" + std::string(text) + "': expected seconds, more than 0 and at most 86400");
  return std::chrono::duration_cast<jaus::rt::Duration>(std::chrono::duration<double>(value));
}

Parsed<jaus::transport::Ipv4Endpoint> parse_endpoint_text(std::string_view text, std::uint16_t default_port,
                                                          bool allow_port_zero) {
  // transport::parse_endpoint refuses port 0 (no peer lives there); a bind
  // address may ask for any free port with it, so the port is read here.
  const auto bad = [&](const std::string& why) {
    return invalid("bad endpoint '" + std::string(text) + "': " + why);
  };
  std::string_view host = text;
  std::uint32_t port = default_port;
  if (const auto colon = text.find(':'); colon != std::string_view::npos) {
    host = text.substr(0, colon);
    const std::string_view digits = text.substr(colon + 1);
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), port);
    if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size() || port > 65535)
      return bad("port must be 0..65535");
    if (port == 0 && !allow_port_zero) return bad("port 0 is not a peer's port");
  }
  const auto address = jaus::transport::parse_ipv4(host);
  if (!address) return bad("expected an IPv4 address a.b.c.d[:port]");
  return jaus::transport::Ipv4Endpoint{*address, static_cast<std::uint16_t>(port)};
}

Parsed<jaus::transport::Ipv4Endpoint> parse_multicast_group(std::string_view text) {
  auto group = parse_endpoint_text(text, jaus::transport::kJausPort, false);
  if (!group) return jaus::unexpected(group.error());
  if (!group->is_multicast())
    return invalid("bad multicast group '" + std::string(text) + "': expected 224.0.0.0..239.255.255.255[:port]");
  return *group;
}

Parsed<PeerOptions> parse_peers(const std::vector<std::string>& to, std::string_view multicast) {
  PeerOptions peers;
  if (!multicast.empty()) {
    auto group = parse_multicast_group(multicast);
    if (!group) return invalid("--multicast: " + group.error().message());
    peers.multicast = *group;
  }
  std::vector<std::string> texts = to;
  if (texts.empty() && !peers.multicast) texts.emplace_back(kDefaultPeer);
  for (const auto& text : texts) {
    auto endpoint = parse_endpoint_text(text, jaus::transport::kJausPort, false);
    if (!endpoint) return invalid("--to: " + endpoint.error().message());
    peers.to.push_back(*endpoint);
  }
  return peers;
}

Parsed<jaus::transport::Framing> parse_framing(std::string_view text) {
  if (text == "opc") return jaus::transport::Framing::opc;
  if (text == "judp") return jaus::transport::Framing::judp;
  return invalid("bad framing '" + std::string(text) + "': expected opc or judp");
}

}  // namespace jausctl::ocu
