// The catalogue's JSS set: every described message is in it once with its
// service and summary, found by ID, name and type name; contents and datagrams
// round-trip through JSON; embedded messages show by field.
#include <gtest/gtest.h>

#include <set>

#include <nlohmann/json.hpp>

#include "jaus/jss/catalogue.hpp"
#include "jss_bytes.hpp"
#include "jss_values.hpp"

namespace jaus::test::jss_catalogue {

using namespace jaus::jss;
namespace msg = jaus::jss::msg;
using jaus::msg::catalogue;
using jaus::msg::find_message;
using jaus::msg::MessageClass;
using Json = nlohmann::ordered_json;
constexpr auto kJss = wire::Dialect::jss;

template <class... Ms>
std::vector<std::uint16_t> ids_of(msg::TypeList<Ms...>) {
  return {Ms::code...};
}

TEST(JssCatalogue, EveryDescribedMessageOnceWithServiceAndSummary) {
  const auto ids = ids_of(AllJssMessages{});
  EXPECT_EQ(std::set<std::uint16_t>(ids.begin(), ids.end()).size(), ids.size()) << "an ID is described twice";
  EXPECT_EQ(catalogue(kJss).size(), ids.size());
  for (const auto id : ids) {
    const auto* info = find_message(kJss, id);
    ASSERT_NE(info, nullptr) << id;
    EXPECT_TRUE(info->service_uri.starts_with("urn:jaus:jss:")) << info->name;
    EXPECT_FALSE(info->summary.empty()) << info->name;
    EXPECT_EQ(find_message(kJss, info->name), info);
    EXPECT_EQ(find_message(kJss, info->type_name), info);
    EXPECT_EQ(info->type_name.find(' '), std::string_view::npos);
    EXPECT_FALSE(info->fields_doc().empty());
  }
  EXPECT_TRUE(std::is_sorted(catalogue(kJss).begin(), catalogue(kJss).end(),
                             [](const auto& a, const auto& b) { return a.code < b.code; }));
}

TEST(JssCatalogue, ClassesServicesAndNames) {
  EXPECT_EQ(find_message(kJss, 0x2B00)->message_class, MessageClass::query);
  EXPECT_EQ(find_message(kJss, 0x4B00)->message_class, MessageClass::inform);
  EXPECT_EQ(find_message(kJss, 0x000D)->message_class, MessageClass::command);
  EXPECT_EQ(find_message(kJss, "RequestControl")->code, 0x000D);
  EXPECT_EQ(service_name(find_message(kJss, 0x0405)->service_uri), "PrimitiveDriver");
  EXPECT_EQ(find_message(kJss, 0x041A)->service_uri, "urn:jaus:jss:mobility:ListManager");
  EXPECT_EQ(find_message(kJss, 0x041E)->service_uri, "urn:jaus:jss:mobility:LocalWaypointListDriver");
  EXPECT_EQ(find_message(kJss, 0x0010)->name, "Reject Control");
  EXPECT_EQ(find_message(kJss, 0x1234), nullptr);
  EXPECT_EQ(find_message(kJss, "Report Component Status"), nullptr);  // RA's name, not JSS's
  EXPECT_EQ(find_message(kJss, 0x0405)->set, kJss);
}

// One catalogue, two sets: a code is looked up in the set its dialect speaks.
TEST(JssCatalogue, TheSameCodeNamesEachSetsOwnMessage) {
  const auto* jss_status = find_message(kJss, 0x4002);
  const auto* ra_status = find_message(wire::Dialect::ra, 0x4002);
  ASSERT_NE(jss_status, nullptr);
  ASSERT_NE(ra_status, nullptr);
  EXPECT_EQ(jss_status->name, "Report Status");
  EXPECT_EQ(ra_status->name, "Report Component Status");
  EXPECT_EQ(find_message(wire::Dialect::openjaus, 0x4002), ra_status);
  // A body both sets share reads in each set's dialect: JSS's Report Local
  // Pose is unsigned where RA's is signed, so one set's bytes are another value in the other.
  const auto* jss_pose = find_message(kJss, 0x4403);
  const auto* ra_pose = find_message(wire::Dialect::ra, 0x4403);
  ASSERT_NE(jss_pose, nullptr);
  ASSERT_NE(ra_pose, nullptr);
  const auto fields = Json::parse(R"({"x_m": -10.0, "y_m": 0})");
  const auto jss_body = jss_pose->body_from_json(fields, kJss);
  const auto ra_body = ra_pose->body_from_json(fields, wire::Dialect::ra);
  ASSERT_TRUE(jss_body && ra_body);
  EXPECT_NE(*jss_body, *ra_body);
  EXPECT_NEAR((*jss_pose->body_to_json(*jss_body, kJss))["x_m"].get<double>(), -10.0, 1e-4);
  EXPECT_NEAR((*ra_pose->body_to_json(*ra_body, wire::Dialect::ra))["x_m"].get<double>(), -10.0, 1e-4);
  // A JSS entry is read as JSS whatever dialect is asked.
  EXPECT_EQ(*jss_pose->body_to_json(*jss_body, wire::Dialect::ra), *jss_pose->body_to_json(*jss_body, kJss));
}

TEST(JssCatalogue, ContentsJsonShowsEmbeddedMessagesByField) {
  const auto bytes = hex_bytes("f1 41 00 07 0c 00 00 00 03 44 03 00 dc 46 03 80 91 5c fe 7f");
  const auto json = contents_to_json(bytes);
  ASSERT_TRUE(json) << json.error().message();
  EXPECT_EQ((*json)["id"], "0x41F1");
  EXPECT_EQ((*json)["name"], "Event");
  const auto& report = (*json)["fields"]["report_message"];
  EXPECT_EQ(report["name"], "Report Local Pose") << json->dump();
  EXPECT_NEAR(report["fields"]["x_m"].get<double>(), 10.0, 1e-4);
  EXPECT_EQ(*contents_from_json(*json), bytes);

  // Bytes that are not a message we know stay hex, and come back as they were.
  msg::Event odd;
  odd.report_message = {0x34, 0x12, 0xAA};
  const auto odd_json = contents_to_json(encode_contents(odd));
  ASSERT_TRUE(odd_json);
  EXPECT_EQ((*odd_json)["fields"]["report_message"]["hex"], "3412AA");
  EXPECT_EQ(*contents_from_json(*odd_json), encode_contents(odd));

  // Written by hand: by name, numbers or names for enums.
  const auto create = contents_from_json(Json::parse(R"({"name": "CreateEvent", "fields": {
      "request_id": 1, "event_type": "periodic", "requested_rate_hz": 5,
      "query_message": {"name": "Query Local Pose", "fields": {"presence_vector": 511}}}})"));
  ASSERT_TRUE(create) << create.error().message();
  EXPECT_EQ(*create, hex_bytes("f0 01 01 00 2c 01 04 00 00 00 03 24 ff 01"));
}

