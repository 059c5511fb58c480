// AS5669A datagrams (docs/jss.md, "The bytes on the wire"): its worked
// example and the IOP node manager's query byte for byte, several transport
// messages per datagram, ACKs, and every malformed framing an error with its
// offset.
#include <gtest/gtest.h>

#include "jaus/jss/all.hpp"
#include "jss_bytes.hpp"

namespace jaus::test::jss_judp {

using namespace jaus::jss;
namespace msg = jaus::jss::msg;

// The worked example: Query Identification type 2, 42.1.1 -> 1.1.1, normal priority, sequence 0.
const char* const kWorkedExample = "02 00 11 00 01 01 01 01 00 01 01 2a 00 00 2b 02 00 00";
// As fkie's IOP node manager sends it: component query from 150.64.200 to all, broadcast 2, sequence 3565.
const char* const kNmVector = "02 00 11 00 09 ff ff ff ff c8 40 96 00 00 2b 04 ed 0d";

TEST(Judp, WorkedExampleDecodes) {
  const auto bytes = hex_bytes(kWorkedExample);
  const auto packets = decode_judp_datagram(bytes);
  ASSERT_TRUE(packets) << packets.error().message();
  ASSERT_EQ(packets->size(), 1u);
  const auto& p = (*packets)[0];
  EXPECT_EQ(p.header.message_type, 0);
  EXPECT_EQ(p.header.priority, JudpPriority::normal);
  EXPECT_EQ(p.header.broadcast, JudpBroadcast::none);
  EXPECT_EQ(p.header.ack_nak, JudpAckNak::none);
  EXPECT_EQ(p.header.data_flag, JudpDataFlag::single);
  EXPECT_EQ(p.header.destination, (JssId{1, 1, 1}));
  EXPECT_EQ(p.header.source, (JssId{42, 1, 1}));
  EXPECT_EQ(p.header.sequence, 0);
  EXPECT_EQ(message_id_of(p.contents), 0x2B00);
  const auto query = decode_contents<msg::QueryIdentification>(p.contents);
  ASSERT_TRUE(query);
  EXPECT_EQ(query->query_type, msg::identification::kSubsystem);
}

TEST(Judp, WorkedExampleEncodes) {
  JudpHeader h;
  h.destination = {1, 1, 1};
  h.source = {42, 1, 1};
  const auto contents = encode_contents(msg::QueryIdentification{msg::identification::kSubsystem});
  EXPECT_EQ(make_judp_datagram(h, contents), hex_bytes(kWorkedExample));
}

TEST(Judp, NodeManagerVector) {
  const auto bytes = hex_bytes(kNmVector);
  const auto packets = decode_judp_datagram(bytes);
  ASSERT_TRUE(packets) << packets.error().message();
  const auto& h = (*packets)[0].header;
  EXPECT_EQ(h.broadcast, JudpBroadcast::global);
  EXPECT_EQ(h.destination, (JssId{65535, 255, 255}));
  EXPECT_TRUE(h.destination.is_broadcast());
  EXPECT_EQ(h.source, (JssId{150, 64, 200}));
  EXPECT_EQ(h.sequence, 3565);
  EXPECT_EQ(make_judp_datagram(h, (*packets)[0].contents), bytes);
}

TEST(Judp, HeaderOnlyAckAndEveryFlag) {
  JudpHeader h;
  h.priority = JudpPriority::safety_critical;
  h.broadcast = JudpBroadcast::local;
  h.ack_nak = JudpAckNak::ack;
  h.data_flag = JudpDataFlag::last;
  h.destination = {42, 1, 1};
  h.source = {1, 1, 33};
  h.sequence = 0xBEEF;
  const auto ack = make_judp_datagram(h, {});
  ASSERT_EQ(ack.size(), 15u);
  EXPECT_EQ(ack[2], 14);  // data size: header-only
  EXPECT_EQ(ack[4], 0xF7);
  const auto packets = decode_judp_datagram(ack);
  ASSERT_TRUE(packets);
  EXPECT_EQ((*packets)[0].header, h);
  EXPECT_TRUE((*packets)[0].contents.empty());
  EXPECT_EQ(message_id_of((*packets)[0].contents), 0);
}

TEST(Judp, SeveralTransportMessagesInOneDatagram) {
  auto bytes = hex_bytes(kWorkedExample);
  const auto second = hex_bytes(kNmVector);
  bytes.insert(bytes.end(), second.begin() + 1, second.end());  // one version byte for both
  const auto packets = decode_judp_datagram(bytes);
  ASSERT_TRUE(packets) << packets.error().message();
  ASSERT_EQ(packets->size(), 2u);
  EXPECT_EQ((*packets)[0].header.source, (JssId{42, 1, 1}));
  EXPECT_EQ((*packets)[1].header.source, (JssId{150, 64, 200}));
}

Error decode_error(const std::vector<std::uint8_t>& bytes) {
  const auto packets = decode_judp_datagram(bytes);
  EXPECT_FALSE(packets) << to_hex(bytes);
  return packets ? Error{} : packets.error();
}

TEST(Judp, MalformedDatagramsAreErrorsWithOffsets) {
  EXPECT_EQ(decode_error({}).code, ErrorCode::truncated);

  auto opc = hex_bytes(kWorkedExample);
  opc[0] = 0x01;
  EXPECT_EQ(decode_error(opc).code, ErrorCode::unsupported_version);
  EXPECT_EQ(decode_error(opc).offset, 0u);

  for (const std::uint8_t hc : {0x40, 0x80, 0x01, 0x02}) {  // both readings of the HC bits
    auto compressed = hex_bytes(kWorkedExample);
    compressed[1] = hc;
    const auto e = decode_error(compressed);
    EXPECT_EQ(e.code, ErrorCode::bad_frame) << int(hc);
    EXPECT_EQ(e.offset, 1u);
    EXPECT_NE(e.detail.find("header compression"), std::string::npos) << e.detail;
  }
  auto type = hex_bytes(kWorkedExample);
  type[1] = 0x04;  // message type 1: reserved
  EXPECT_EQ(decode_error(type).code, ErrorCode::unknown_message);

  auto small = hex_bytes(kWorkedExample);
  small[2] = 13;
  EXPECT_EQ(decode_error(small).code, ErrorCode::bad_frame);
  EXPECT_EQ(decode_error(small).offset, 2u);
  EXPECT_EQ(decode_error(small).field, "data_size");

  auto large = hex_bytes(kWorkedExample);
  large[2] = 18;
  EXPECT_EQ(decode_error(large).code, ErrorCode::data_size_mismatch);

  auto broadcast3 = hex_bytes(kWorkedExample);
  broadcast3[4] = 0x0D;
  EXPECT_EQ(decode_error(broadcast3).code, ErrorCode::bad_value);
  EXPECT_EQ(decode_error(broadcast3).offset, 4u);

  // A short tail after a whole transport message.
  auto tail = hex_bytes(kWorkedExample);
  tail.push_back(0);
  tail.push_back(0x0E);
  EXPECT_EQ(decode_error(tail).code, ErrorCode::truncated);
  EXPECT_EQ(decode_error(tail).offset, 18u);

  // Every truncation of a valid datagram.
  const auto whole = hex_bytes(kWorkedExample);
  for (std::size_t cut = 0; cut < whole.size(); ++cut)
    EXPECT_FALSE(decode_judp_datagram(std::span(whole).first(cut))) << cut;
}

TEST(Judp, EncodeRefusesWhatCannotBeSent) {
  JudpHeader h;
  std::vector<std::uint8_t> out(10);
  EXPECT_EQ(encode_judp_datagram(h, {}, out).error().code, ErrorCode::output_too_small);
  std::vector<std::uint8_t> huge(70'000);
  std::vector<std::uint8_t> room(80'000);
  EXPECT_EQ(encode_judp_datagram(h, huge, room).error().code, ErrorCode::payload_too_large);
  h.message_type = 5;
  EXPECT_EQ(encode_judp_datagram(h, {}, room).error().code, ErrorCode::bad_value);
}

TEST(Judp, PriorityMapsAsJrmDoes) {
  EXPECT_EQ(jss_priority_from_ra(6), JudpPriority::normal);  // RA default
  EXPECT_EQ(jss_priority_from_ra(0), JudpPriority::low);
  EXPECT_EQ(jss_priority_from_ra(9), JudpPriority::high);
  EXPECT_EQ(jss_priority_from_ra(12), JudpPriority::safety_critical);
  EXPECT_EQ(jss_priority_from_ra(15), JudpPriority::safety_critical);
  EXPECT_EQ(ra_priority_from_jss(JudpPriority::normal), 6);
  EXPECT_EQ(ra_priority_from_jss(JudpPriority::safety_critical), 12);
  EXPECT_EQ(to_string(JudpAckNak::ack_requested), "ack_requested");
  EXPECT_EQ(to_string(JudpDataFlag::middle), "middle");
}

}  // namespace jaus::test::jss_judp
