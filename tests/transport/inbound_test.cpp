// One received datagram decoded once, whatever its framing (inbound.hpp):
// what the UDP link's one receive path reads of RA (OPC, JUDP) and AS5669A
// datagrams alike, and the reasons it drops the rest.
#include <gtest/gtest.h>

#include "jaus/transport/inbound.hpp"

namespace jaus::transport {
namespace {

std::vector<std::uint8_t> ra_datagram(Framing framing, std::uint16_t code, Address source, AckNak ack = AckNak::none) {
  Header h;
  h.command_code = code;
  h.ack_nak = ack;
  h.source = source;
  h.destination = Address{1, 1, 1, 1};
  h.data_size = 0;
  h.sequence = 7;
  std::array<std::uint8_t, kHeaderSize> message{};
  encode_header_unchecked(h, message);
  const FramePrefix prefix = frame_prefix(framing, message.size());
  std::vector<std::uint8_t> out(prefix.view().begin(), prefix.view().end());
  out.insert(out.end(), message.begin(), message.end());
  return out;
}

jss::JudpHeader jss_header(jss::JssId source, jss::JudpAckNak ack = jss::JudpAckNak::none,
                           jss::JudpDataFlag piece = jss::JudpDataFlag::single) {
  jss::JudpHeader h;
  h.source = source;
  h.destination = jss::JssId{1, 1, 1};
  h.ack_nak = ack;
  h.data_flag = piece;
  h.sequence = 9;
  return h;
}

std::vector<std::uint8_t> contents_of(std::uint16_t id) {
  return {static_cast<std::uint8_t>(id & 0xFF), static_cast<std::uint8_t>(id >> 8)};
}

std::vector<std::uint8_t> jss_datagram(const jss::JudpHeader& h, std::uint16_t id) {
  return jss::make_judp_datagram(h, contents_of(id));
}

TEST(Inbound, AnRaCommandNamesItsSenderAndWhatItAsks) {
  for (const Framing framing : {Framing::opc, Framing::judp}) {
    const auto bytes = ra_datagram(framing, 0x000D, Address{2, 3, 200, 1});  // Request Component Control
    const auto in = decode_datagram(bytes);
    ASSERT_TRUE(in) << in.error().message();
    EXPECT_EQ(in->framing, framing);
    EXPECT_EQ(in->id_space(), IdSpace::ra);
    EXPECT_EQ(in->subsystem, 2);
    EXPECT_EQ(in->node, 3);
    EXPECT_TRUE(in->one_sender);
    EXPECT_TRUE(in->carries_command);
    EXPECT_FALSE(in->carries_stop);
    EXPECT_EQ(in->command_code, 0x000D);
    EXPECT_EQ(in->ra.header.sequence, 7);
    EXPECT_EQ(in->bytes.size(), bytes.size());
    EXPECT_EQ(in->source_text(), "2.3.200.1");
  }
}

TEST(Inbound, StopsQueriesAndAnswersAreToldApartInBothDialects) {
  const auto stop = decode_datagram(ra_datagram(Framing::opc, 0x0006, Address{2, 3, 200, 1}));  // Set Emergency
  ASSERT_TRUE(stop);
  EXPECT_TRUE(stop->carries_stop);
  EXPECT_FALSE(stop->carries_command);
  const auto query = decode_datagram(ra_datagram(Framing::opc, 0x2002, Address{2, 3, 200, 1}));
  ASSERT_TRUE(query);
  EXPECT_FALSE(query->carries_stop || query->carries_command || query->is_answer);
  // An ACK of a command carries the command's code and acts on nothing.
  const auto ack = decode_datagram(ra_datagram(Framing::opc, 0x000D, Address{2, 3, 200, 1}, AckNak::ack));
  ASSERT_TRUE(ack);
  EXPECT_TRUE(ack->is_answer);
  EXPECT_FALSE(ack->carries_command);

  const auto stop_bytes = jss_datagram(jss_header({42, 1, 1}), 0x0006);  // the messages view it
  const auto jss_stop = decode_datagram(stop_bytes);
  ASSERT_TRUE(jss_stop) << jss_stop.error().message();
  EXPECT_EQ(jss_stop->framing, Framing::as5669a);
  EXPECT_EQ(jss_stop->id_space(), IdSpace::jss);
  EXPECT_EQ(jss_stop->subsystem, 42);
  EXPECT_EQ(jss_stop->node, 1);
  EXPECT_TRUE(jss_stop->carries_stop);
  ASSERT_EQ(jss_stop->jss.size(), 1u);
  EXPECT_EQ(jss::message_id_of(jss_stop->jss.front().contents), 0x0006);
  EXPECT_EQ(jss_stop->source_text(), "42.1.1");
  const auto jss_ack = decode_datagram(jss::make_judp_datagram(jss_header({42, 1, 1}, jss::JudpAckNak::ack), {}));
  ASSERT_TRUE(jss_ack) << jss_ack.error().message();
  EXPECT_TRUE(jss_ack->is_answer);
  EXPECT_FALSE(jss_ack->carries_command || jss_ack->carries_stop);
}

TEST(Inbound, ALaterPieceOfAJssMessageIsTakenForACommand) {
  // Its message ID came in an earlier datagram: it may complete a command,
  // so the endpoint rules treat it as one (its reply's budget is needed).
  auto middle = jss::make_judp_datagram(jss_header({42, 1, 1}, jss::JudpAckNak::none, jss::JudpDataFlag::middle),
                                        contents_of(0x4402));  // bytes that would read as a report's ID
  const auto in = decode_datagram(middle);
  ASSERT_TRUE(in) << in.error().message();
  EXPECT_TRUE(in->carries_command);
  EXPECT_FALSE(in->carries_stop);
  const auto first = decode_datagram(
      jss::make_judp_datagram(jss_header({42, 1, 1}, jss::JudpAckNak::none, jss::JudpDataFlag::first),
                              contents_of(0x4402)));
  ASSERT_TRUE(first);
  EXPECT_FALSE(first->carries_command);  // the first piece names its message: a report
}

TEST(Inbound, AFirstPieceNamingACommandIsTakenForOne) {
  // Pieces are put together in any order (the one assembler): a first piece
  // arriving last completes its message, which it names.
  const auto first = decode_datagram(
      jss::make_judp_datagram(jss_header({42, 1, 1}, jss::JudpAckNak::none, jss::JudpDataFlag::first),
                              contents_of(0x0405)));  // Set Wrench Effort
  ASSERT_TRUE(first) << first.error().message();
  EXPECT_TRUE(first->carries_command);
  EXPECT_EQ(first->command_code, 0x0405);
  EXPECT_FALSE(first->carries_stop);
}

TEST(Inbound, ASourceOfNoOneSenderIsMarked) {
  const auto ra = decode_datagram(ra_datagram(Framing::opc, 0x2002, Address{2, 255, 200, 1}));
  ASSERT_TRUE(ra);
  EXPECT_FALSE(ra->one_sender);
  const auto jss = decode_datagram(jss_datagram(jss_header({42, 0, 1}), 0x2202));
  ASSERT_TRUE(jss);
  EXPECT_FALSE(jss->one_sender);
}

TEST(Inbound, WhatIsNotOneSendersJausIsDroppedWithItsReason) {
  const std::vector<std::uint8_t> garbage = {0xDE, 0xAD, 0xBE, 0xEF};
  const auto bad = decode_datagram(garbage);
  ASSERT_FALSE(bad);
  EXPECT_EQ(drop_reason(garbage, bad.error()), DropReason::unknown_framing);

  // Two senders in one AS5669A datagram: one claim must not ride on another's route.
  auto mixed = jss_datagram(jss_header({42, 1, 1}), 0x2202);
  const auto second = jss_datagram(jss_header({43, 1, 1}), 0x2202);
  mixed.insert(mixed.end(), second.begin() + 1, second.end());  // one version byte, then both messages
  const auto two = decode_datagram(mixed);
  ASSERT_FALSE(two);
  EXPECT_EQ(drop_reason(mixed, two.error()), DropReason::jss_malformed);
  EXPECT_NE(two.error().message().find("42.1.1 and 43.1.1"), std::string::npos) << two.error().message();

  const std::vector<std::uint8_t> version_only = {jss::kAs5669aVersion};
  const auto empty = decode_datagram(version_only);
  ASSERT_FALSE(empty);
  EXPECT_EQ(drop_reason(version_only, empty.error()), DropReason::jss_malformed);
}

}  // namespace
}  // namespace jaus::transport
