// Bad input to the dissector: unknown codes and types, cut-short payloads,
// reserved presence bits, counts that cannot fit, framing lengths that lie,
// frames cut off or with a bad CRC. Each ends in the expert info that says
// so, never in a Lua error.
#include <gtest/gtest.h>

#include "jaus/base/hex.hpp"
#include "pcap_writer.hpp"
#include "tshark_session.hpp"

namespace jaus::test {
namespace {

std::vector<std::uint8_t> bytes_of(const std::string& hex) {
  auto out = jaus::parse_hex(hex);
  if (!out) throw std::runtime_error(out.error().message());
  return std::move(*out);
}

// OPC prefix + a header (priority 6, version 2, 1.1.33.1 <- 2.1.40.1) with `code` and `payload`.
std::vector<std::uint8_t> opc_message(std::uint16_t code, const std::string& payload_hex) {
  const auto payload = bytes_of(payload_hex);
  auto out = bytes_of("4A41555330312E300602");  // "JAUS01.0", properties
  out.push_back(static_cast<std::uint8_t>(code));
  out.push_back(static_cast<std::uint8_t>(code >> 8));
  const auto addresses = bytes_of("0121010101280102");
  out.insert(out.end(), addresses.begin(), addresses.end());
  out.push_back(static_cast<std::uint8_t>(payload.size()));
  out.push_back(static_cast<std::uint8_t>(payload.size() >> 8));
  out.push_back(0x0B);  // sequence
  out.push_back(0x0A);
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

struct Case {
  std::string what;
  std::vector<std::uint8_t> datagram;
  std::uint16_t port;
  std::string expert;  // the expert info's abbreviation
};

TEST(TsharkMalformed, BadInputEndsInExpertInfoNeverALuaError) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("malformed");
  // JUDP length 0x40 before a 16-byte message.
  const auto judp_bad_length = bytes_of("010000004006020244012101010128010200000B0A");
  const std::vector<Case> cases = {
      {"unknown code", opc_message(0x7777, "0102"), 3794, "jaus.unknown_code"},
      {"Report Global Pose cut short", opc_message(0x4402, "0100EC2F"), 3794, "jaus.malformed"},
      {"reserved presence bits", opc_message(0x4402, "0080"), 3794, "jaus.malformed"},
      {"records that cannot fit", opc_message(0x4B01, "C801"), 3794, "jaus.malformed"},
      {"trailing bytes", opc_message(0x0006, "01000000"), 3794, "jaus.trailing"},
      // Create Event with a lower limit (bit 2) of type 14.
      {"event limit of an unknown type", opc_message(0x01F0, "0409014B010E"), 3794, "jaus.malformed"},
      {"JUDP length that lies", judp_bad_length, 3794, "jaus.bad_header"},
      {"OPC prefix and half a header", bytes_of("4A41555330312E30060202"), 3794, "jaus.bad_header"},
      {"Clearpath type not in the document", bytes_of("AA0BF40040E20100000100551234"), 40002, "clearpath.unknown_type"},
      {"Clearpath frame cut off", bytes_of("AA11EE0040E20100000402557D00CE"), 40002, "clearpath.malformed"},
      {"Clearpath payload cut short", bytes_of("AA0EF10040E2010000040255010000ABCD"), 40002, "clearpath.malformed"},
  };
  PcapWriter pcap((session.dir() / "malformed.pcap").string());
  for (const auto& c : cases) pcap.add({{127, 0, 0, 62}, 40001}, {{127, 0, 0, 60}, c.port}, c.datagram);
  pcap.close();
  std::string failure;
  const auto layers = session.dissect(session.dir() / "malformed.pcap", {"clearpath.port:40002"}, failure);
  ASSERT_EQ(layers.size(), cases.size()) << failure;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].what);
    ASSERT_FALSE(layers[i].is_null()) << "not dissected";
    FieldValues shown;
    flatten_tshark(layers[i], "", shown);
    EXPECT_EQ(shown.count(cases[i].expert), 1u) << layers[i].dump();
    for (const auto& message : shown["_ws.expert.message"])
      EXPECT_EQ(message.dump().find("dissector error"), std::string::npos) << message.dump();
  }
}

}  // namespace
}  // namespace jaus::test
