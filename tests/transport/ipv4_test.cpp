// IPv4 addresses, endpoints and CIDR networks as the configuration and the
// command line write them: what is accepted, and the exact error for what is
// not (the configuration loader and jausd --bind show these messages).
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <utility>

#include "jaus/transport/ipv4.hpp"
#include "jaus/transport/peer.hpp"

namespace jaus::transport {

// Readable values in failure messages (found by gtest through ADL).
void PrintTo(const Ipv4Endpoint& endpoint, std::ostream* os) { *os << to_string(endpoint); }
void PrintTo(const Cidr& cidr, std::ostream* os) { *os << to_string(cidr); }
void PrintTo(const StaticPeer& peer, std::ostream* os) {
  *os << to_string(peer.endpoint) << " " << to_string(peer.framing);
}

namespace {

const std::string kNotIpv4 = " is not an IPv4 address a.b.c.d (host names are not resolved)";

// ------------------------------------------------------------ parse_ipv4

TEST(Ipv4, Parses) {
  EXPECT_EQ(parse_ipv4("127.0.0.1"), 0x7F000001u);
  EXPECT_EQ(parse_ipv4("0.0.0.0"), 0u);
  EXPECT_EQ(parse_ipv4("255.255.255.255"), 0xFFFFFFFFu);
  EXPECT_EQ(parse_ipv4("10.20.30.40"), 0x0A141E28u);
  EXPECT_EQ(parse_ipv4("192.168.100.7"), 0xC0A86407u);
  EXPECT_EQ(parse_ipv4("0.10.100.0"), 0x000A6400u);  // a lone 0 is not a leading zero
}

TEST(Ipv4, RefusesAnythingButFourPlainDecimalOctets) {
  const std::string_view bad[] = {
      // empty, missing or extra octets
      "", ".", "...", "1.2.3", "1.2.3.", ".1.2.3", "1..2.3", "1.2..3", "1.2.3.4.", "1.2.3.4.5", "127.1", "2130706433",
      // leading zeros (octal to inet_aton: 010 is 8)
      "01.2.3.4", "1.2.3.04", "1.2.3.00", "010.0.0.1", "0000.0.0.0",
      // out of range
      "256.1.1.1", "1.2.3.256", "1.2.3.999", "1.2.3.1000", "4294967296.0.0.0",
      // spaces
      " 1.2.3.4", "1.2.3.4 ", "1. 2.3.4", "1.2.3 .4", "1.2.3.4\n", "\t1.2.3.4",
      // signs
      "+1.2.3.4", "-1.2.3.4", "1.2.3.+4", "1.-2.3.4",
      // other notations, host names, IPv6
      "0x7f.0.0.1", "1.2.3.4e0", "1.2.3.a", "localhost", "robot.local", "::1", "::ffff:1.2.3.4", "1.2.3.4:3794",
      "1.2.3.4/8",
  };
  for (const auto text : bad) EXPECT_EQ(parse_ipv4(text), std::nullopt) << "'" << text << "'";
}

TEST(Ipv4, ToString) {
  EXPECT_EQ(ipv4_to_string(0x7F000001), "127.0.0.1");
  EXPECT_EQ(ipv4_to_string(0), "0.0.0.0");
  EXPECT_EQ(ipv4_to_string(0xFFFFFFFF), "255.255.255.255");
  for (const std::string_view text : {"10.20.30.40", "192.168.100.7", "0.10.100.0"})
    EXPECT_EQ(ipv4_to_string(*parse_ipv4(text)), text);
}

// ------------------------------------------------------------ parse_endpoint

TEST(Endpoint, Parses) {
  EXPECT_EQ(*parse_endpoint("127.0.0.2:3794"), (Ipv4Endpoint{0x7F000002, 3794}));
  EXPECT_EQ(*parse_endpoint("127.0.0.2"), (Ipv4Endpoint{0x7F000002, 3794}));
  EXPECT_EQ(*parse_endpoint("0.0.0.0:1"), (Ipv4Endpoint{0, 1}));
  EXPECT_EQ(*parse_endpoint("255.255.255.255:65535"), (Ipv4Endpoint{0xFFFFFFFF, 65535}));
  EXPECT_EQ(*parse_endpoint("10.0.0.1:03794"), (Ipv4Endpoint{0x0A000001, 3794}));  // a port has no octal reading
  EXPECT_EQ(*parse_endpoint("224.1.0.1:3795"), (Ipv4Endpoint{0xE0010001, 3795}));
  EXPECT_EQ(to_string(*parse_endpoint("10.0.0.1:4000")), "10.0.0.1:4000");
  EXPECT_EQ(to_string(*parse_endpoint("10.0.0.1")), "10.0.0.1:3794");
}

TEST(Endpoint, AMissingPortIsTheDefaultPort) {
  EXPECT_EQ(parse_endpoint("127.0.0.2")->port, kJausPort);
  EXPECT_EQ(parse_endpoint("127.0.0.2", 4000)->port, 4000);
  EXPECT_EQ(parse_endpoint("127.0.0.2:5000", 4000)->port, 5000);  // a written port wins
  EXPECT_EQ(parse_endpoint("127.0.0.2", 0)->port, 0);             // the caller's choice, not the text's
  EXPECT_FALSE(parse_endpoint("127.0.0.2:0", 0));                 // ...which still may not write 0
}

TEST(Endpoint, KnowsAnyAndMulticast) {
  EXPECT_TRUE(parse_endpoint("0.0.0.0")->is_any());
  EXPECT_FALSE(parse_endpoint("0.0.0.1")->is_any());
  EXPECT_TRUE(parse_endpoint("224.0.0.0")->is_multicast());
  EXPECT_TRUE(parse_endpoint("239.255.255.255")->is_multicast());
  EXPECT_FALSE(parse_endpoint("223.255.255.255")->is_multicast());
  EXPECT_FALSE(parse_endpoint("240.0.0.0")->is_multicast());
}

TEST(Endpoint, RefusesWithAMessageNamingTheValue) {
  const std::pair<std::string_view, std::string> bad[] = {
      {"", "empty address (expected a.b.c.d[:port])"},
      {"localhost", "'localhost'" + kNotIpv4},
      {"localhost:3794", "'localhost'" + kNotIpv4},
      {"robot.local:3794", "'robot.local'" + kNotIpv4},
      {"1.2.3", "'1.2.3'" + kNotIpv4},
      {"1.2.3:3794", "'1.2.3'" + kNotIpv4},
      {"1.2.3.4.5", "'1.2.3.4.5'" + kNotIpv4},
      {"256.1.1.1", "'256.1.1.1'" + kNotIpv4},
      {"1.2.3.256:3794", "'1.2.3.256'" + kNotIpv4},
      {"01.2.3.4", "'01.2.3.4'" + kNotIpv4},
      {"1..2.3", "'1..2.3'" + kNotIpv4},
      {"1.2.3.4.", "'1.2.3.4.'" + kNotIpv4},
      {"-1.2.3.4", "'-1.2.3.4'" + kNotIpv4},
      {"+1.2.3.4", "'+1.2.3.4'" + kNotIpv4},
      {" 1.2.3.4", "' 1.2.3.4'" + kNotIpv4},
      {"1.2.3.4 ", "'1.2.3.4 '" + kNotIpv4},
      {"1.2.3.4 :3794", "'1.2.3.4 '" + kNotIpv4},
      {":3794", "''" + kNotIpv4},
      {"::1", "''" + kNotIpv4},
      {"[::1]:3794", "'['" + kNotIpv4},
      {"1.2.3.4:", "port '' of '1.2.3.4:' must be 1..65535"},
      {"1.2.3.4:0", "port '0' of '1.2.3.4:0' must be 1..65535"},
      {"1.2.3.4:00000", "port '00000' of '1.2.3.4:00000' must be 1..65535"},
      {"1.2.3.4:65536", "port '65536' of '1.2.3.4:65536' must be 1..65535"},
      {"1.2.3.4:99999", "port '99999' of '1.2.3.4:99999' must be 1..65535"},
      {"1.2.3.4:003794", "port '003794' of '1.2.3.4:003794' must be 1..65535"},  // five digits at most
      {"1.2.3.4:1000000", "port '1000000' of '1.2.3.4:1000000' must be 1..65535"},
      {"1.2.3.4:+1", "port '+1' of '1.2.3.4:+1' must be 1..65535"},
      {"1.2.3.4:-1", "port '-1' of '1.2.3.4:-1' must be 1..65535"},
      {"1.2.3.4: 3794", "port ' 3794' of '1.2.3.4: 3794' must be 1..65535"},
      {"1.2.3.4:3794 ", "port '3794 ' of '1.2.3.4:3794 ' must be 1..65535"},
      {"1.2.3.4:0x10", "port '0x10' of '1.2.3.4:0x10' must be 1..65535"},
      {"1.2.3.4:http", "port 'http' of '1.2.3.4:http' must be 1..65535"},
      {"1.2.3.4:3794:1", "port '3794:1' of '1.2.3.4:3794:1' must be 1..65535"},
  };
  for (const auto& [text, why] : bad) {
    const auto result = parse_endpoint(text);
    ASSERT_FALSE(result.has_value()) << text;
    EXPECT_EQ(result.error().code, ErrorCode::invalid_argument) << text;
    EXPECT_EQ(result.error().message(), why) << text;
  }
}

TEST(Endpoint, MessagesQuoteValuesOnOneShortLine) {
  EXPECT_EQ(parse_endpoint("1.2.3.4\n").error().message(), "'1.2.3.4\\n'" + kNotIpv4);
  EXPECT_EQ(parse_endpoint("a\tb\x01").error().message(), "'a\\tb?'" + kNotIpv4);
  EXPECT_EQ(parse_endpoint(std::string(70, 'x')).error().message(), "'" + std::string(60, 'x') + "...'" + kNotIpv4);
}

// ------------------------------------------------------------ parse_cidr

TEST(Cidr, Parses) {
  EXPECT_EQ(*parse_cidr("10.0.0.0/8"), (Cidr{0x0A000000, 8}));
  EXPECT_EQ(*parse_cidr("127.0.0.1"), (Cidr{0x7F000001, 32}));
  EXPECT_EQ(*parse_cidr("127.0.0.1/32"), (Cidr{0x7F000001, 32}));
  EXPECT_EQ(*parse_cidr("0.0.0.0/0"), (Cidr{0, 0}));
  EXPECT_EQ(*parse_cidr("255.255.255.255/32"), (Cidr{0xFFFFFFFF, 32}));
  EXPECT_EQ(*parse_cidr("192.168.4.0/22"), (Cidr{0xC0A80400, 22}));
  EXPECT_EQ(*parse_cidr("10.0.0.2/31"), (Cidr{0x0A000002, 31}));
  EXPECT_EQ(*parse_cidr("128.0.0.0/1"), (Cidr{0x80000000, 1}));
  EXPECT_EQ(*parse_cidr("10.0.0.0/08"), (Cidr{0x0A000000, 8}));  // a prefix has no octal reading
  EXPECT_EQ(to_string(*parse_cidr("192.168.4.0/22")), "192.168.4.0/22");
  EXPECT_EQ(to_string(*parse_cidr("127.0.0.1")), "127.0.0.1/32");
}

TEST(Cidr, RefusesWithAMessageNamingTheValue) {
  const std::pair<std::string_view, std::string> bad[] = {
      {"", "empty network (expected a.b.c.d/prefix)"},
      {"10.0.0.0/33", "prefix length '33' of '10.0.0.0/33' must be 0..32"},
      {"10.0.0.0/99", "prefix length '99' of '10.0.0.0/99' must be 0..32"},
      {"10.0.0.0/", "prefix length '' of '10.0.0.0/' must be 0..32"},
      {"10.0.0.0/-1", "prefix length '-1' of '10.0.0.0/-1' must be 0..32"},
      {"10.0.0.0/+8", "prefix length '+8' of '10.0.0.0/+8' must be 0..32"},
      {"10.0.0.0/ 8", "prefix length ' 8' of '10.0.0.0/ 8' must be 0..32"},
      {"10.0.0.0/8 ", "prefix length '8 ' of '10.0.0.0/8 ' must be 0..32"},
      {"10.0.0.0/008", "prefix length '008' of '10.0.0.0/008' must be 0..32"},
      {"10.0.0.0/8/8", "prefix length '8/8' of '10.0.0.0/8/8' must be 0..32"},
      {"10.0.0.0/255.0.0.0", "prefix length '255.0.0.0' of '10.0.0.0/255.0.0.0' must be 0..32"},
      {"/8", "''" + kNotIpv4},
      {"10.0.0.0 /8", "'10.0.0.0 '" + kNotIpv4},
      {"010.0.0.0/8", "'010.0.0.0'" + kNotIpv4},
      {"256.0.0.0/8", "'256.0.0.0'" + kNotIpv4},
      {"10.0.0/8", "'10.0.0'" + kNotIpv4},
      {"lan/24", "'lan'" + kNotIpv4},
      {"lan", "'lan'" + kNotIpv4},
      {"::1/128", "'::1'" + kNotIpv4},
      {"10.1.0.0/8", "'10.1.0.0/8' has host bits set below the prefix (the network is 10.0.0.0/8)"},
      {"10.1.2.3/8", "'10.1.2.3/8' has host bits set below the prefix (the network is 10.0.0.0/8)"},
      {"192.168.1.1/24", "'192.168.1.1/24' has host bits set below the prefix (the network is 192.168.1.0/24)"},
      {"10.0.0.3/31", "'10.0.0.3/31' has host bits set below the prefix (the network is 10.0.0.2/31)"},
      {"1.2.3.4/0", "'1.2.3.4/0' has host bits set below the prefix (the network is 0.0.0.0/0)"},
  };
  for (const auto& [text, why] : bad) {
    const auto result = parse_cidr(text);
    ASSERT_FALSE(result.has_value()) << text;
    EXPECT_EQ(result.error().code, ErrorCode::invalid_argument) << text;
    EXPECT_EQ(result.error().message(), why) << text;
  }
}

// ------------------------------------------------------------ Cidr::contains

TEST(Cidr, SlashZeroContainsEverything) {
  const Cidr all = *parse_cidr("0.0.0.0/0");
  for (const std::uint32_t address : {0u, 1u, 0x7F000001u, 0x80000000u, 0xE0010001u, 0xFFFFFFFFu})
    EXPECT_TRUE(all.contains(address)) << ipv4_to_string(address);
}

TEST(Cidr, SlashThirtyTwoContainsOnlyItsAddress) {
  const Cidr host = *parse_cidr("127.0.0.2");
  EXPECT_TRUE(host.contains(0x7F000002));
  EXPECT_FALSE(host.contains(0x7F000001));
  EXPECT_FALSE(host.contains(0x7F000003));
  EXPECT_FALSE(host.contains(0xFF000002));
  EXPECT_FALSE(host.contains(0));
  const Cidr broadcast = *parse_cidr("255.255.255.255/32");
  EXPECT_TRUE(broadcast.contains(0xFFFFFFFF));
  EXPECT_FALSE(broadcast.contains(0xFFFFFFFE));
}

TEST(Cidr, SlashEightContainsItsNetworkOnly) {
  const Cidr ten = *parse_cidr("10.0.0.0/8");
  EXPECT_TRUE(ten.contains(0x0A000000));   // 10.0.0.0
  EXPECT_TRUE(ten.contains(0x0A010203));   // 10.1.2.3
  EXPECT_TRUE(ten.contains(0x0AFFFFFF));   // 10.255.255.255
  EXPECT_FALSE(ten.contains(0x09FFFFFF));  // 9.255.255.255
  EXPECT_FALSE(ten.contains(0x0B000000));  // 11.0.0.0
  EXPECT_FALSE(ten.contains(0x8A000000));  // 138.0.0.0: the top bit is in the prefix too
}

TEST(Cidr, OtherPrefixes) {
  const Cidr lan = *parse_cidr("192.168.1.0/24");
  EXPECT_TRUE(lan.contains(0xC0A80100));
  EXPECT_TRUE(lan.contains(0xC0A801FF));
  EXPECT_FALSE(lan.contains(0xC0A80200));
  EXPECT_FALSE(lan.contains(0xC0A800FF));
  const Cidr pair = *parse_cidr("10.0.0.2/31");
  EXPECT_TRUE(pair.contains(0x0A000002));
  EXPECT_TRUE(pair.contains(0x0A000003));
  EXPECT_FALSE(pair.contains(0x0A000001));
  EXPECT_FALSE(pair.contains(0x0A000004));
  const Cidr top = *parse_cidr("128.0.0.0/1");
  EXPECT_TRUE(top.contains(0x80000000));
  EXPECT_TRUE(top.contains(0xFFFFFFFF));
  EXPECT_FALSE(top.contains(0x7FFFFFFF));
}

TEST(Cidr, ValuesBuiltByHandAreReadLeniently) {
  // parse_cidr never makes these; a Cidr written in code still means its network.
  const Cidr host_bits{0x0A010203, 8};  // 10.1.2.3/8 = 10.0.0.0/8
  EXPECT_TRUE(host_bits.contains(0x0A000001));
  EXPECT_FALSE(host_bits.contains(0x0B000001));
  const Cidr too_long{0x7F000001, 40};  // counts as /32
  EXPECT_TRUE(too_long.contains(0x7F000001));
  EXPECT_FALSE(too_long.contains(0x7F000002));
}

// ------------------------------------------------------------ StaticPeer

TEST(StaticPeer, ComparesEndpointAndFraming) {
  const StaticPeer a{*parse_endpoint("127.0.0.2"), Framing::opc};
  EXPECT_EQ(a, (StaticPeer{Ipv4Endpoint{0x7F000002, 3794}, Framing::opc}));
  EXPECT_NE(a, (StaticPeer{Ipv4Endpoint{0x7F000002, 3794}, Framing::judp}));
  EXPECT_NE(a, (StaticPeer{Ipv4Endpoint{0x7F000002, 3795}, Framing::opc}));
  EXPECT_EQ(StaticPeer{}.framing, Framing::opc);
}

}  // namespace
}  // namespace jaus::transport
