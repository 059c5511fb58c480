// Fields, presence bits and presence vectors of one dialect only (issue 44):
// a body JSS shares with RA says in its description what one side alone
// sends (Field::only_in / not_in / always_in, PresenceVector::not_in), and
// every walk (binary, sizes, presence vector, reserved bits, docs, JSON)
// follows it. Local Waypoint is the real case: RA numbers its waypoints, JSS
// adds two tolerances in bits 4 and 5.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/messages/all.hpp"

namespace jaus {
namespace dialect_presence_test {  // named: the unity batches mix this file's helpers with others'

using Bytes = std::vector<std::uint8_t>;
using Json = nlohmann::ordered_json;
using wire::Dialect;

template <class M>
Bytes payload(const M& message, Dialect dialect) {
  std::array<std::uint8_t, 256> out{};
  auto size = wire::encode_payload(message, out, dialect);
  EXPECT_TRUE(size) << (size ? "" : size.error().message());
  return size ? Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(*size)) : Bytes{};
}

msg::SetLocalWaypoint waypoint_with_everything() {
  msg::SetLocalWaypoint w{};
  w.waypoint_number = 7;
  w.x_m = 10;
  w.y_m = -20;
  w.z_m = -50'000;  // inside JSS's range, below RA's
  w.yaw_rad = 1.0;
  w.waypoint_tolerance_m = 2.5;
  w.path_tolerance_m = 100;
  return w;
}

TEST(DialectPresence, EachDialectSendsItsOwnFieldsOfLocalWaypoint) {
  const auto w = waypoint_with_everything();
  // RA: PV (z, yaw), waypoint number, x, y, z (clamped to -10000), yaw; no tolerances.
  const Bytes ra = payload(w, Dialect::ra);
  ASSERT_EQ(ra.size(), 1u + 2 + 4 + 4 + 4 + 2);
  EXPECT_EQ(ra[0], 0x09);
  EXPECT_EQ(ra[1], 7);
  EXPECT_EQ(wire::presence_of(static_cast<const msg::LocalWaypointBody&>(w)), 0x09u);  // RA is the default
  // JSS: PV (z, yaw, both tolerances), no waypoint number, x, y, z, yaw, u16 + u32 tolerances.
  const Bytes jss = payload(w, Dialect::jss);
  ASSERT_EQ(jss.size(), 1u + 4 + 4 + 4 + 2 + 2 + 4);
  EXPECT_EQ(jss[0], 0x39);
  EXPECT_EQ(wire::presence_of(static_cast<const msg::LocalWaypointBody&>(w), Dialect::jss), 0x39u);

  auto back = wire::decode_payload<msg::SetLocalWaypoint>(jss, Dialect::jss);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->waypoint_number, 0);  // not in JSS
  EXPECT_NEAR(*back->z_m, -50'000, 1e-4);
  EXPECT_NEAR(*back->waypoint_tolerance_m, 2.5, 0.01);
  EXPECT_NEAR(*back->path_tolerance_m, 100, 1e-4);
  EXPECT_FALSE(back->roll_rad);

  auto from_ra = wire::decode_payload<msg::SetLocalWaypoint>(ra, Dialect::ra);
  ASSERT_TRUE(from_ra) << from_ra.error().message();
  EXPECT_EQ(from_ra->waypoint_number, 7);
  EXPECT_NEAR(*from_ra->z_m, -10'000, 1);
  EXPECT_FALSE(from_ra->waypoint_tolerance_m);
  EXPECT_FALSE(from_ra->path_tolerance_m);
}

TEST(DialectPresence, ADecodeInAnotherDialectLeavesNothingOfTheLastMessage) {
  msg::SetLocalWaypoint reused = waypoint_with_everything();
  const Bytes jss = payload(msg::SetLocalWaypoint{}, Dialect::jss);
  ASSERT_TRUE(wire::decode_payload_into(jss, reused, Dialect::jss));
  EXPECT_EQ(reused.waypoint_number, 0);  // RA's field, not in the message
  EXPECT_NEAR(reused.x_m, 0, 1e-4);     // JSS's symmetric range has no exact zero
  EXPECT_FALSE(reused.z_m || reused.yaw_rad || reused.waypoint_tolerance_m || reused.path_tolerance_m);
  reused = waypoint_with_everything();
  ASSERT_TRUE(wire::decode_payload_into(payload(msg::SetLocalWaypoint{}, Dialect::ra), reused, Dialect::ra));
  EXPECT_EQ(reused, msg::SetLocalWaypoint{});
}

TEST(DialectPresence, ABitOfTheOtherDialectIsReserved) {
  // PV with bit 4 (waypoint tolerance): JSS's, reserved in RA.
  const Bytes jss = payload(waypoint_with_everything(), Dialect::jss);
  const auto as_ra = wire::decode_payload<msg::SetLocalWaypoint>(jss, Dialect::ra);
  ASSERT_FALSE(as_ra);
  EXPECT_EQ(as_ra.error().code, ErrorCode::reserved_presence_bits);
  Bytes bit6 = payload(msg::SetLocalWaypoint{}, Dialect::jss);
  bit6[0] = 0x40;
  const auto as_jss = wire::decode_payload<msg::SetLocalWaypoint>(bit6, Dialect::jss);
  ASSERT_FALSE(as_jss);
  EXPECT_EQ(as_jss.error().code, ErrorCode::reserved_presence_bits);
  EXPECT_EQ(wire::optional_mask<msg::LocalWaypointBody>(), 0x0Fu);
  EXPECT_EQ(wire::optional_mask<msg::LocalWaypointBody>(Dialect::jss), 0x3Fu);
}

TEST(DialectPresence, ACutBodyIsNamedInTheFieldOfItsDialect) {
  // The checked walk (taken when the bytes run short) skips what the dialect does not send.
  Bytes jss = payload(waypoint_with_everything(), Dialect::jss);
  jss.pop_back();
  const auto cut = wire::decode_payload<msg::SetLocalWaypoint>(jss, Dialect::jss);
  ASSERT_FALSE(cut);
  EXPECT_NE(cut.error().message().find("path_tolerance_m"), std::string::npos) << cut.error().message();
  std::array<std::uint8_t, 18> small{};  // one byte short of the JSS body
  const auto too_small = wire::encode_payload(waypoint_with_everything(), small, Dialect::jss);
  ASSERT_FALSE(too_small);
  EXPECT_NE(too_small.error().message().find("path_tolerance_m"), std::string::npos) << too_small.error().message();
}

TEST(DialectPresence, EachDialectsDocAndJsonShowItsOwnFields) {
  const std::string ra = wire::fields_doc<msg::LocalWaypointBody>(Dialect::ra);
  const std::string jss = wire::fields_doc<msg::LocalWaypointBody>(Dialect::jss);
  EXPECT_NE(ra.find("`waypoint_number`: u16"), std::string::npos) << ra;
  EXPECT_EQ(ra.find("tolerance"), std::string::npos) << ra;
  EXPECT_EQ(jss.find("waypoint_number"), std::string::npos) << jss;
  EXPECT_NE(jss.find("`waypoint_tolerance_m` (bit 4): u16 scaled [0, 100]"), std::string::npos) << jss;
  EXPECT_NE(jss.find("`z_m` (bit 0): u32 scaled [-100000, 100000]"), std::string::npos) << jss;

  const auto w = waypoint_with_everything();
  const Json ra_json = wire::fields_to_json<Json>(static_cast<const msg::LocalWaypointBody&>(w));
  EXPECT_TRUE(ra_json.contains("waypoint_number"));
  const Json jss_json = wire::fields_to_json<Json>(static_cast<const msg::LocalWaypointBody&>(w), Dialect::jss);
  EXPECT_FALSE(jss_json.contains("waypoint_number"));
  EXPECT_TRUE(jss_json.contains("path_tolerance_m"));

  msg::LocalWaypointBody filled{};
  EXPECT_TRUE(wire::fields_from_json(jss_json, filled, Dialect::jss));
  EXPECT_EQ(filled.path_tolerance_m, 100);
  Json with_number = jss_json;
  with_number["waypoint_number"] = 7;
  const auto refused = wire::fields_from_json(with_number, filled, Dialect::ra);  // RA has no tolerances
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message().find("unknown field"), std::string::npos) << refused.error().message();
  EXPECT_FALSE(wire::fields_from_json(ra_json, filled, Dialect::jss));  // JSS has no waypoint number
}

// A body whose presence vector only RA sends; JSS sends one of its RA-optional
// fields always, the other never (Cancel Event's shape).
struct CancelLike {
  std::uint8_t request_id = 0;
  std::optional<std::uint16_t> message_code;
  std::optional<std::uint8_t> event_id;
  bool operator==(const CancelLike&) const = default;
  static constexpr auto describe() {
    using B = CancelLike;
    return std::make_tuple(wire::presence_vector<std::uint8_t>().not_in(Dialect::jss),
                           wire::field("request_id", &B::request_id, wire::Int<std::uint8_t>{}),
                           wire::optional(0, "message_code", &B::message_code, wire::Int<std::uint16_t>{})
                               .not_in(Dialect::jss),
                           wire::optional(1, "event_id", &B::event_id, wire::Int<std::uint8_t>{})
                               .always_in(Dialect::jss));
  }
};

TEST(DialectPresence, APresenceVectorOfOneDialectOnly) {
  const CancelLike by_id{3, std::nullopt, 9};
  EXPECT_EQ(payload(by_id, Dialect::ra), (Bytes{0x02, 3, 9}));
  EXPECT_EQ(payload(by_id, Dialect::jss), (Bytes{3, 9}));
  const CancelLike by_code{3, 0x4402, std::nullopt};
  EXPECT_EQ(payload(by_code, Dialect::ra), (Bytes{0x01, 3, 0x02, 0x44}));
  EXPECT_EQ(payload(by_code, Dialect::jss), (Bytes{3, 0}));  // always sent there: its zero value

  const auto back = wire::decode_payload<CancelLike>(Bytes{3, 9}, Dialect::jss);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(*back, by_id);
  EXPECT_FALSE(wire::decode_payload<CancelLike>(Bytes{3, 9, 0}, Dialect::jss));  // trailing byte
  EXPECT_FALSE(wire::decode_payload<CancelLike>(Bytes{3}, Dialect::jss));        // event ID missing

  const std::string jss = wire::fields_doc<CancelLike>(Dialect::jss);
  EXPECT_EQ(jss, "{`request_id`: u8; `event_id`: u8}");
  const std::string ra = wire::fields_doc<CancelLike>(Dialect::ra);
  EXPECT_EQ(ra, "{presence vector (u8); `request_id`: u8; `message_code` (bit 0): u16; `event_id` (bit 1): u8}");
  CancelLike filled{};
  EXPECT_FALSE(wire::fields_from_json(Json{{"request_id", 1}}, filled, Dialect::jss));  // event_id is required there
  EXPECT_TRUE(wire::fields_from_json(Json{{"request_id", 1}}, filled, Dialect::ra));
}

TEST(DialectPresence, EventEmbedsTheReportAsEachDialectDoes) {
  msg::Event event{};
  event.event_id = 4;
  event.report_code = 0x4402;
  event.sequence_number = 9;
  event.report_message = {0x01, 0x00, 0x2A};
  // RA: event ID, report code, sequence number, u32 size, the payload.
  EXPECT_EQ(payload(event, Dialect::ra), (Bytes{4, 0x02, 0x44, 9, 3, 0, 0, 0, 0x01, 0x00, 0x2A}));
  // JSS: event ID, sequence number, u32 count, the whole report (ID first); no report code.
  EXPECT_EQ(payload(event, Dialect::jss), (Bytes{4, 9, 3, 0, 0, 0, 0x01, 0x00, 0x2A}));
  const auto back = wire::decode_payload<msg::Event>(Bytes{4, 9, 3, 0, 0, 0, 0x01, 0x00, 0x2A}, Dialect::jss);
  ASSERT_TRUE(back) << back.error().message();
  EXPECT_EQ(back->report_code, 0);
  EXPECT_EQ(back->report_message, (Bytes{0x01, 0x00, 0x2A}));
  // JSS's embedded report must hold at least its ID; RA's payload may be empty.
  EXPECT_FALSE(wire::decode_payload<msg::Event>(Bytes{4, 9, 1, 0, 0, 0, 0x01}, Dialect::jss));
  EXPECT_TRUE(wire::decode_payload<msg::Event>(Bytes{4, 0x02, 0x44, 9, 0, 0, 0, 0}, Dialect::ra));

  EXPECT_NE(wire::fields_doc<msg::EventBody>(Dialect::jss).find("embedded JSS message"), std::string::npos);
  EXPECT_NE(wire::fields_doc<msg::EventBody>(Dialect::ra).find("u32 size + bytes"), std::string::npos);
  const Json ra_json = wire::fields_to_json<Json>(static_cast<const msg::EventBody&>(event));
  EXPECT_TRUE(ra_json["report_message"].is_string()) << ra_json.dump();  // hex
  const Json jss_json = wire::fields_to_json<Json>(static_cast<const msg::EventBody&>(event), Dialect::jss);
  EXPECT_FALSE(jss_json["report_message"].is_string()) << jss_json.dump();  // the embedded message's JSON
  msg::EventBody filled{};
  ASSERT_TRUE(wire::fields_from_json(jss_json, filled, Dialect::jss));
  EXPECT_EQ(filled.report_message, event.report_message);
}

}  // namespace dialect_presence_test
}  // namespace jaus