TEST(JssCatalogue, JsonErrorsSayWhere) {
  const auto unknown = contents_from_json(Json::parse(R"({"name": "Query Nothing"})"));
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::json);
  const auto bad_field = contents_from_json(Json::parse(R"({"id": "0x000D", "fields": {"authority": "high"}})"));
  ASSERT_FALSE(bad_field);
  EXPECT_NE(bad_field.error().message().find("authority"), std::string::npos) << bad_field.error().message();
  const auto bad_variant = contents_from_json(Json::parse(R"({"id": "0x21F0", "fields": {"filter": {"colour": 1}}})"));
  ASSERT_FALSE(bad_variant);
  EXPECT_NE(bad_variant.error().message().find("message_id"), std::string::npos) << bad_variant.error().message();
  EXPECT_FALSE(contents_to_json(hex_bytes("34 12")));  // unknown ID
  EXPECT_FALSE(contents_to_json(hex_bytes("02")));
}

TEST(JssCatalogue, DatagramJsonRoundTrip) {
  const auto bytes = hex_bytes("02 00 11 00 01 01 01 01 00 01 01 2a 00 00 2b 02 00 00");
  const auto json = datagram_to_json(bytes);
  ASSERT_TRUE(json) << json.error().message();
  const auto& packet = (*json)["packets"][0];
  EXPECT_EQ(packet["header"]["source"], "42.1.1");
  EXPECT_EQ(packet["header"]["priority"], "normal");
  EXPECT_EQ(packet["message"]["name"], "Query Identification");
  EXPECT_EQ(packet["message"]["fields"]["query_type"], "subsystem");
  EXPECT_EQ(*datagram_from_json(packet), bytes);

  // An ACK carries no message: its contents show as (empty) hex.
  JudpHeader ack;
  ack.ack_nak = JudpAckNak::ack;
  ack.source = {1, 1, 1};
  ack.destination = {42, 1, 1};
  const auto ack_bytes = make_judp_datagram(ack, {});
  const auto ack_json = datagram_to_json(ack_bytes);
  ASSERT_TRUE(ack_json);
  EXPECT_EQ((*ack_json)["packets"][0]["contents"], "");
  EXPECT_EQ((*ack_json)["packets"][0]["header"]["ack_nak"], "ack");
  EXPECT_EQ(*datagram_from_json((*ack_json)["packets"][0]), ack_bytes);

  // A body one byte too long inside a good datagram: the offset counts from the datagram.
  auto bad = bytes;
  bad.insert(bad.begin() + 16, 0x00);
  bad[2] = 18;
  const auto bad_json = datagram_to_json(bad);
  ASSERT_FALSE(bad_json);
  EXPECT_EQ(bad_json.error().code, ErrorCode::trailing_bytes);
  EXPECT_EQ(bad_json.error().offset, 16u);
}

TEST(JssCatalogue, MarkdownListsEveryMessage) {
  const auto doc = messages_markdown();
  for (const auto& m : catalogue(kJss)) EXPECT_NE(doc.find("| " + std::string(m.name) + " |"), std::string::npos) << m.name;
  EXPECT_NE(doc.find("u8 length + text"), std::string::npos);
}

}  // namespace jaus::test::jss_catalogue
