#include <gtest/gtest.h>

#include "jaus/core/header.hpp"
#include "jaus/base/hex.hpp"

namespace jaus {
namespace {

std::vector<std::uint8_t> hex(std::string_view text) {
  auto out = parse_hex(text);
  EXPECT_TRUE(out) << out.error().message();
  return out ? *out : std::vector<std::uint8_t>{};
}

TEST(Header, DecodesEveryField) {
  // Properties 0x02F6: priority 6, ACK requested... built field by field below.
  Header h;
  h.priority = 13;
  h.ack_nak = AckNak::ack_requested;
  h.service_connection = true;
  h.experimental = true;
  h.version = kVersionRa30;
  h.command_code = 0x4402;
  h.destination = {1, 2, 33, 4};
  h.source = {5, 6, 40, 7};
  h.data_size = 4080;
  h.data_flag = DataFlag::last;
  h.sequence = 0xBEEF;
  auto bytes = encode_header(h);
  ASSERT_TRUE(bytes);
  EXPECT_EQ(to_hex(*bytes), "DD0102440421020107280605F08FEFBE");
  auto back = decode_header(*bytes);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(*back, h);
}

TEST(Header, MatchesThePeersHeaderBytes) {
  auto decoded = decode_header(hex("06020D00012101010128010201000B0A"));
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->priority, 6);
  EXPECT_EQ(decoded->version, kVersionRa32);
  EXPECT_EQ(decoded->command_code, 0x000D);
  EXPECT_EQ(decoded->destination, (Address{1, 1, 33, 1}));
  EXPECT_EQ(decoded->source, (Address{2, 1, 40, 1}));
  EXPECT_EQ(decoded->data_size, 1);
  EXPECT_EQ(decoded->sequence, 0x0A0B);
}

TEST(Header, RejectsUnsupportedVersions) {
  for (const char* text : {"06000D00012101010128010201000B0A", "06030D00012101010128010201000B0A"}) {
    auto decoded = decode_header(hex(text));
    ASSERT_FALSE(decoded);
    EXPECT_EQ(decoded.error().code, ErrorCode::unsupported_version);
    EXPECT_EQ(decoded.error().field, "version");
  }
}

TEST(Header, RejectsUnknownDataFlagsAndOversizePayloads) {
  auto flag = decode_header(hex("06020D00012101010128010201300B0A"));
  ASSERT_FALSE(flag);
  EXPECT_EQ(flag.error().code, ErrorCode::bad_data_flag);
  auto size = decode_header(hex("06020D000121010101280102F10F0B0A"));  // 0xFF1 = 4081
  ASSERT_FALSE(size);
  EXPECT_EQ(size.error().code, ErrorCode::data_size_too_large);
}

TEST(Header, PacketDataSizeMustMatchTheDatagram) {
  auto ok = decode_packet(hex("06020D00012101010128010201000B0A7B"));
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->payload.size(), 1u);
  auto shorter = decode_packet(hex("06020D00012101010128010201000B0A"));
  ASSERT_FALSE(shorter);
  EXPECT_EQ(shorter.error().code, ErrorCode::data_size_mismatch);
  auto longer = decode_packet(hex("06020D00012101010128010201000B0A7B7B"));
  ASSERT_FALSE(longer);
  EXPECT_EQ(longer.error().code, ErrorCode::data_size_mismatch);
}

TEST(Header, EveryTruncationIsAnError) {
  const auto full = hex("06020D00012101010128010201000B0A");
  for (std::size_t n = 0; n < full.size(); ++n) {
    auto decoded = decode_header(std::span(full).first(n));
    ASSERT_FALSE(decoded);
    EXPECT_EQ(decoded.error().code, ErrorCode::truncated);
  }
}

TEST(Header, EncodeRejectsFieldsOutsideTheirBits) {
  Header h;
  h.priority = 16;
  EXPECT_FALSE(encode_header(h));
  h.priority = 6;
  h.data_size = 4081;
  EXPECT_FALSE(encode_header(h));
}

TEST(Address, ParsesAndPrintsDottedForm) {
  auto a = Address::parse("1.2.33.255");
  ASSERT_TRUE(a);
  EXPECT_EQ(*a, (Address{1, 2, 33, 255}));
  EXPECT_EQ(a->to_string(), "1.2.33.255");
  EXPECT_TRUE(a->is_broadcast());
  for (const char* bad : {"", "1.2.3", "1.2.3.4.5", "1.2.3.256", "a.b.c.d", "1..3.4", "1.2.3.4 "})
    EXPECT_FALSE(Address::parse(bad)) << bad;
}

TEST(Address, BroadcastMatchesEveryIdAtItsLevel) {
  const Address component{3, 1, 33, 1};
  EXPECT_TRUE((Address{3, 255, 255, 255}.matches(component)));
  EXPECT_TRUE((Address{3, 1, 33, 1}.matches(component)));
  EXPECT_FALSE((Address{3, 2, 255, 255}.matches(component)));
}

}  // namespace
}  // namespace jaus
