// The sans-I/O pieces of the OCU: command-line values, messages from codes
// and JSON, the rate meter, and what discovery asks next.
#include <gtest/gtest.h>

#include "jaus/messages/all.hpp"
#include "ocu/cli_values.hpp"
#include "jaus/ocu/discovery.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/rate_meter.hpp"

namespace jausctl::ocu {
namespace {

using namespace std::chrono_literals;

TEST(CliValues, Addresses) {
  EXPECT_EQ(*parse_address("1.1.35.1", false), (jaus::Address{1, 1, 35, 1}));
  EXPECT_EQ(*parse_address("1.255.255.255", true), (jaus::Address{1, 255, 255, 255}));
  EXPECT_EQ(parse_address("1.255.255.255", false).error().message(),
            "bad address '1.255.255.255': 255 (broadcast) is not allowed here");
  EXPECT_EQ(parse_address("1.1.0.1", true).error().message(), "bad address '1.1.0.1': 0 is not a valid ID at any level");
  EXPECT_FALSE(parse_address("1.1.35", true));
  EXPECT_FALSE(parse_address("1.1.35.256", true));
  EXPECT_FALSE(parse_address("", true));
}

TEST(CliValues, MessageCodesByNumberOrName) {
  EXPECT_EQ(*parse_message_code("0x2002"), 0x2002);
  EXPECT_EQ(*parse_message_code("2002"), 0x2002);
  EXPECT_EQ(*parse_message_code("Report Global Pose"), 0x4402);
  EXPECT_EQ(parse_message_code("0x1234").error().message(), "unknown message code 0x1234 (jausctl msg list shows every code)");
  EXPECT_FALSE(parse_message_code("0x12345"));
  EXPECT_FALSE(parse_message_code("Report Nothing"));
}

TEST(CliValues, DurationsEndpointsPresenceVectors) {
  EXPECT_EQ(*parse_seconds("0.25"), 250ms);
  EXPECT_EQ(*parse_seconds("2"), 2s);
  for (const char* bad : {"0", "-1", "abc", "1s", "nan", "inf", "100000"}) EXPECT_FALSE(parse_seconds(bad)) << bad;
  EXPECT_EQ(seconds_text(1s), "1 s");
  EXPECT_EQ(seconds_text(300ms), "0.3 s");
  EXPECT_EQ(elapsed_text(4000880us), "4.0 s");

  const auto any = parse_endpoint_text("0.0.0.0:0", 0, true);
  ASSERT_TRUE(any);
  EXPECT_EQ(any->port, 0);
  EXPECT_FALSE(parse_endpoint_text("127.0.0.1:0", 3794, false));
  EXPECT_EQ(parse_endpoint_text("127.0.0.2", 3794, false)->port, 3794);
  EXPECT_EQ(parse_endpoint_text("127.0.0.2", 3794, false)->address, 0x7F000002u);
  EXPECT_FALSE(parse_endpoint_text("localhost:3794", 3794, false));
  EXPECT_FALSE(parse_endpoint_text("127.0.0.1:70000", 3794, false));

  EXPECT_EQ(*parse_presence_vector("0x1F"), 0x1Fu);
  EXPECT_EQ(*parse_presence_vector("ffffffff"), 0xFFFFFFFFu);
  EXPECT_FALSE(parse_presence_vector("0x123456789"));
  EXPECT_FALSE(parse_presence_vector("xyz"));

  EXPECT_EQ(*parse_authority("255"), 255);
  EXPECT_FALSE(parse_authority("256"));
  EXPECT_FALSE(parse_authority("-1"));
  EXPECT_DOUBLE_EQ(*parse_rate_hz("0.5"), 0.5);
  EXPECT_FALSE(parse_rate_hz("0"));
  EXPECT_FALSE(parse_rate_hz("1093"));
  EXPECT_FALSE(parse_rate_hz("5Hz"));
  EXPECT_EQ(*parse_count("3"), 3u);
  EXPECT_FALSE(parse_count("0"));
  EXPECT_FALSE(parse_count("-2"));

  EXPECT_EQ(hz_text(4.99886), "5");
  EXPECT_EQ(hz_text(0.25), "0.25");
  EXPECT_EQ(hz_text(12.5), "12.5");
}

TEST(MessageJson, QueriesGetTheirPresenceVectorAndDefaultFields) {
  auto pose = prepare_query(0x2402, 0x3, Json::object());
  ASSERT_TRUE(pose) << pose.error().message();
  EXPECT_EQ(pose->header.command_code, 0x2402);
  EXPECT_EQ(pose->payload, (std::vector<std::uint8_t>{0x03, 0x00}));

  // Query Camera Pose: presence vector and camera ID; the camera defaults to 0.
  auto camera = prepare_query(0x2800, 0x1, Json::object());
  ASSERT_TRUE(camera) << camera.error().message();
  EXPECT_EQ(camera->payload, (std::vector<std::uint8_t>{0x01, 0x00, 0x00}));
  auto camera2 = prepare_query(0x2800, std::nullopt, Json{{"camera_id", 2}});
  ASSERT_TRUE(camera2) << camera2.error().message();
  EXPECT_EQ(camera2->payload, (std::vector<std::uint8_t>{0x00, 0x00, 0x02}));

  EXPECT_EQ(prepare_query(0x2002, 1, Json::object()).error().code, jaus::ErrorCode::invalid_argument);
  EXPECT_EQ(prepare_query(0x2002, 1, Json::object()).error().message(),
            "Query Component Status (0x2002) has no presence vector (--pv)");
  EXPECT_EQ(prepare_query(0x0006, std::nullopt, Json::object()).error().message(),
            "Set Emergency (0x0006) is not a query (queries are 0x2nnn; `jausctl send` sends any message)");
  EXPECT_FALSE(prepare_query(0x2800, std::nullopt, Json{{"lens", 1}}));
  EXPECT_EQ(*report_code_for(0x2402), 0x4402);
  EXPECT_FALSE(report_code_for(0x4402));
}

TEST(MessageJson, MessagesFromDecodeJson) {
  auto m = prepare_message(Json::parse(R"({"code":"0x000D","header":{"priority":11},"fields":{"authority":7}})"),
                           jaus::wire::Dialect::ra);
  ASSERT_TRUE(m) << m.error().message();
  EXPECT_EQ(m->header.command_code, 0x000D);
  EXPECT_EQ(m->header.priority, 11);
  EXPECT_EQ(m->payload, (std::vector<std::uint8_t>{7}));
  EXPECT_FALSE(prepare_message(Json::parse(R"({"code":"0x000D","fields":{"authority":"high"}})"),
                               jaus::wire::Dialect::ra));
  EXPECT_FALSE(prepare_message(Json::parse(R"({"code":"0x1234"})"), jaus::wire::Dialect::ra));
  EXPECT_FALSE(prepare_message(Json::parse(R"([1,2])"), jaus::wire::Dialect::ra));
}

TEST(MessageJson, ReceivedMessagesInTheDecodeForm) {
  Received r;
  r.header.command_code = 0x4002;
  r.header.source = {1, 1, 35, 1};
  r.header.destination = {254, 1, 40, 1};
  r.payload = {0x01, 0, 0, 0, 0};
  auto j = message_json(r, jaus::wire::Dialect::ra);
  ASSERT_TRUE(j) << j.error().message();
  EXPECT_EQ(json_line(*j).rfind(R"({"code":"0x4002","name":"Report Component Status","header":{)", 0), 0u);
  EXPECT_EQ((*j)["fields"]["primary_status"], "ready");

  r.payload = {0x01};
  EXPECT_FALSE(message_json(r, jaus::wire::Dialect::ra));
  r.header.command_code = 0x7F00;  // experimental, not in the catalogue: kept as hex
  auto unknown = message_json(r, jaus::wire::Dialect::ra);
  ASSERT_TRUE(unknown);
  EXPECT_EQ((*unknown)["payload"], "01");
}

TEST(RateMeter, WindowsAndTheWholeRun) {
  const jaus::rt::TimePoint t0{};
  RateMeter meter(t0);
  for (int i = 0; i <= 10; ++i) meter.tick(t0 + i * 200ms);  // 5 Hz for 2 s: 11 reports
  const auto window = meter.take_window(t0 + 2s);
  EXPECT_EQ(window.count, 11u);
  EXPECT_DOUBLE_EQ(window.hz, 5.5);
  const auto total = meter.total();
  EXPECT_EQ(total.count, 11u);
  EXPECT_DOUBLE_EQ(total.hz, 5.0);
  EXPECT_EQ(summary_text(total), "11 reports in 2.0 s (5.00 Hz)");
  EXPECT_EQ(meter.take_window(t0 + 3s).count, 0u);
  EXPECT_EQ(summary_text(RateMeter(t0).total()), "0 reports in 0.0 s (0.00 Hz)");
}

// The typical OCU sequence (docs/wire-format.md, "Typical OCU sequence"),
// message by message.
class DiscoveryModel : public ::testing::Test {
 protected:
  template <class M>
  std::vector<DiscoveryQuery> reply(const jaus::Address& from, const M& message) {
    std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
    const auto size = jaus::wire::encode_payload(message, payload);
    EXPECT_TRUE(size);
    payload.resize(*size);
    jaus::Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = self;
    return discovery.received(h, payload, jaus::wire::Dialect::ra);
  }
  static bool asks(const std::vector<DiscoveryQuery>& qs, const jaus::Address& to, DiscoveryQuery::Kind kind,
                   std::uint8_t field) {
    return std::find(qs.begin(), qs.end(), DiscoveryQuery{to, kind, field}) != qs.end();
  }

