// Every JSS message: random in-range values and presence vectors (fixed seed)
// survive encode -> decode within one scale step; re-encoding, the typed JSON
// and the catalogue's JSON are byte-exact; every truncation and a wrong
// message ID are errors that say where.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "jaus/jss/catalogue.hpp"
#include "jss_values.hpp"

namespace jaus::test::jss_round_trip {

using Json = nlohmann::ordered_json;

template <class M>
void check_message() {
  using Body = typename M::body_type;
  const std::string name(M::name);
  Rng rng(0x055'0000u + M::code);
  for (int i = 0; i < 25; ++i) {
    M original{};
    wire::CodecContext ctx{wire::Dialect::jss, {}};
    randomize(static_cast<Body&>(original), rng, ctx, /*all_present=*/i == 0);
    const std::string where = name + " #" + std::to_string(i);

    auto contents = jss::try_encode_contents(original);
    ASSERT_TRUE(contents) << where << ": " << contents.error().message();
    ASSERT_GE(contents->size(), 2u);
    EXPECT_EQ(jss::message_id_of(*contents), M::code) << where;

    auto decoded = jss::decode_contents<M>(*contents);
    ASSERT_TRUE(decoded) << where << ": " << decoded.error().message();
    expect_close_body<Body>(original, *decoded, where, wire::Dialect::jss);

    // Once quantised, a value re-encodes to the same bytes.
    EXPECT_EQ(jss::encode_contents(*decoded), *contents) << where;

    // The catalogue's JSON carries the same message, and the typed JSON too.
    auto json = jss::contents_to_json(*contents);
    ASSERT_TRUE(json) << where << ": " << json.error().message();
    EXPECT_EQ((*json)["name"], name) << where;
    auto back = jss::contents_from_json(*json);
    ASSERT_TRUE(back) << where << ": " << back.error().message() << "\n" << json->dump();
    EXPECT_EQ(*back, *contents) << where << "\n" << json->dump();
    M from_json{};
    ASSERT_TRUE(wire::fields_from_json((*json)["fields"], static_cast<Body&>(from_json), wire::Dialect::jss)) << where;
    EXPECT_EQ(jss::encode_contents(from_json), *contents) << where;

    // Every truncation is an error naming a field, at an offset within the bytes given
    // (on the first messages: the walk is the same for the others).
    for (std::size_t cut = 0; i < 6 && cut < contents->size(); ++cut) {
      const auto partial = jss::decode_contents<M>(std::span(*contents).first(cut));
      ASSERT_FALSE(partial.has_value()) << where << " truncated to " << cut;
      EXPECT_FALSE(partial.error().field.empty()) << where << " cut " << cut << ": " << partial.error().message();
      EXPECT_LE(partial.error().offset, cut) << where << " cut " << cut << ": " << partial.error().message();
    }
    // One byte too many.
    auto longer = *contents;
    longer.push_back(0xA5);
    const auto extra = jss::decode_contents<M>(longer);
    ASSERT_FALSE(extra.has_value()) << where;
    EXPECT_EQ(extra.error().code, ErrorCode::trailing_bytes) << where;
    EXPECT_EQ(extra.error().offset, contents->size()) << where;
  }
}

template <class... Ms>
void check_all(msg::TypeList<Ms...>) {
  (check_message<Ms>(), ...);
}

// One test per family, so that the shards share them out.
TEST(JssRoundTrip, AccessControlManagementTimeLiveness) {
  check_all(jss::msg::AccessControlMessages{});
  check_all(jss::msg::ManagementMessages{});
  check_all(jss::msg::TimeMessages{});
  check_all(jss::msg::LivenessMessages{});
}
TEST(JssRoundTrip, Events) { check_all(jss::msg::EventsMessages{}); }
TEST(JssRoundTrip, Discovery) { check_all(jss::msg::DiscoveryMessages{}); }
TEST(JssRoundTrip, SensorsAndDriver) { check_all(jss::msg::SensorDriverMessages{}); }
TEST(JssRoundTrip, WaypointsAndLists) { check_all(jss::msg::WaypointMessages{}); }

TEST(JssRoundTrip, WrongMessageIdIsAnErrorAtOffsetZero) {
  const auto contents = jss::encode_contents(jss::msg::QueryStatus{});
  const auto wrong = jss::decode_contents<jss::msg::QueryControl>(contents);
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().code, ErrorCode::unknown_message);
  EXPECT_EQ(wrong.error().offset, 0u);
  EXPECT_EQ(wrong.error().field, "message_id");
  EXPECT_NE(wrong.error().detail.find("0x2002"), std::string::npos) << wrong.error().detail;
  EXPECT_NE(wrong.error().detail.find("Query Control"), std::string::npos) << wrong.error().detail;
}

TEST(JssRoundTrip, DecodeBodyCountsOffsetsFromTheContents) {
  // Report Timeout's body is one byte; a second is trailing, at contents offset 3.
  const std::vector<std::uint8_t> body{10, 0};
  const auto decoded = jss::decode_body<jss::msg::ReportTimeout>(body);
  ASSERT_FALSE(decoded);
  EXPECT_EQ(decoded.error().code, ErrorCode::trailing_bytes);
  EXPECT_EQ(decoded.error().offset, 3u);
  const auto good = jss::decode_body<jss::msg::ReportTimeout>(std::span(body).first(1));
  ASSERT_TRUE(good);
  EXPECT_EQ(good->timeout_s, 10);
}

TEST(JssRoundTrip, EncodeFailureIsAValueAndEncodeContentsIsEmpty) {
  jss::msg::ReportIdentification report;
  report.identification.assign(256, 'x');  // str8 carries at most 255
  const auto failed = jss::try_encode_contents(report);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().code, ErrorCode::string_too_long);
  EXPECT_EQ(failed.error().field, "identification");
  EXPECT_TRUE(jss::encode_contents(report).empty());

  jss::msg::CreateEvent create;  // no embedded query: not even its ID
  const auto no_query = jss::try_encode_contents(create);
  ASSERT_FALSE(no_query);
  EXPECT_EQ(no_query.error().field, "query_message");
}

}  // namespace jaus::test::jss_round_trip
