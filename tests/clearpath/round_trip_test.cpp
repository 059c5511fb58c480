// Every message type survives encode -> frame -> parse -> decode, and the
// JSON form, with random in-range values (fixed seed).
#include <gtest/gtest.h>

#include <random>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"
#include "jaus/clearpath/message_json.hpp"
#include "random_message.hpp"

namespace cp = jaus::clearpath;

namespace {
constexpr int kSamplesPerType = 40;

cp::Direction sender_of(std::uint16_t type) {
  return cp::kind_of(type) == cp::MessageKind::data ? cp::Direction::from_platform : cp::Direction::to_platform;
}
}  // namespace

TEST(ClearpathCatalogue, CoversTheDocument) {
  std::size_t commands = 0, requests = 0, data = 0;
  for (const auto& info : cp::message_catalogue()) {
    switch (info.kind) {
      case cp::MessageKind::command: ++commands; break;
      case cp::MessageKind::request: ++requests; break;
      case cp::MessageKind::data: ++data; break;
      case cp::MessageKind::unassigned: ADD_FAILURE() << info.name; break;
    }
    EXPECT_EQ(cp::find_message(info.name)->type, info.type);
  }
  EXPECT_EQ(commands, 27u);
  EXPECT_EQ(requests, 41u);
  EXPECT_EQ(data, 41u);
  // Every request has its data reply.
  for (const auto& info : cp::message_catalogue())
    if (info.kind == cp::MessageKind::request) {
      EXPECT_TRUE(cp::find_message(cp::reply_type_of(info.type))) << info.name;
    }
}

TEST(ClearpathRoundTrip, EveryTypeWithRandomInRangeValues) {
  std::mt19937 rng(20240605);
  std::uint32_t timestamp = 1;
  for (const auto& info : cp::message_catalogue()) {
    SCOPED_TRACE(std::string(info.name));
    for (int i = 0; i < kSamplesPerType; ++i) {
      cp::AnyMessage message = *cp::make_message(info.type);
      cp::testing::randomize(message, rng);
      const auto in_range = cp::check_ranges(message);
      ASSERT_TRUE(in_range) << in_range.error().message();

      const cp::Envelope sent{{0, timestamp++, static_cast<std::uint8_t>(i % 2), info.type}, message};
      const auto bytes = cp::encode(sent);
      ASSERT_TRUE(bytes) << bytes.error().message();

      cp::FrameParser parser;
      parser.feed(*bytes);
      auto event = parser.poll();
      ASSERT_TRUE(event);
      ASSERT_TRUE(std::holds_alternative<cp::Frame>(*event));
      const auto received = cp::decode(std::get<cp::Frame>(*event), sender_of(info.type));
      ASSERT_TRUE(received) << received.error().message();
      EXPECT_EQ(received->header, sent.header);
      EXPECT_TRUE(received->message == message) << cp::fields_to_json(received->message).dump();

      const auto json = cp::to_json(sent);
      const auto back = cp::envelope_from_json(json);
      ASSERT_TRUE(back) << back.error().message() << " in " << json.dump();
      EXPECT_TRUE(back->message == message) << json.dump();
      EXPECT_EQ(back->header, sent.header);
    }
  }
}

TEST(ClearpathRoundTrip, AcksOfEveryCommandAndRequest) {
  std::mt19937 rng(7);
  for (const auto& info : cp::message_catalogue()) {
    if (info.kind == cp::MessageKind::data) continue;
    const cp::Ack ack{static_cast<std::uint16_t>(rng() & 0x7F)};
    const cp::Envelope sent{{0, 99, 0, info.type}, cp::AnyMessage{ack}};
    const auto bytes = cp::encode(sent);
    ASSERT_TRUE(bytes);
    EXPECT_EQ(bytes->size(), 16u);  // LEN 13
    const auto frame = cp::decode_frame(*bytes);
    ASSERT_TRUE(frame);
    const auto back = cp::decode(*frame, cp::Direction::from_platform);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->message.get<cp::Ack>(), ack);
    EXPECT_EQ(back->header.type, info.type);
  }
}