  const jaus::Address self{254, 1, 40, 1};
  Discovery discovery{self};
};

TEST_F(DiscoveryModel, AHeartbeatStartsTheSequenceAndEachQuestionIsAskedOnce) {
  using K = DiscoveryQuery::Kind;
  const auto start = discovery.start();
  ASSERT_EQ(start.size(), 1u);
  EXPECT_EQ(start[0].to, (jaus::Address{255, 255, 1, 1}));

  const jaus::Address manager{3, 2, 1, 1};
  const auto first = discovery.heard(manager);
  EXPECT_TRUE(asks(first, manager, K::identification, 2));
  EXPECT_TRUE(asks(first, manager, K::configuration, 2));
  EXPECT_TRUE(asks(first, manager, K::identification, 3));
  EXPECT_TRUE(asks(first, manager, K::identification, 4));
  EXPECT_TRUE(asks(first, manager, K::services, 0));
  EXPECT_TRUE(asks(first, manager, K::subsystem_list, 0));
  EXPECT_TRUE(discovery.heard(manager).empty());  // the next heartbeat asks nothing new
  EXPECT_TRUE(discovery.heard(jaus::Address{254, 1, 1, 1}).empty());  // the OCU's own node

  jaus::msg::ReportConfiguration configuration;
  configuration.nodes.push_back({2, {{1, 1}, {33, 1}}});
  const auto next = reply(manager, configuration);
  EXPECT_TRUE(asks(next, jaus::Address{3, 2, 33, 1}, K::identification, 4));
  EXPECT_TRUE(asks(next, jaus::Address{3, 2, 33, 1}, K::services, 0));
  EXPECT_EQ(discovery.component_count(), 2u);

  reply(manager, jaus::msg::ReportIdentification{{2, 0, 10001, "rover"}});
  jaus::msg::ReportServices services;
  services.services.push_back({33, {{0x0405, 0}}, {}});
  reply(manager, services);
  const auto& node = discovery.subsystems().at(3).nodes.at(2);
  EXPECT_EQ(discovery.subsystems().at(3).identification->name, "rover");
  const auto driver_services = Discovery::services_of(node, node.components.at({33, 1}));
  ASSERT_EQ(driver_services.size(), 1u);
  EXPECT_EQ(driver_services[0].inputs[0].command_code, 0x0405);
}

// A node's subsystem list names the subsystems it knows (and relays to): each
// is asked in turn, as if heard; the OCU's own node is not.
TEST_F(DiscoveryModel, EverySubsystemInASubsystemListIsAsked) {
  using K = DiscoveryQuery::Kind;
  const jaus::Address manager{3, 2, 1, 1};
  discovery.heard(manager);
  const jaus::Address other_communicator{5, 1, 35, 1};
  const auto next = reply(manager, jaus::msg::ReportSubsystemList{{{manager, other_communicator, {254, 1, 1, 1}}}});
  EXPECT_TRUE(asks(next, jaus::Address{5, 1, 1, 1}, K::identification, 2));
  EXPECT_TRUE(asks(next, jaus::Address{5, 1, 1, 1}, K::configuration, 2));
  EXPECT_TRUE(asks(next, jaus::Address{5, 1, 1, 1}, K::subsystem_list, 0));
  EXPECT_TRUE(asks(next, other_communicator, K::identification, 4));
  for (const auto& q : next) EXPECT_NE(q.to.subsystem, 254) << q.to.to_string();
  for (const auto& q : next) EXPECT_NE(q.to.subsystem, 3) << "asked again: " << q.to.to_string();
  ASSERT_EQ(discovery.subsystems().size(), 2u);
  EXPECT_TRUE(discovery.subsystems().contains(5));
}

TEST_F(DiscoveryModel, ASubsystemClaimingTooManyComponentsIsNotBelieved) {
  jaus::msg::ReportConfiguration configuration;
  for (std::uint8_t node = 1; node <= 10; ++node) {
    jaus::msg::NodeEntry entry{node, {}};
    for (std::uint8_t c = 1; c <= 200; ++c) entry.components.push_back({c, 1});
    configuration.nodes.push_back(entry);
  }
  const auto queries = reply(jaus::Address{3, 1, 1, 1}, configuration);
  EXPECT_EQ(discovery.component_count(), Discovery::kMaxComponentsPerSubsystem);
  EXPECT_EQ(discovery.components_left_out(), 2000 - Discovery::kMaxComponentsPerSubsystem);
  EXPECT_LE(queries.size(), 2 * Discovery::kMaxComponentsPerSubsystem + 4 * 10 + 2);
}

// bench_scale found the bound counted over the whole system: 170 vehicles of
// six components filled it and the rest were silently left out.
TEST_F(DiscoveryModel, TwoHundredFiftyVehiclesOfSixComponentsAreAllListed) {
  for (std::uint8_t subsystem = 1; subsystem <= 250; ++subsystem) {
    jaus::msg::ReportConfiguration configuration;
    for (std::uint8_t node = 1; node <= 2; ++node) {
      jaus::msg::NodeEntry entry{node, {}};
      for (std::uint8_t c : {std::uint8_t{1}, std::uint8_t{33}, std::uint8_t{38}}) entry.components.push_back({c, 1});
      configuration.nodes.push_back(entry);
    }
    reply(jaus::Address{subsystem, 1, 1, 1}, configuration);
  }
  EXPECT_EQ(discovery.component_count(), 250u * 6u);
  EXPECT_EQ(discovery.components_left_out(), 0u);
  EXPECT_EQ(discovery.subsystems().size(), 250u);
}

TEST_F(DiscoveryModel, MalformedRepliesAreIgnored) {
  jaus::Header h;
  h.command_code = jaus::msg::ReportConfiguration::code;
  h.source = {3, 2, 1, 1};
  const std::vector<std::uint8_t> garbage{0x05, 0x01};
  discovery.received(h, garbage, jaus::wire::Dialect::ra);
  EXPECT_EQ(discovery.component_count(), 1u);  // only the sender, as heard
}

}  // namespace
}  // namespace jausctl::ocu
